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
#include "rockfit/fitting/group_pooling.hpp"
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

const char* const kSummaryParameters[] = {"t0", "alpha", "lambda", "lambda_lat", "lambda_lon", "tau_edge"};

// Interval columns of one /fits/<trial>/parameters table (NaN / "" where a file written before intervals
// existed lacks them).
struct StoredIntervals {
  std::vector<double> lo68, hi68, lo95, hi95;
  std::vector<std::string> determined;
};

StoredIntervals ReadStoredIntervals(const io::hdf5::Group& g, std::size_t rows) {
  StoredIntervals s;
  auto doubles = [&](const char* name) {
    const std::string path = std::string("parameters/") + name;
    return g.IsDataset(path) ? g.ReadDoubles(path) : std::vector<double>(rows, std::nan(""));
  };
  s.lo68 = doubles("interval_68_lower");
  s.hi68 = doubles("interval_68_upper");
  s.lo95 = doubles("interval_95_lower");
  s.hi95 = doubles("interval_95_upper");
  s.determined = g.IsDataset("parameters/determined") ? g.ReadStrings("parameters/determined")
                                                       : std::vector<std::string>(rows, "");
  return s;
}

// One (block, position) group's range of every parameter (fitting::PoolTrials).
struct GroupRange {
  std::string block, position;
  std::int64_t n = 0;
  std::map<std::string, double> mean, std_dev;
  std::map<std::string, fitting::PooledEstimate> pooled;
};

// /summary/fits from every /fits/<trial> in the file: a per-trial table with the intervals and a
// per-(block, position) table of mean, spread, pooled estimate with its interval and consistency (layout in
// fitting/README.md). Returns the groups (for the text table of `batch`).
std::vector<GroupRange> WriteFitSummaryTables(const io::hdf5::Group& root) {
  std::vector<std::string> trials, blocks, positions;
  std::map<std::string, std::vector<double>> columns, lo68, hi68, lo95, hi95;
  std::map<std::string, std::vector<std::string>> determined;
  std::vector<double> epsilon, wall, mounting_x, mounting_y, mounting_z;
  std::vector<std::string> mounting;
  std::vector<std::int64_t> simulations;
  const io::hdf5::Group fits = root.OpenGroup("fits");
  for (const std::string& id : fits.Children()) {
    const io::hdf5::Group g = fits.OpenGroup(id);
    trials.push_back(id);
    blocks.push_back(g.GetString("block").value_or(""));
    positions.push_back(g.GetString("position").value_or(""));
    const std::vector<std::string> names = g.ReadStrings("parameters/name");
    const std::vector<double> values = g.ReadDoubles("parameters/value");
    const StoredIntervals stored = ReadStoredIntervals(g, names.size());
    for (const char* name : kSummaryParameters) {
      const auto it = std::find(names.begin(), names.end(), name);
      const bool found = it != names.end();
      const std::size_t row = static_cast<std::size_t>(it - names.begin());
      columns[name].push_back(found ? values[row] : std::nan(""));
      lo68[name].push_back(found ? stored.lo68[row] : std::nan(""));
      hi68[name].push_back(found ? stored.hi68[row] : std::nan(""));
      lo95[name].push_back(found ? stored.lo95[row] : std::nan(""));
      hi95[name].push_back(found ? stored.hi95[row] : std::nan(""));
      determined[name].push_back(found ? stored.determined[row] : "");
    }
    epsilon.push_back(g.GetDouble("epsilon_rad_s").value_or(std::nan("")));
    wall.push_back(g.GetDouble("wall_s").value_or(std::nan("")));
    simulations.push_back(g.GetInt("simulations").value_or(0));
    mounting.push_back(g.GetString("mounting").value_or(""));
    const std::vector<double> angles =
        g.Exists("mounting_angles_deg") ? g.ReadDoubles("mounting_angles_deg") : std::vector<double>{};
    mounting_x.push_back(angles.size() == 3 ? angles[0] : std::nan(""));
    mounting_y.push_back(angles.size() == 3 ? angles[1] : std::nan(""));
    mounting_z.push_back(angles.size() == 3 ? angles[2] : std::nan(""));
  }
  const io::hdf5::Group t = root.CreateGroup("summary/fits/per_trial");
  t.WriteStrings("trial", trials);
  t.WriteStrings("block", blocks);
  t.WriteStrings("position", positions);
  for (const char* name : kSummaryParameters) {
    const std::string unit = fitting::Unit(fitting::ParseParameterName(name));
    const std::string n = name;
    t.WriteDoubles(n, columns[name], unit);
    t.WriteDoubles(n + "_interval_68_lower", lo68[name], unit + "; NaN: open");
    t.WriteDoubles(n + "_interval_68_upper", hi68[name], unit + "; NaN: open");
    t.WriteDoubles(n + "_interval_95_lower", lo95[name], unit + "; NaN: open");
    t.WriteDoubles(n + "_interval_95_upper", hi95[name], unit + "; NaN: open");
    t.WriteStrings(n + "_determined", determined[name]);
  }
  t.WriteDoubles("epsilon_rad_s", epsilon, "rad/s");
  t.WriteDoubles("wall_s", wall, "s");
  t.WriteInts("simulations", simulations, "1");
  t.WriteStrings("mounting", mounting);
  t.WriteDoubles("mounting_angle_x_deg", mounting_x, "deg");
  t.WriteDoubles("mounting_angle_y_deg", mounting_y, "deg");
  t.WriteDoubles("mounting_angle_z_deg", mounting_z, "deg");

  std::map<std::pair<std::string, std::string>, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < trials.size(); ++i) groups[{blocks[i], positions[i]}].push_back(i);
  std::vector<GroupRange> ranges;
  for (const auto& [key, members] : groups) {
    GroupRange range;
    range.block = key.first;
    range.position = key.second;
    range.n = static_cast<std::int64_t>(members.size());
    for (const char* name : kSummaryParameters) {
      double sum = 0.0;
      for (std::size_t i : members) sum += columns[name][i];
      const double m = sum / static_cast<double>(members.size());
      double ss = 0.0;
      for (std::size_t i : members) ss += (columns[name][i] - m) * (columns[name][i] - m);
      range.mean[name] = m;
      range.std_dev[name] = members.size() > 1 ? std::sqrt(ss / static_cast<double>(members.size() - 1)) : std::nan("");
      std::vector<fitting::TrialEstimate> estimates;
      for (std::size_t i : members) {
        estimates.push_back({columns[name][i], {lo95[name][i], hi95[name][i]}, determined[name][i] == "yes"});
      }
      range.pooled[name] = fitting::PoolTrials(estimates);
    }
    ranges.push_back(range);
  }
  const io::hdf5::Group g = root.CreateGroup("summary/fits/per_group");
  std::vector<std::string> group_block, group_position;
  std::vector<std::int64_t> count;
  for (const GroupRange& r : ranges) {
    group_block.push_back(r.block);
    group_position.push_back(r.position);
    count.push_back(r.n);
  }
  g.WriteStrings("block", group_block);
  g.WriteStrings("position", group_position);
  g.WriteInts("n", count, "1");
  for (const char* name : kSummaryParameters) {
    const std::string unit = fitting::Unit(fitting::ParseParameterName(name));
    const std::string n = name;
    std::vector<double> mean, std_dev, pooled, lo, hi, chi2, p;
    std::vector<std::int64_t> n_pooled;
    for (const GroupRange& r : ranges) {
      mean.push_back(r.mean.at(name));
      std_dev.push_back(r.std_dev.at(name));
      const fitting::PooledEstimate& e = r.pooled.at(name);
      pooled.push_back(e.n_pooled > 0 ? e.pooled : std::nan(""));
      lo.push_back(e.interval_95[0]);
      hi.push_back(e.interval_95[1]);
      chi2.push_back(e.chi2_per_dof);
      p.push_back(e.consistency_p);
      n_pooled.push_back(e.n_pooled);
    }
    g.WriteDoubles(n + "_mean", mean, unit);
    g.WriteDoubles(n + "_std", std_dev, unit + "; the spread between trials");
    g.WriteDoubles(n + "_pooled", pooled, unit + "; inverse-variance weighted over the determined trials");
    g.WriteDoubles(n + "_pooled_95_lower", lo, unit);
    g.WriteDoubles(n + "_pooled_95_upper", hi, unit);
    g.WriteInts(n + "_n_pooled", n_pooled, "1");
    g.WriteDoubles(n + "_chi2_per_dof", chi2, "1");
    g.WriteDoubles(n + "_consistency_p", p, "1; below 0.05 the trials disagree beyond their intervals");
  }
  return ranges;
}

// The per-group table of `batch`: pooled estimate [95 % interval], spread, consistency per parameter.
std::string GroupRangeTable(const std::vector<GroupRange>& ranges) {
  std::string out = fmt::format("{:<10} {:<4} {:>2}  {:<11} {:>34} {:>9} {:>7} {:>7}\n", "block", "pos", "n",
                                "parameter", "pooled [95 % interval] (pooled/n)", "spread", "χ²/dof", "p");
  for (const GroupRange& r : ranges) {
    for (const char* name : kSummaryParameters) {
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

// Hashes of the fits already in the file (for --resume).
std::map<std::string, std::string> StoredSettingsHashes(const std::filesystem::path& path) {
  std::map<std::string, std::string> hashes;
  if (!std::filesystem::exists(path) || !io::hdf5::File::IsHdf5(path)) return hashes;
  const io::hdf5::File file = io::hdf5::File::Open(path);
  if (!file.Root().IsGroup("fits")) return hashes;
  const io::hdf5::Group fits = file.Root().OpenGroup("fits");
  for (const std::string& id : fits.Children()) {
    hashes[id] = fits.OpenGroup(id).GetString("settings_hash").value_or("");
  }
  return hashes;
}

int RunBatch(const BatchCommand& cmd) {
  const io::Manifest manifest = io::ReadManifest(cmd.manifest);
  if (manifest.trials.empty()) throw BadInput(fmt::format("{}: the manifest lists no trials", cmd.manifest));
  if (cmd.jobs < 0) throw InvalidArgument("-j must be ≥ 0 (0: all cores)");
  MakeParameterSet(cmd.fit);  // option errors before any work
  fitting::ParseFitMethod(cmd.fit.method);
  // Fail early on an output that cannot be written (OutputError, exit 4), before hours of fitting.
  { io::hdf5::Transaction probe(cmd.output); }

  const std::map<std::string, std::string> stored = cmd.resume ? StoredSettingsHashes(cmd.output)
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
        const std::string hash = SettingsHash(settings);
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
          WriteFitGroup(tx.Root(), o.trial, {spec.block_id, spec.position, spec.notes}, prepared, summary);
          io::WriteMountingHdf5(tx.Root().OpenGroup("fits/" + o.trial), recording);
          last_ranges = WriteFitSummaryTables(tx.Root());
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
    for (const char* name : kSummaryParameters) {
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
