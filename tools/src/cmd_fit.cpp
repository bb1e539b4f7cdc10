// `rockfit fit PATH` / `rockfit fit MANIFEST --trial ID`: fit t0, α, λ, λ_lat, λ_lon of one trial (paper Sect. 5,
// docs/design.md §7) from no starting point, or `--evaluate` the error (28) at given parameters.
#include <iostream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/fit_setup.hpp"
#include "rockfit/app/mounting_report.hpp"
#include "plot_fit.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/fitting/recorded_fit.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_transaction.hpp"

namespace rockfit::tools {
namespace {

struct FitCommand {
  RecordingArgs input;
  BlockArgs block;
  FitArgs fit;
  std::string output;
  std::string plot;
  bool json = false;
  bool evaluate = false;
  std::optional<double> t0_s, alpha_rad, lambda, lambda_lat, lambda_lon, release_roll_rad;
};

core::Block BlockFor(const FitCommand& cmd, const TrialInput& input) {
  std::optional<core::Block> block = MakeOptionalBlock(cmd.block);
  if (!block && input.manifest_block) block = input.manifest_block->ToBlock();
  if (!block) {
    throw InvalidArgument("the fit needs the block geometry: give --b1 --b2 --h with --density or --mass, or "
                          "--manifest FILE --block ID (or PATH a manifest with --trial ID)");
  }
  return *block;
}

int RunEvaluate(const FitCommand& cmd, const TrialInput& input, const PreparedFit& prepared) {
  fitting::ParameterSet values = prepared.start;
  std::vector<std::pair<fitting::ParameterId, std::optional<double>>> given = {
      {fitting::ParameterId::kT0, cmd.t0_s},           {fitting::ParameterId::kAlpha, cmd.alpha_rad},
      {fitting::ParameterId::kLambda, cmd.lambda},      {fitting::ParameterId::kLambdaLat, cmd.lambda_lat},
      {fitting::ParameterId::kLambdaLon, cmd.lambda_lon}};
  // The release roll: given, or the data estimate where the fit would fit it (release_roll_choice.hpp); a planar
  // fall evaluates at β = 0 and does not show the row.
  if (cmd.release_roll_rad) {
    const fitting::Parameter& beta = values[fitting::ParameterId::kReleaseRoll];
    if (!(beta.lower <= *cmd.release_roll_rad && *cmd.release_roll_rad <= beta.upper)) {
      throw InvalidArgument(fmt::format("--release-roll {:g}: the roll must lie within its bounds [{:g}, {:g}] rad",
                                        *cmd.release_roll_rad, beta.lower, beta.upper));
    }
  }
  if (cmd.release_roll_rad || !values[fitting::ParameterId::kReleaseRoll].fixed) {
    given.push_back({fitting::ParameterId::kReleaseRoll, cmd.release_roll_rad});
  }
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [id, v] : given) {
    if (v) values[id].value = *v;
    params[fitting::Name(id)] = {{"value", values.value(id)}, {"given", v.has_value()}};
  }
  const fitting::Evaluation e = prepared.objective.Evaluate(values);
  if (cmd.json) {
    PrintJson({{"trial", input.trial_id},
               {"epsilon", e.feasible ? nlohmann::json(e.epsilon_rad_s) : nlohmann::json()},
               {"feasible", e.feasible},
               {"failure", e.failure_category()},
               {"t_end", prepared.objective.t_end_s()},
               {"parameters", params}});
  } else {
    std::cout << fmt::format("trial        {}\n", input.trial_id);
    for (const auto& [id, v] : given) {
      std::cout << fmt::format("{:<12} {:.6g} {}{}\n", fitting::Name(id), values.value(id), fitting::Unit(id),
                               v ? "" : "   (data estimate)");
    }
    if (e.feasible) {
      std::cout << fmt::format("ε (28)       {:.6g} rad/s over [t0, {:.4f} s]\n", e.epsilon_rad_s,
                               prepared.objective.t_end_s());
    } else {
      std::cout << "ε (28)       — (the simulation failed: " << e.failure_category() << ")\n";
    }
  }
  if (!e.feasible) {
    std::cerr << "rockfit: the model cannot run at these parameters (" << e.failure_category()
              << "); try values inside the bounds shown by `rockfit fit --help`\n";
    return kExitNumerical;
  }
  return kExitOk;
}

int RunFit(const FitCommand& cmd) {
  MakeParameterSet(cmd.fit);  // option errors (exit 1) before reading the recording
  const TrialInput input = LoadTrialInput(cmd.input);
  PrintMountingWarning(input.recording);
  const core::Block block = BlockFor(cmd, input);
  const PreparedFit prepared = PrepareFit(input.recording, block, cmd.fit);
  if (cmd.evaluate) return RunEvaluate(cmd, input, prepared);

  const fitting::FitSummary summary =
      fitting::FitRecordedTrial(prepared.objective, prepared.start, prepared.options, prepared.release_roll_choice,
                                &input.recording);
  const std::string trial = TrialNameFrom(input.trial_id);
  if (!cmd.output.empty()) {
    io::hdf5::Transaction tx(cmd.output, {"/fits/" + trial});
    io::WriteFileAttributes(tx.Root(), ROCKFIT_VERSION);
    fitting::WriteFitGroup(tx.Root(), trial, input.labels, prepared.objective, prepared.settings, summary);
    io::WriteMountingHdf5(tx.Root().OpenGroup("fits/" + trial), input.recording);
    tx.Commit();
  }
  if (!cmd.plot.empty()) {
    FitPlotData data;
    data.trial = trial;
    data.epsilon_rad_s = summary.epsilon_rad_s;
    fitting::ErrorNodes nodes;
    fitting::ModelOutput output;
    prepared.objective.WithWindowEnd(summary.t_end_s).EvaluateDetailed(summary.parameters, &nodes, &output);
    data.t_s = nodes.t_s;
    data.w_measured_B = nodes.w_m_B;
    if (output.ok()) data.w_simulated_B = output.w_B;
    for (const fitting::ModelEvent& e : output.events) {
      data.impact_t_s.push_back(summary.parameters.value(fitting::ParameterId::kT0) + e.t_s);
      data.impact_kind.push_back(e.kind);
    }
    std::vector<std::string> names, units;
    std::vector<double> values, lo, hi;
    std::vector<bool> fixed;
    for (fitting::ParameterId id : summary.parameters.ReportedIds()) {
      const std::size_t k = static_cast<std::size_t>(id);
      names.push_back(fitting::Name(id));
      units.push_back(fitting::Unit(id));
      values.push_back(summary.parameters.value(id));
      fixed.push_back(summary.parameters[id].fixed);
      lo.push_back(summary.uncertainty.interval_95[k][0]);
      hi.push_back(summary.uncertainty.interval_95[k][1]);
    }
    if (summary.uncertainty.method != fitting::IntervalMethod::kNone) {
      data.parameter_lines = ParameterLines(names, units, values, fixed, lo, hi);
    }
    RenderFitPlot(data, cmd.plot, 1200, 900);
  }
  if (cmd.json) {
    nlohmann::json out = FitResultJson(trial, summary);
    out["mounting"] = MountingJson(input.recording);
    PrintJson(out);
  } else {
    std::cout << "mounting     " << MountingText(input.recording) << "\n";
    for (const std::string& note : prepared.notes) std::cout << "estimate     " << note << "\n";
    std::cout << FitResultTable(trial, summary);
  }
  if (!summary.feasible) {
    std::cerr << "rockfit: no parameter set in the bounds lets the simulation run (" << summary.termination
              << "); widen the bounds (--lower/--upper, --bounds empirical) or check the block geometry\n";
    return kExitNumerical;
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<FitCommand>();
  CLI::App* app = root.add_subcommand(
      "fit",
      "Fit the release time t0, tilt α and impact parameters λ, λ_lat, λ_lon of one trial by minimising the error "
      "(28) between measured and simulated ω, from no starting point (data estimate, global stage, local polish)");
  AddRecordingOptions(*app, cmd->input);
  AddBlockOptions(*app, cmd->block);
  AddFitOptions(*app, cmd->fit);
  app->add_option("-o,--output", cmd->output, "HDF5 file to write /fits/<trial> into (other groups are kept)");
  app->add_option("--plot", cmd->plot, "Picture of the fit (.png or .svg): measured dots, simulated lines, impacts");
  app->add_flag("--json", cmd->json, "Print one JSON object");
  app->add_flag("--evaluate", cmd->evaluate,
                "Print ε (28) at --t0 --alpha --lambda --lambda-lat --lambda-lon --release-roll (others: data estimate); no fit");
  app->add_option("--t0", cmd->t0_s, "With --evaluate: release time [s]");
  app->add_option("--alpha", cmd->alpha_rad, "With --evaluate: release tilt [rad]");
  app->add_option("--lambda", cmd->lambda, "With --evaluate: λ of edge impacts (19)");
  app->add_option("--lambda-lat", cmd->lambda_lat, "With --evaluate: λ_lat of facet impacts (21)");
  app->add_option("--lambda-lon", cmd->lambda_lon, "With --evaluate: λ_lon of facet impacts (21)");
  app->add_option("--release-roll", cmd->release_roll_rad,
                  "With --evaluate: the release roll β [rad] (default: the data estimate where the fall shows a roll, "
                  "else 0)");
  app->callback([cmd] { SetExitCode(RunFit(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
