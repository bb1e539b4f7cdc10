// `rockfit validate MANIFEST`: the predictive check of a campaign (fitting/predictive_check.hpp): every trial left
// out of its block and position in turn, fitted only in its release (t0, α and, where --release-roll-mode fits it,
// the release roll) with the others' pooled λ, λ_lat, λ_lon, and its error (28) compared with its own fit's.
#include <iostream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/gnuplot.hpp"
#include "plot_validation.hpp"
#include "rockfit/app/validation_run.hpp"
#include "rockfit/fitting/validation_store.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_transaction.hpp"

namespace rockfit::tools {
namespace {

struct ValidateCommand {
  ValidateArgs args;
  std::string output;
  std::string plot;
  bool json = false;
};

int RunValidate(const ValidateCommand& cmd) {
  if (!cmd.plot.empty()) ImageFormatFor(cmd.plot);
  const fitting::ValidationSummary s = RunValidation(cmd.args);
  if (!cmd.output.empty()) {
    io::hdf5::Transaction tx(cmd.output, {"/validation"});
    io::WriteFileAttributes(tx.Root(), ROCKFIT_VERSION);
    fitting::WriteValidationGroup(tx.Root(), s);
    tx.Commit();
  }
  if (!cmd.plot.empty()) RenderValidationPlot(s, cmd.plot, 1000, 600);
  if (cmd.json) {
    nlohmann::json out = nlohmann::json::parse(fitting::ValidationJson(s));
    out["manifest"] = cmd.args.manifest;
    out["fits"] = cmd.args.fits.empty() ? nlohmann::json() : nlohmann::json(cmd.args.fits);
    PrintJson(out);
  } else {
    std::cout << ValidationTable(s);
    std::cout << fmt::format("effort   {} simulations for the predictions in {:.1f} s\n", s.simulations, s.wall_time_s);
    if (!cmd.output.empty()) std::cout << "written  " << cmd.output << "\n";
  }
  std::size_t failed = 0;
  for (const fitting::TrialPrediction& t : s.trials) {
    if (!t.predicted && t.n_others > 0) ++failed;
  }
  if (failed > 0) {
    std::cerr << fmt::format("rockfit: {} trial(s) could not be predicted (see the table); check their recordings "
                             "with rockfit fit MANIFEST --trial ID\n", failed);
    return kExitNumerical;
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<ValidateCommand>();
  CLI::App* app = root.add_subcommand(
      "validate",
      "Predictive check of a campaign: leave each trial of a block and position out, fit only its t0 and α (and its "
      "release roll where --release-roll-mode fits it) with the others' pooled λ, λ_lat, λ_lon, and compare its error (28) with its own fit's (ε_pred/ε_own)");
  app->add_option("MANIFEST", cmd->args.manifest, "Campaign manifest (.toml)")->required();
  app->add_option("--fits", cmd->args.fits,
                  "HDF5 file of `rockfit batch` holding every trial's own fit (default: fit them now)");
  app->add_option("-o,--output", cmd->output, "HDF5 file to write /validation into (other groups are kept)");
  app->add_option("--plot", cmd->plot, "Picture of the ratios (.png or .svg)");
  app->add_option("-j,--jobs", cmd->args.jobs, "Trials at once (0: all cores)")->capture_default_str();
  app->add_option("--ratio-warning", cmd->args.ratio_warning,
                  "ε_pred/ε_own above this is marked as not transferring (!)")
      ->capture_default_str();
  app->add_flag("--json", cmd->json, "Print one JSON object");
  AddFitOptions(*app, cmd->args.fit);
  app->footer("Exit codes: 0 done; 1 bad option; 2 unreadable manifest, recording or fits file; 3 a trial could not "
              "be predicted; 4 cannot write the output.");
  app->callback([cmd] { SetExitCode(RunValidate(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
