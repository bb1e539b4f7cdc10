#include "rockfit/fitting/batch.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_settings.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_transaction.hpp"

namespace rockfit::fitting {
namespace {

MeasuredSignal SignalOf(const io::Recording& r) {
  MeasuredSignal s;
  s.t_s = r.t_s;
  s.w_B = r.w_B;
  return s;
}

FitLabels LabelsOf(const io::TrialSpec& trial, const io::BlockSpec& block) {
  return {trial.block_id, trial.position, block.b1_m, block.b2_m, block.h_m};
}

std::filesystem::path PartPath(const std::filesystem::path& parts, const std::string& trial_id) {
  return parts / (trial_id + ".h5");
}

// The settings hash of a finished part file for the trial, if it holds a successful fit.
std::optional<std::string> PartHash(const std::filesystem::path& part, const std::string& trial_id) {
  if (!std::filesystem::exists(part) || !io::hdf5::File::IsHdf5(part)) return std::nullopt;
  try {
    const io::hdf5::File file = io::hdf5::File::Open(part);
    return StoredSettingsHash(file.Root(), trial_id);
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: fit again
  }
}

}  // namespace

void BatchOptions::Validate() const {
  parameters.Validate();
  trial.Validate();
  if (jobs < 0) throw InvalidArgument(fmt::format("-j/--jobs must be 0 (all cores) or positive, got {}", jobs));
}

std::filesystem::path PartsDirectory(const std::filesystem::path& output) {
  return std::filesystem::path(output.string() + ".parts");
}

std::string TrialSettingsHash(const io::TrialSpec& trial, const io::BlockSpec& block, const BatchOptions& options,
                              std::string* settings_json) {
  nlohmann::json input = {{"files", trial.files.string()},
                          {"format", trial.format},
                          {"rate_hz", trial.rate_hz ? nlohmann::json(*trial.rate_hz) : nlohmann::json()},
                          {"mounting", trial.mounting},
                          {"block", {{"b1_m", block.b1_m}, {"b2_m", block.b2_m}, {"h_m", block.h_m},
                                     {"density_kg_m3", block.density_kg_m3 ? nlohmann::json(*block.density_kg_m3) : nlohmann::json()},
                                     {"mass_kg", block.mass_kg ? nlohmann::json(*block.mass_kg) : nlohmann::json()}}}};
  TrialFitOptions trial_options = options.trial;
  trial_options.fit.num_threads = 1;
  const std::string json = FitSettingsJson(options.parameters, trial_options, input.dump());
  if (settings_json) *settings_json = json;
  return SettingsHash(json);
}

BatchReport RunBatch(const io::Manifest& manifest, const std::filesystem::path& output, const BatchOptions& options_in,
                     const TrialLoader& load, const BatchProgress& progress) {
  BatchOptions options = options_in;
  options.trial.fit.num_threads = 1;
  options.Validate();
  const auto clock_start = std::chrono::steady_clock::now();

  // The trials to consider.
  std::vector<const io::TrialSpec*> trials;
  for (const io::TrialSpec& t : manifest.trials) {
    if (options.only_trials.empty() ||
        std::find(options.only_trials.begin(), options.only_trials.end(), t.id) != options.only_trials.end()) {
      trials.push_back(&t);
    }
  }
  for (const std::string& id : options.only_trials) manifest.FindTrial(id);  // BadInput for an unknown id

  const std::filesystem::path parts = PartsDirectory(output);
  std::error_code ec;
  if (!options.resume) std::filesystem::remove_all(parts, ec);
  std::filesystem::create_directories(parts, ec);
  if (ec || !std::filesystem::is_directory(parts)) {
    throw OutputError(fmt::format("cannot create the directory {} for finished trials: {}; check the permissions",
                                  parts.string(), ec.message()));
  }

  // What is already done (resume).
  std::vector<std::string> hashes(trials.size()), settings(trials.size());
  std::vector<char> skip(trials.size(), 0);
  std::optional<io::hdf5::File> existing;
  if (options.resume && std::filesystem::exists(output) && io::hdf5::File::IsHdf5(output)) existing = io::hdf5::File::Open(output);
  for (std::size_t i = 0; i < trials.size(); ++i) {
    hashes[i] = TrialSettingsHash(*trials[i], manifest.FindBlock(trials[i]->block_id), options, &settings[i]);
    if (!options.resume) continue;
    const std::optional<std::string> in_parts = PartHash(PartPath(parts, trials[i]->id), trials[i]->id);
    const std::optional<std::string> in_output = existing ? StoredSettingsHash(existing->Root(), trials[i]->id) : std::nullopt;
    if (in_parts == hashes[i] || in_output == hashes[i]) skip[i] = 1;
  }
  existing.reset();

  BatchReport report;
  report.output = output;
  report.trials.resize(trials.size());
  std::mutex mutex;  // progress callback, counters and HDF5 writes
  std::size_t finished = 0;
  const std::size_t total = trials.size();
  for (std::size_t i = 0; i < trials.size(); ++i) {
    if (!skip[i]) continue;
    report.trials[i] = {trials[i]->id, "skipped", "already fitted with the same settings", 0.0, 0.0, 0, 0};
    ++finished;
    if (progress) progress(report.trials[i], finished, total);
  }

  auto fit_one = [&](std::size_t i) {
    if (skip[i]) return;
    const io::TrialSpec& trial = *trials[i];
    BatchTrialResult result;
    result.trial_id = trial.id;
    const auto start = std::chrono::steady_clock::now();
    std::optional<TrialFit> fit;
    try {
      const io::BlockSpec& block = manifest.FindBlock(trial.block_id);
      const io::Recording recording = load(trial);
      fit = FitTrial(block.ToBlock(), SignalOf(recording), options.parameters, options.trial);
      if (!fit->summary.feasible) throw NumericalFailure("no feasible parameters: the model fails everywhere it was tried");
      result.status = "ok";
      result.epsilon_rad_s = fit->summary.epsilon_rad_s;
      result.simulations = fit->summary.simulations;
      result.warnings = fit->summary.warnings.size();
    } catch (const std::exception& e) {
      result.status = "failed";
      result.message = e.what();
    }
    result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Write the part at once: a kill after this line does not lose the trial.
    std::lock_guard<std::mutex> lock(mutex);
    try {
      io::hdf5::Transaction tx(PartPath(parts, trial.id));
      const FitLabels labels = LabelsOf(trial, manifest.FindBlock(trial.block_id));
      if (result.status == "ok") {
        WriteFitHdf5(tx.Root(), trial.id, labels, *fit, settings[i], hashes[i]);
      } else {
        WriteFailedFitHdf5(tx.Root(), trial.id, labels, result.message, hashes[i]);
      }
      tx.Commit();
    } catch (const std::exception& e) {
      result.status = "failed";
      result.message = std::string("cannot store the result: ") + e.what();
    }
    report.trials[i] = result;
    ++finished;
    if (progress) progress(result, finished, total);
  };
  const int cores = tbb::info::default_concurrency();
  tbb::task_arena arena(options.jobs > 0 ? std::min(options.jobs, std::max(cores, 1)) : cores);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, trials.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) fit_one(i);
                      });
  });

  // Merge every part into the output in one atomic rewrite.
  std::vector<std::string> replaced = {"/fit_summary"};
  std::vector<std::size_t> with_part;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    if (std::filesystem::exists(PartPath(parts, trials[i]->id))) {
      with_part.push_back(i);
      replaced.push_back("/fits/" + trials[i]->id);
    }
  }
  {
    io::hdf5::Transaction tx(output, replaced);
    {  // every group is closed before the commit closes the file
      const io::hdf5::Group root = tx.Root();
      io::WriteFileAttributes(root, options.rockfit_version);
      const io::hdf5::Group fits = root.RequireGroup("fits");
      for (std::size_t i : with_part) {
        const io::hdf5::File part = io::hdf5::File::Open(PartPath(parts, trials[i]->id));
        io::hdf5::CopyObject(part.Root().OpenGroup("fits"), trials[i]->id, fits);
      }
      for (const io::BlockSpec& b : manifest.blocks) io::WriteBlockHdf5(root, b.id, b.ToBlock(), b.notes);
      WriteFitTablesHdf5(root);
    }
    tx.Commit();
  }
  std::filesystem::remove_all(parts, ec);

  for (const BatchTrialResult& r : report.trials) {
    if (r.status == "ok") ++report.ok;
    if (r.status == "failed") ++report.failed;
    if (r.status == "skipped") ++report.skipped;
  }
  report.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return report;
}

}  // namespace rockfit::fitting
