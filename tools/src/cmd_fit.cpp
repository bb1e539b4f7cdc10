// `rockfit fit`: fit t0, α, λ, λ_lat, λ_lon of one trial without a starting point (DESIGN §7), or evaluate the
// error (28) of given parameters (--evaluate).
#include <cmath>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "fit_cli.hpp"
#include "gnuplot.hpp"
#include "plot_fit.hpp"
#include "recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_settings.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/fitting/trial_fit.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_transaction.hpp"

namespace rockfit::tools {
namespace {

struct FitCommand {
  RecordingArgs input;
  BlockArgs block;
  FitArgs fit;
  std::vector<std::string> evaluate;
  std::string output;
  std::string plot;
  bool json = false;
};

fitting::MeasuredSignal SignalOf(const io::Recording& r) {
  fitting::MeasuredSignal s;
  s.t_s = r.t_s;
  s.w_B = r.w_B;
  return s;
}

core::Block BlockFor(const FitCommand& cmd, const TrialInput& input) {
  if (HasBlockOptions(cmd.block)) return MakeBlock(cmd.block);
  if (input.manifest_block) return input.manifest_block->ToBlock();
  throw InvalidArgument("the block is needed: give --b1 --b2 --h with --density or --mass, --manifest FILE --block ID, "
                        "or fit a trial of a manifest (PATH.toml --trial ID)");
}

nlohmann::json EstimateJson(const fitting::DataEstimate& e) {
  return {{"first_impact_s", e.first_impact_s},
          {"t_end_impact_s", e.t_end_impact_s},
          {"rest_bias_rad_s", e.bias_estimated ? ToJson(e.rest_bias_rad_s) : nlohmann::json()},
          {"w_minus_rad_s", e.w_minus_rad_s},
          {"alpha_from_energy_rad", e.alpha_from_energy_rad},
          {"notes", e.notes}};
}

int RunEvaluate(const FitCommand& cmd, const TrialInput& input, const core::Block& block) {
  fitting::ParameterSet values = MakeParameterSet(cmd.fit);
  const auto given = ParseAssignments(cmd.evaluate, "--evaluate");
  for (const auto& [id, value] : given) values[id].value = value;
  fitting::TrialFitOptions options = MakeTrialFitOptions(cmd.fit);
  // Parameters not given take the estimate from the data.
  fitting::ParameterSet estimate_request = values;
  for (fitting::ParameterId id : fitting::kAllParameters) {
    const bool was_given = std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.first == id; });
    estimate_request[id].fixed = was_given || values[id].fixed;
  }
  const fitting::TrialEvaluation e = fitting::EvaluateTrial(block, SignalOf(input.recording), estimate_request, options);
  fitting::ParameterSet used = e.estimate.parameters;
  for (const auto& [id, value] : given) used[id].value = value;
  // The evaluation used `estimate_request` values for given/fixed ones and the estimate for the others.
  if (cmd.json) {
    nlohmann::json j;
    j["trial"] = input.trial_id;
    for (fitting::ParameterId id : fitting::kAllParameters) {
      const bool was_given = std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.first == id; });
      j["parameters"][fitting::Name(id)] = {{"value", used.value(id)}, {"given", was_given}, {"unit", fitting::Unit(id)}};
    }
    j["epsilon"] = e.epsilon_rad_s;
    j["feasible"] = e.feasible;
    j["failure"] = e.failure;
    j["t_end"] = e.t_end_s;
    j["estimate"] = EstimateJson(e.estimate);
    PrintJson(j);
  } else {
    std::cout << fmt::format("trial {}: ε (28) = {:.6g} rad/s over [t0, t_end = {:.4f} s]{}\n", input.trial_id,
                             e.epsilon_rad_s, e.t_end_s, e.feasible ? "" : " (infeasible: " + e.failure + ")");
    for (fitting::ParameterId id : fitting::kAllParameters) {
      const bool was_given = std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.first == id; });
      std::cout << fmt::format("  {:<11} {:12.6g} {:<6} {}\n", fitting::Name(id), used.value(id), fitting::Unit(id),
                               was_given ? "given" : (values[id].fixed ? "fixed" : "estimated from the data"));
    }
  }
  if (!cmd.plot.empty() && !e.trace.ok) {
    std::cerr << "rockfit: no picture: the model fails at these parameters (" << e.trace.failure << ")\n";
  }
  if (!cmd.plot.empty() && e.trace.ok) {
    fitting::TrialFit as_fit;
    as_fit.signal = e.signal;
    as_fit.trace = e.trace;
    as_fit.summary.parameters = used;
    as_fit.summary.epsilon_rad_s = e.epsilon_rad_s;
    RenderFitFigure(FitFigureFrom(as_fit, input.trial_id), cmd.plot, 1200, 900);
  }
  if (!e.feasible) {
    std::cerr << "rockfit: the model fails at these parameters (" << e.failure << "); ε is the penalty value\n";
    return kExitNumerical;
  }
  return kExitOk;
}

int RunFit(const FitCommand& cmd) {
  if (!cmd.plot.empty()) ImageFormatFor(cmd.plot);  // reject a wrong extension before the work
  const TrialInput input = LoadTrialInput(cmd.input);
  const core::Block block = BlockFor(cmd, input);
  if (!cmd.evaluate.empty()) return RunEvaluate(cmd, input, block);

  const fitting::ParameterSet parameters = MakeParameterSet(cmd.fit);
  const fitting::TrialFitOptions options = MakeTrialFitOptions(cmd.fit);
  const fitting::TrialFit fit = fitting::FitTrial(block, SignalOf(input.recording), parameters, options);
  const fitting::FitSummary& s = fit.summary;

  if (!cmd.output.empty()) {
    const nlohmann::json input_json = {{"path", cmd.input.path}, {"trial", input.trial_id},
                                       {"block", {{"b1_m", block.b1()}, {"b2_m", block.b2()}, {"h_m", block.h()},
                                                  {"mass_kg", block.mass()}}}};
    const std::string settings = fitting::FitSettingsJson(parameters, options, input_json.dump());
    io::hdf5::Transaction tx(cmd.output, {"/fits/" + input.trial_id, "/fit_summary"});
    io::WriteFileAttributes(tx.Root(), ROCKFIT_VERSION);
    fitting::FitLabels labels{input.labels.block_id, input.labels.position, block.b1(), block.b2(), block.h()};
    fitting::WriteFitHdf5(tx.Root(), input.trial_id, labels, fit, settings, fitting::SettingsHash(settings));
    fitting::WriteFitTablesHdf5(tx.Root());
    tx.Commit();
  }
  if (!cmd.plot.empty()) {
    if (fit.trace.ok) {
      RenderFitFigure(FitFigureFrom(fit, input.trial_id), cmd.plot, 1200, 900);
    } else {
      std::cerr << "rockfit: no picture: the model fails at the fitted parameters (" << fit.trace.failure << ")\n";
    }
  }

  if (cmd.json) {
    nlohmann::json j = nlohmann::json::parse(s.ToJson(input.trial_id));
    j["estimate"] = EstimateJson(fit.estimate);
    j["block"] = {{"b1_m", block.b1()}, {"b2_m", block.b2()}, {"h_m", block.h()}, {"mass_kg", block.mass()}};
    if (!cmd.output.empty()) j["output"] = cmd.output;
    if (!cmd.plot.empty()) j["plot"] = cmd.plot;
    PrintJson(j);
  } else {
    std::cout << "trial " << input.trial_id << " (" << s.model_description << ")\n";
    for (const std::string& note : fit.estimate.notes) std::cout << "estimate    " << note << "\n";
    std::cout << s.FullReport();
    if (!cmd.output.empty()) std::cout << "written " << cmd.output << " (/fits/" << input.trial_id << ")\n";
    if (!cmd.plot.empty() && fit.trace.ok) std::cout << "written " << cmd.plot << "\n";
  }
  if (!s.feasible) {
    std::cerr << "rockfit: no feasible parameters for trial " << input.trial_id
              << ": the model fails everywhere it was tried; check the block size, the mounting and the bounds\n";
    return kExitNumerical;
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<FitCommand>();
  CLI::App* app = root.add_subcommand(
      "fit", "Fit release time, tilt and impact parameters (t0, α, λ, λ_lat, λ_lon) of one trial by the error (28), "
             "without a starting point");
  AddRecordingOptions(*app, cmd->input);
  AddBlockOptions(*app, cmd->block);
  AddFitOptions(*app, cmd->fit, true);
  app->add_option("--evaluate", cmd->evaluate,
                  "Print ε (28) of these parameters instead of fitting, NAME=VALUE,... (the others from the data)")
      ->group("Fit");
  app->add_option("-o,--output", cmd->output, "HDF5 file to store the fit in (/fits/<trial>; other content is kept)")
      ->group("Output");
  app->add_option("--plot", cmd->plot, "Draw measured and simulated ω (Fig. 14) to FILE.png or FILE.svg")->group("Output");
  app->add_flag("--json", cmd->json,
                "Print one JSON object: trial, parameters (value, lower, upper, fixed, std_error, …), epsilon, "
                "epsilon_initial, t_end, simulations, wall_s, termination, warnings, …")
      ->group("Output");
  app->callback([cmd] { SetExitCode(RunFit(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
