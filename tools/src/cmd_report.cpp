// `rockfit report SUMMARY.h5 --fits FITS.h5 [--validation V.h5] [--fragility F.h5]… [--response R.h5]… -o
// report.html`: one self-contained HTML page of a campaign (report_builder.hpp, which does the work).
#include <iostream>
#include <map>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/report_builder.hpp"

namespace rockfit::tools {
namespace {

struct ReportCommand {
  std::string summary, fits, validation, output, title = "Campaign report";
  std::vector<std::string> fragility, responses;
  bool no_figures = false;
  bool json = false;
};

std::string Quoted(const std::string& s) {
  return s.find_first_of(" \t'\"$\\") == std::string::npos ? s : "'" + s + "'";
}

// The command that makes this report, for its provenance section.
std::string CommandLine(const ReportCommand& cmd) {
  std::string line = "rockfit report " + Quoted(cmd.summary);
  if (!cmd.fits.empty()) line += " --fits " + Quoted(cmd.fits);
  if (!cmd.validation.empty()) line += " --validation " + Quoted(cmd.validation);
  for (const std::string& f : cmd.fragility) line += " --fragility " + Quoted(f);
  for (const std::string& r : cmd.responses) line += " --response " + Quoted(r);
  if (cmd.title != "Campaign report") line += " --title " + Quoted(cmd.title);
  if (cmd.no_figures) line += " --no-figures";
  return line + " -o " + Quoted(cmd.output);
}

int RunReport(const ReportCommand& cmd) {
  ReportOptions options;
  options.inputs.summary = cmd.summary;
  options.inputs.fits = cmd.fits;
  options.inputs.validation = cmd.validation;
  options.inputs.fragility.assign(cmd.fragility.begin(), cmd.fragility.end());
  options.inputs.responses.assign(cmd.responses.begin(), cmd.responses.end());
  options.title = cmd.title;
  options.rockfit_version = ROCKFIT_VERSION;
  options.command_line = CommandLine(cmd);
  options.figures = !cmd.no_figures;
  const ReportSummary s = WriteReport(options, cmd.output);
  if (cmd.json) {
    nlohmann::json gaps = nlohmann::json::array();
    for (const Gap& g : s.gaps) gaps.push_back({{"where", g.where}, {"what", g.what}});
    PrintJson({{"output", cmd.output},
               {"trials", s.trials},
               {"trials_fitted", s.trials_fitted},
               {"figures", s.figures},
               {"figures_missing", s.figures_missing},
               {"gaps", gaps},
               {"bytes", s.bytes}});
    return kExitOk;
  }
  for (const Gap& g : s.gaps) std::cerr << "rockfit: note: " << g.where << " " << g.what << "\n";
  // "name: reason" grouped by reason, so that a missing gnuplot is said once.
  std::map<std::string, std::vector<std::string>> missing;
  for (const std::string& f : s.figures_missing) {
    const std::size_t colon = f.find(": ");
    missing[colon == std::string::npos ? f : f.substr(colon + 2)].push_back(f.substr(0, colon));
  }
  for (const auto& [reason, names] : missing) {
    std::cerr << fmt::format("rockfit: {} not drawn ({}{}): {}\n", names.size() == 1 ? "1 figure" : fmt::format("{} figures", names.size()),
                             names.front(), names.size() > 1 ? ", …" : "", reason);
  }
  std::cout << fmt::format("written  {} ({} trials, {} fitted; {} figures, {} not drawn)\n", cmd.output, s.trials,
                           s.trials_fitted, s.figures, s.figures_missing.size());
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<ReportCommand>();
  CLI::App* app = root.add_subcommand(
      "report",
      "One self-contained HTML page of a campaign to share: overview (OPMF, AVRF, parameter ranges, warnings), one "
      "section per trial (angles, measured against simulated ω, parameters with intervals, model error, mounting), "
      "the earthquake side and the provenance. Opens offline in any browser and prints on A4.");
  app->add_option("SUMMARY", cmd->summary, "HDF5 file of `rockfit summary MANIFEST -o FILE`")->required();
  app->add_option("--fits", cmd->fits, "HDF5 file of `rockfit batch MANIFEST -o FILE` (fitted parameters)");
  app->add_option("--validation", cmd->validation, "HDF5 file of `rockfit validate MANIFEST -o FILE`");
  app->add_option("--fragility", cmd->fragility, "HDF5 file of `rockfit fragility -o FILE` (repeatable)");
  app->add_option("--response", cmd->responses, "HDF5 file of `rockfit respond --format hdf5 -o FILE` (repeatable)");
  app->add_option("-o,--output", cmd->output, "HTML file to write")->required();
  app->add_option("--title", cmd->title, "Title of the page")->capture_default_str();
  app->add_flag("--no-figures", cmd->no_figures, "Tables only (no gnuplot runs)");
  app->add_flag("--json", cmd->json, "Print one JSON object: output, trials, trials_fitted, figures, figures_missing, "
                                     "gaps, bytes");
  app->footer("Figures need gnuplot (apt-get install gnuplot-nox); without it the page still has every table and "
              "names the figures it lacks. Inputs that lack something (a trial without a fit, a fragility study of "
              "another block) are named on the page and on stderr. Exit codes: 0 written; 1 bad arguments; 2 "
              "unreadable summary file; 4 cannot write the page.");
  app->callback([cmd] { SetExitCode(RunReport(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
