// `rockfit batch MANIFEST -o fits.h5`: fit every trial of a campaign in parallel into one HDF5 file (docs/design.md §7,
// §8). A front end to fitting::FitCampaign, which commits each finished trial through its own atomic transaction
// (so killing the batch at any moment loses at most the trials still running) and, with `--resume`, skips the
// trials the file already holds with the same settings. This file parses, prepares each trial's problem and prints.
#include <algorithm>
#include <cmath>
#include <exception>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/fit_setup.hpp"
#include "rockfit/app/progress_bar.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_campaign.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/mounting_estimate.hpp"

namespace rockfit::tools {
namespace {

struct BatchCommand {
  std::string manifest;
  std::string output;
  FitArgs fit;
  int jobs = 0;
  bool resume = false;
  bool json = false;
};

// What the command reports of a trial besides the library's outcome: the mounting of its recording.
struct TrialMounting {
  std::string applied;
  double disagreement_deg = std::nan("");
  std::string warning;
};

// The per-group table of `batch`: pooled estimate [95 % interval], spread, consistency per parameter.
using GroupRange = fitting::GroupSummary;

std::string GroupRangeTable(const std::vector<GroupRange>& ranges) {
  std::string out = fmt::format("{:<10} {:<4} {:>2}  {:<11} {:>34} {:>9} {:>7} {:>7}\n", "block", "pos", "n",
                                "parameter", "pooled [95 % interval] (pooled/n)", "spread", "χ²/dof", "p");
  for (const GroupRange& r : ranges) {
    for (const char* name : fitting::kSummaryParameters) {
      // t0 is a time in each recording, not a property of the block: no range (the HDF5 table has it anyway).
      if (std::string(name) == "tau_edge" || std::string(name) == "t0") continue;
      const fitting::PooledEstimate& e = r.pooled.at(name);
      const std::string pooled = e.n_pooled > 0 ? fmt::format("{:.4g} [{:.4g}, {:.4g}] ({}/{})", e.pooled,
                                                              e.interval_95[0], e.interval_95[1], e.n_pooled, e.n_trials)
                                                : fmt::format("— (0/{})", e.n_trials);
      out += fmt::format("{:<10} {:<4} {:>2}  {:<11} {:>34} {:>9.3g} {:>7.3g} {:>7.3g}\n", r.block, r.position, r.n,
                         name, pooled, r.std_dev.at(name), e.chi2_per_dof, e.consistency_p);
    }
  }
  return out;
}

// The exit code of a trial that is not ok: the kind of its error (infeasible: numerical).
int ExitCodeOf(const fitting::TrialOutcome& o) {
  if (!o.error) return kExitNumerical;
  try {
    std::rethrow_exception(o.error);
  } catch (const InvalidArgument&) {
    return kExitUsage;
  } catch (const BadInput&) {
    return kExitBadInput;
  } catch (const OutputError&) {
    return kExitCannotWrite;
  } catch (...) {
    return kExitNumerical;
  }
}

// The progress line of a finished trial.
std::string ProgressText(const fitting::TrialOutcome& o) {
  if (o.status == fitting::TrialStatus::kSkipped) return o.trial + ": already fitted";
  if (o.ok()) {
    const fitting::ModelErrorStatement& m = o.model_error;
    return o.trial + ": " +
           fmt::format("ε = {:.4g} rad/s in {:.1f} s{}", o.epsilon_rad_s, o.fit_wall_s,
                       m.available ? fmt::format(", {:.2f} × noise floor{}", m.ratio, m.dominates ? " (model error dominates)" : "")
                                   : "");
  }
  return o.trial + ": FAILED: " + o.message;
}

nlohmann::json TrialsJson(const fitting::CampaignSummary& s, const std::vector<TrialMounting>& mountings) {
  nlohmann::json trials = nlohmann::json::array();
  for (std::size_t i = 0; i < s.trials.size(); ++i) {
    const fitting::TrialOutcome& o = s.trials[i];
    trials.push_back({{"trial", o.trial},
                      {"ok", o.ok()},
                      {"skipped", o.status == fitting::TrialStatus::kSkipped},
                      {"epsilon", std::isfinite(o.epsilon_rad_s) ? nlohmann::json(o.epsilon_rad_s) : nlohmann::json()},
                      {"wall_s", o.fit_wall_s},
                      {"model_error", nlohmann::json::parse(fitting::ModelErrorJson(o.model_error))},
                      {"mounting", mountings[i].applied},
                      {"mounting_disagreement_deg", OrNull(mountings[i].disagreement_deg)},
                      {"message", o.message}});
  }
  return trials;
}

nlohmann::json GroupsJson(const std::vector<GroupRange>& ranges) {
  nlohmann::json groups = nlohmann::json::array();
  for (const GroupRange& r : ranges) {
    nlohmann::json params = nlohmann::json::object();
    for (const char* name : fitting::kSummaryParameters) {
      const fitting::PooledEstimate& e = r.pooled.at(name);
      params[name] = {{"mean", OrNull(r.mean.at(name))},
                      {"spread", OrNull(r.std_dev.at(name))},
                      {"pooled", e.n_pooled > 0 ? OrNull(e.pooled) : nlohmann::json()},
                      {"pooled_interval_95", {OrNull(e.interval_95[0]), OrNull(e.interval_95[1])}},
                      {"n_pooled", e.n_pooled},
                      {"chi2_per_dof", OrNull(e.chi2_per_dof)},
                      {"consistency_p", OrNull(e.consistency_p)}};
    }
    groups.push_back({{"block", r.block}, {"position", r.position}, {"n", r.n}, {"parameters", params}});
  }
  return groups;
}

// Mounting warnings, then the failed trials with what to do, on stderr.
void ReportProblems(const fitting::CampaignSummary& s, const std::vector<TrialMounting>& mountings) {
  for (std::size_t i = 0; i < s.trials.size(); ++i) {
    if (!mountings[i].warning.empty()) {
      std::cerr << "rockfit: warning: " << s.trials[i].trial << ": " << mountings[i].warning << "\n";
    }
  }
  if (s.failed == 0) return;
  std::cerr << fmt::format("rockfit: {} trial(s) failed:\n", s.failed);
  for (const fitting::TrialOutcome& o : s.trials) {
    if (!o.ok()) std::cerr << "  " << o.trial << ": " << o.message << "\n";
  }
  std::cerr << "Fix or remove them and re-run with --resume (finished trials are kept).\n";
}

int RunBatch(const BatchCommand& cmd) {
  const io::Manifest manifest = io::ReadManifest(cmd.manifest);
  if (manifest.trials.empty()) throw BadInput(fmt::format("{}: the manifest lists no trials", cmd.manifest));
  if (cmd.jobs < 0) throw InvalidArgument("-j must be ≥ 0 (0: all cores)");
  MakeParameterSet(cmd.fit);  // option errors before any work
  fitting::ParseFitMethod(cmd.fit.method);

  const std::size_t n = manifest.trials.size();
  FitArgs fit_args = cmd.fit;
  fit_args.threads = 1;  // parallel over trials, not inside one fit
  std::vector<TrialMounting> mountings(n);
  std::vector<fitting::CampaignTrial> trials;
  for (std::size_t i = 0; i < n; ++i) {
    TrialMounting* mounting = &mountings[i];
    trials.push_back(MakeCampaignTrial(manifest, manifest.trials[i], fit_args, [mounting](const io::Recording& r) {
      mounting->applied = r.mounting;
      mounting->disagreement_deg = io::MountingDisagreementDeg(r.mounting_check);
      mounting->warning = r.mounting_check.warning;
    }));
  }
  fitting::CampaignOptions options;
  options.num_threads = cmd.jobs;
  options.resume = cmd.resume;
  options.rockfit_version = ROCKFIT_VERSION;
  ProgressBar progress("batch", n, 0, StderrIsTerminal());
  std::size_t done = 0;
  const fitting::CampaignSummary s =
      fitting::FitCampaign(trials, cmd.output, options,
                           [&](const fitting::TrialOutcome& o, double) { progress.Report(++done, ProgressText(o)); });

  if (cmd.json) {
    PrintJson({{"output", cmd.output}, {"trials", TrialsJson(s, mountings)}, {"fitted", n - s.failed - s.skipped},
               {"skipped", s.skipped}, {"failed", s.failed}, {"groups", GroupsJson(s.groups)}});
  } else {
    std::cout << fmt::format("{} trials: {} fitted, {} skipped (already in {} with the same settings), {} failed\n", n,
                             n - s.failed - s.skipped, s.skipped, cmd.output, s.failed);
    if (!s.groups.empty()) std::cout << GroupRangeTable(s.groups);
  }
  ReportProblems(s, mountings);
  int exit_code = kExitOk;
  for (const fitting::TrialOutcome& o : s.trials) {
    if (!o.ok()) exit_code = std::max(exit_code, ExitCodeOf(o));
  }
  return exit_code;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<BatchCommand>();
  CLI::App* app = root.add_subcommand(
      "batch", "Fit every trial of a campaign manifest in parallel into one HDF5 file (/fits/<trial>, /summary/fits)");
  app->add_option("MANIFEST", cmd->manifest, "Campaign manifest (.toml)")->required();
  app->add_option("-o,--output", cmd->output, "HDF5 file (created or extended; other groups are kept)")->required();
  app->add_option("-j,--jobs", cmd->jobs, "Trials fitted at once (0: all cores)")->capture_default_str();
  app->add_flag("--resume", cmd->resume, "Skip trials already in the file with the same settings (settings_hash)");
  app->add_flag("--json", cmd->json, "Print one JSON object");
  AddFitOptions(*app, cmd->fit);
  app->callback([cmd] { SetExitCode(RunBatch(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
