// `rockfit batch MANIFEST -o fits.h5`: fit every trial of a campaign in parallel into one HDF5 file (docs/design.md §7,
// §8). Each finished trial is committed through an atomic transaction before the next one is written (a mutex
// serialises the writers), so killing the batch at any moment loses at most the trials still running, and
// `--resume` skips the trials the file already holds with the same settings.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "fit_setup.hpp"
#include "mounting_report.hpp"
#include "progress_bar.hpp"
#include "recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_transaction.hpp"
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

struct TrialOutcome {
  std::string trial;
  bool ok = false;
  bool skipped = false;
  int exit_code = kExitOk;
  std::string message;
  double epsilon_rad_s = std::nan("");
  double wall_s = 0.0;
  std::string mounting;  // applied
  double mounting_disagreement_deg = std::nan("");
  std::string mounting_warning;
};

using GroupRange = fitting::GroupSummary;

// The per-group table of `batch`: pooled estimate [95 % interval], spread, consistency per parameter.
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

int RunBatch(const BatchCommand& cmd) {
  const io::Manifest manifest = io::ReadManifest(cmd.manifest);
  if (manifest.trials.empty()) throw BadInput(fmt::format("{}: the manifest lists no trials", cmd.manifest));
  if (cmd.jobs < 0) throw InvalidArgument("-j must be ≥ 0 (0: all cores)");
  MakeParameterSet(cmd.fit);  // option errors before any work
  fitting::ParseFitMethod(cmd.fit.method);
  // Fail early on an output that cannot be written (OutputError, exit 4), before hours of fitting.
  { io::hdf5::Transaction probe(cmd.output); }

  const std::map<std::string, std::string> stored = cmd.resume ? fitting::StoredSettingsHashes(cmd.output)
                                                               : std::map<std::string, std::string>{};
  const std::size_t n = manifest.trials.size();
  std::vector<TrialOutcome> outcomes(n);
  std::atomic<std::size_t> next{0};
  std::mutex write_mutex;
  std::vector<GroupRange> last_ranges;  // the group table of the last commit
  ProgressBar progress("batch", n, 0, StderrIsTerminal());
  std::size_t done = 0;
  FitArgs fit_args = cmd.fit;
  fit_args.threads = 1;  // parallel over trials, not inside one fit

  auto work = [&] {
    for (std::size_t i = next.fetch_add(1); i < n; i = next.fetch_add(1)) {
      const io::TrialSpec& spec = manifest.trials[i];
      TrialOutcome& o = outcomes[i];
      o.trial = TrialNameFrom(spec.id);
      try {
        const core::Block block = manifest.FindBlock(spec.block_id).ToBlock();
        // The trial's mounting as the manifest gives it ("auto" included) changes what is fitted.
        const std::string settings = FitSettingsText(block, fit_args) + "; mounting=" +
                                     (spec.mounting.empty() ? "identity" : spec.mounting);
        const std::string hash = fitting::SettingsHash(settings);
        const auto it = stored.find(o.trial);
        if (it != stored.end() && it->second == hash) {
          o.ok = o.skipped = true;
        } else {
          const io::Recording recording = LoadManifestTrial(spec);
          o.mounting = recording.mounting;
          o.mounting_disagreement_deg = io::MountingDisagreementDeg(recording.mounting_check);
          o.mounting_warning = recording.mounting_check.warning;
          PreparedFit prepared = PrepareFit(recording, block, fit_args);
          prepared.settings = settings;
          const fitting::FitSummary summary = fitting::Fit(prepared.objective, prepared.start, prepared.options);
          o.epsilon_rad_s = summary.epsilon_rad_s;
          o.wall_s = summary.wall_time_s;
          o.ok = summary.feasible;
          if (!o.ok) {
            o.exit_code = kExitNumerical;
            o.message = "no feasible parameters: " + summary.termination;
          }
          std::lock_guard<std::mutex> lock(write_mutex);
          io::hdf5::Transaction tx(cmd.output, {"/fits/" + o.trial, "/summary/fits"});
          io::WriteFileAttributes(tx.Root(), ROCKFIT_VERSION);
          fitting::WriteFitGroup(tx.Root(), o.trial, {spec.block_id, spec.position, spec.notes}, prepared.objective,
                                 prepared.settings, summary);
          io::WriteMountingHdf5(tx.Root().OpenGroup("fits/" + o.trial), recording);
          last_ranges = fitting::WriteFitSummaryTables(tx.Root());
          tx.Commit();
        }
      } catch (const InvalidArgument& e) {
        o.exit_code = kExitUsage;
        o.message = e.what();
      } catch (const BadInput& e) {
        o.exit_code = kExitBadInput;
        o.message = e.what();
      } catch (const OutputError& e) {
        o.exit_code = kExitCannotWrite;
        o.message = e.what();
      } catch (const std::exception& e) {
        o.exit_code = kExitNumerical;
        o.message = e.what();
      }
      const std::string what = o.skipped ? "already fitted"
                               : o.ok    ? fmt::format("ε = {:.4g} rad/s in {:.1f} s", o.epsilon_rad_s, o.wall_s)
                                         : "FAILED: " + o.message;
      std::lock_guard<std::mutex> lock(write_mutex);
      progress.Report(++done, o.trial + ": " + what);
    }
  };
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = std::min<std::size_t>(n, cmd.jobs > 0 ? static_cast<std::size_t>(cmd.jobs) : cores);
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();

  int exit_code = kExitOk;
  std::size_t failed = 0, skipped = 0;
  nlohmann::json trials = nlohmann::json::array();
  for (const TrialOutcome& o : outcomes) {
    if (o.skipped) ++skipped;
    if (!o.ok) {
      ++failed;
      exit_code = std::max(exit_code, o.exit_code);
    }
    trials.push_back({{"trial", o.trial},
                      {"ok", o.ok},
                      {"skipped", o.skipped},
                      {"epsilon", std::isfinite(o.epsilon_rad_s) ? nlohmann::json(o.epsilon_rad_s) : nlohmann::json()},
                      {"wall_s", o.wall_s},
                      {"mounting", o.mounting},
                      {"mounting_disagreement_deg", OrNull(o.mounting_disagreement_deg)},
                      {"message", o.message}});
  }
  nlohmann::json groups = nlohmann::json::array();
  for (const GroupRange& r : last_ranges) {
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
  if (cmd.json) {
    PrintJson({{"output", cmd.output}, {"trials", trials}, {"fitted", n - failed - skipped}, {"skipped", skipped},
               {"failed", failed}, {"groups", groups}});
  } else {
    std::cout << fmt::format("{} trials: {} fitted, {} skipped (already in {} with the same settings), {} failed\n", n,
                             n - failed - skipped, skipped, cmd.output, failed);
    if (!last_ranges.empty()) std::cout << GroupRangeTable(last_ranges);
  }
  for (const TrialOutcome& o : outcomes) {
    if (!o.mounting_warning.empty()) std::cerr << "rockfit: warning: " << o.trial << ": " << o.mounting_warning << "\n";
  }
  if (failed > 0) {
    std::cerr << fmt::format("rockfit: {} trial(s) failed:\n", failed);
    for (const TrialOutcome& o : outcomes) {
      if (!o.ok) std::cerr << "  " << o.trial << ": " << o.message << "\n";
    }
    std::cerr << "Fix or remove them and re-run with --resume (finished trials are kept).\n";
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
