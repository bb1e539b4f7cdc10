#include "rockfit/fitting/fit_campaign.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>

#include <fmt/format.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "rockfit/core/checks.hpp"
#include "rockfit/fitting/recorded_fit.hpp"
#include "rockfit/io/hdf5_transaction.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::fitting {
namespace {

using Clock = std::chrono::steady_clock;

// What every worker shares: the trials, the stored hashes, the output and the one mutex that serialises the
// commits and the callbacks.
struct CampaignRun {
  const std::vector<CampaignTrial>& trials;
  const std::filesystem::path& output;
  const CampaignOptions& options;
  const TrialEndCallback& on_trial_end;
  std::map<std::string, std::string> stored_hashes;
  std::vector<TrialOutcome> outcomes;
  std::vector<GroupSummary> groups;  // of the last commit
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
};

// Replaces /fits/<trial> and /summary/fits in one transaction (the caller holds the mutex).
void Commit(CampaignRun& run, const CampaignTrial& trial, const PreparedTrial& prepared, const std::string& settings,
            const FitSummary& summary) {
  io::hdf5::Transaction tx(run.output, {"/fits/" + trial.id, "/summary/fits"});
  io::WriteFileAttributes(tx.Root(), run.options.rockfit_version);
  WriteFitGroup(tx.Root(), trial.id, trial.labels, prepared.objective, settings, summary);
  if (prepared.recording) io::WriteMountingHdf5(tx.Root().OpenGroup("fits/" + trial.id), *prepared.recording);
  run.groups = WriteFitSummaryTables(tx.Root());
  tx.Commit();
}

// Fits one trial and commits it, unless the file holds it with the same settings. Exceptions propagate.
void FitOne(CampaignRun& run, const CampaignTrial& trial, TrialOutcome& o) {
  const std::string settings = trial.settings();
  const auto stored = run.stored_hashes.find(trial.id);
  if (stored != run.stored_hashes.end() && stored->second == SettingsHash(settings)) {
    o.status = TrialStatus::kSkipped;
    return;
  }
  const PreparedTrial prepared = trial.prepare();
  const FitSummary summary =
      FitRecordedTrial(prepared.objective, prepared.start, prepared.options, prepared.release_roll_choice,
                       prepared.recording ? &*prepared.recording : nullptr);
  o.epsilon_rad_s = summary.epsilon_rad_s;
  o.fit_wall_s = summary.wall_time_s;
  o.model_error = summary.model_error;
  o.status = summary.feasible ? TrialStatus::kFitted : TrialStatus::kInfeasible;
  if (!summary.feasible) o.message = "no feasible parameters: " + summary.termination;
  std::lock_guard<std::mutex> lock(run.mutex);
  Commit(run, trial, prepared, settings, summary);
}

void RunTrial(CampaignRun& run, std::size_t i) {
  const Clock::time_point start = Clock::now();
  const CampaignTrial& trial = run.trials[i];
  TrialOutcome& o = run.outcomes[i];
  o.trial = trial.id;
  try {
    FitOne(run, trial, o);
  } catch (const std::exception& e) {
    o.status = TrialStatus::kFailed;
    o.message = e.what();
    o.error = std::current_exception();
  }
  const double elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
  std::lock_guard<std::mutex> lock(run.mutex);
  if (run.on_trial_end) run.on_trial_end(o, elapsed_s);
}

// Each worker takes the next trial not yet started, so trials start in the order given.
void Work(CampaignRun& run) {
  for (std::size_t i = run.next.fetch_add(1); i < run.trials.size(); i = run.next.fetch_add(1)) RunTrial(run, i);
}

std::size_t Workers(const CampaignOptions& options, std::size_t trials) {
  const int cores = tbb::info::default_concurrency();
  const int threads = options.num_threads > 0 ? std::min(options.num_threads, cores) : cores;
  return std::max<std::size_t>(1, std::min<std::size_t>(trials, static_cast<std::size_t>(threads)));
}

CampaignSummary Summarise(CampaignRun& run) {
  CampaignSummary s;
  s.trials = std::move(run.outcomes);
  for (const TrialOutcome& o : s.trials) {
    if (o.status == TrialStatus::kFitted) ++s.fitted;
    if (o.status == TrialStatus::kSkipped) ++s.skipped;
    if (!o.ok()) ++s.failed;
  }
  s.groups = std::move(run.groups);
  return s;
}

}  // namespace

void CampaignOptions::Validate() const { RequireAtLeast(num_threads, 0, "campaign option num_threads"); }

const char* ToString(TrialStatus status) {
  switch (status) {
    case TrialStatus::kFitted: return "fitted";
    case TrialStatus::kSkipped: return "skipped";
    case TrialStatus::kInfeasible: return "infeasible";
    case TrialStatus::kFailed: return "failed";
  }
  return "?";
}

bool FromString(std::string_view text, TrialStatus* value) {
  static constexpr TrialStatus kAll[] = {TrialStatus::kFitted, TrialStatus::kSkipped, TrialStatus::kInfeasible, TrialStatus::kFailed};
  return core::FromStringAmong(text, kAll, value);
}

CampaignSummary FitCampaign(const std::vector<CampaignTrial>& trials, const std::filesystem::path& output,
                            const CampaignOptions& options, const TrialEndCallback& on_trial_end) {
  options.Validate();
  // An output that cannot be written fails now (OutputError), not after hours of fitting.
  { io::hdf5::Transaction probe(output); }
  CampaignRun run{trials, output, options, on_trial_end, {}, {}, {}, {}, {}};
  if (options.resume) run.stored_hashes = StoredSettingsHashes(output);
  run.outcomes.resize(trials.size());
  const std::size_t workers = Workers(options, trials.size());
  tbb::task_arena arena(static_cast<int>(workers));
  arena.execute([&] {
    tbb::task_group group;
    for (std::size_t w = 0; w < workers; ++w) group.run([&run] { Work(run); });
    group.wait();
  });
  return Summarise(run);
}

}  // namespace rockfit::fitting
