// `rockfit fragility`: the probability that a block overturns (or exceeds given peak tilts) at each intensity
// level, with binomial intervals and a fitted lognormal curve, from a Monte-Carlo study of `respond` runs
// (fitting/quake/include/rockfit/quake/fragility_study.hpp). Threads (TBB) on one machine, MPI ranks on several (sample_ranks.hpp): the
// ranks split the samples round-robin, rank 0 gathers each round, appends it to a journal (kill-safe, for
// --resume) and at the end writes the HDF5 file atomically.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "rockfit/app/activity.hpp"
#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/fit_setup.hpp"
#include "rockfit/app/fitted_parameters.hpp"
#include "fragility_ledger.hpp"
#include "rockfit/app/fragility_output.hpp"
#include "rockfit/app/fragility_setup.hpp"
#include "rockfit/app/ground_motion_args.hpp"
#include "rockfit/app/progress_bar.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/io/hdf5_transaction.hpp"
#include "rockfit/app/run_limits.hpp"
#include "sample_ranks.hpp"

namespace rockfit::tools {
namespace {

// Samples per rank and thread in one round (one journal append): small enough that a kill loses little, large
// enough that the collective gather and the flush to disk cost nothing next to the simulations (a few ms each).
constexpr int kSamplesPerThreadPerRound = 8;
// The journal is flushed to disk (fdatasync, milliseconds) at most this often: a kill -9 loses nothing written
// before it anyway; a power failure loses at most this much work.
constexpr std::chrono::seconds kSyncEvery{10};
// The progress line is written at most this often (and at the end).
constexpr std::chrono::seconds kReportEvery{1};

struct FragilityCommand {
  FragilityArgs study;
  int threads = 0;
  int round = 0;
  bool mpi = false;
  bool resume = false;
  bool json = false;
  std::string output;
};

int RunFragility(const FragilityCommand& cmd) {
  SampleRanks ranks(cmd.mpi || StartedByLauncher());
  // Every rank reads the inputs; a failure on any rank stops all of them (no rank waits forever in a collective).
  quake::FragilityStudyOptions study;
  std::string hash;
  std::optional<FragilityLedger> ledger;
  std::exception_ptr failure;
  bool already_complete = false;
  try {
    if (cmd.threads < 0) throw InvalidArgument("-j must be ≥ 0 (0: all cores)");
    if (cmd.round < 0) throw InvalidArgument("--round must be ≥ 0 (0: automatic)");
    study = MakeFragilityStudy(cmd.study);
    hash = fitting::SettingsHash(study.SettingsText());
    if (ranks.rank() == 0) {
      { io::hdf5::Transaction probe(cmd.output); }  // exit 4 now, not after the study, when it cannot be written
      already_complete = cmd.resume && !std::filesystem::exists(FragilityJournalPath(cmd.output)) &&
                         StoredFragilityHash(cmd.output) == hash;
      if (!already_complete) ledger.emplace(OpenLedger(FragilityJournalPath(cmd.output), study, hash, cmd.resume));
    }
  } catch (...) {
    failure = std::current_exception();
  }
  const bool all_ok = ranks.AllOk(!failure);
  if (failure) std::rethrow_exception(failure);
  if (!all_ok) throw BadInput("another MPI rank could not set up the study (its message is above)");

  std::vector<std::int64_t> remaining;
  if (ranks.rank() == 0 && ledger) remaining = ledger->Remaining();
  const std::vector<std::int64_t> flag = ranks.Broadcast({already_complete ? 1 : 0});
  if (flag.at(0) != 0) {
    if (ranks.rank() == 0) {
      if (cmd.json) {
        PrintJson({{"output", cmd.output}, {"settings_hash", hash}, {"complete", true}, {"samples", study.num_samples()},
                   {"simulated", 0}});
      } else {
        std::cout << fmt::format("{} already holds this study (settings hash {}): nothing to do\n", cmd.output, hash);
      }
    }
    return kExitOk;
  }
  remaining = ranks.Broadcast(std::move(remaining));

  // Round-robin over the ranks; every rank runs the same number of rounds (the gather is collective).
  std::vector<std::int64_t> mine;
  for (std::size_t i = static_cast<std::size_t>(ranks.rank()); i < remaining.size(); i += static_cast<std::size_t>(ranks.size())) {
    mine.push_back(remaining[i]);
  }
  const int threads = cmd.threads > 0 ? cmd.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::size_t per_round =
      static_cast<std::size_t>(cmd.round > 0 ? cmd.round : kSamplesPerThreadPerRound * threads);
  const std::size_t per_rank_max = (remaining.size() + static_cast<std::size_t>(ranks.size()) - 1) / static_cast<std::size_t>(ranks.size());
  const std::size_t rounds = (per_rank_max + per_round - 1) / per_round;
  const std::size_t total = static_cast<std::size_t>(study.num_samples());
  const std::size_t resumed = ranks.rank() == 0 ? ledger->resumed : 0;
  ProgressBar progress("fragility", total, resumed, StderrIsTerminal());
  std::size_t done = resumed, overturned_this_run = 0;
  const auto start = std::chrono::steady_clock::now();
  auto last_report = start, last_sync = start;
  const Activity activity(fmt::format("running the {} samples of the fragility study", total));
  for (std::size_t r = 0; r < rounds; ++r) {
    const std::size_t from = std::min(mine.size(), r * per_round), to = std::min(mine.size(), (r + 1) * per_round);
    const std::vector<std::int64_t> chunk(mine.begin() + static_cast<std::ptrdiff_t>(from),
                                          mine.begin() + static_cast<std::ptrdiff_t>(to));
    const std::vector<quake::SampleOutcome> local = quake::RunSamples(study, chunk, cmd.threads);
    const std::vector<quake::SampleOutcome> gathered = ranks.Gather(local);
    if (ranks.rank() != 0) continue;
    try {
      done += ledger->Record(gathered, &overturned_this_run);
      if (std::chrono::steady_clock::now() - last_sync >= kSyncEvery) {
        ledger->journal->Sync();
        last_sync = std::chrono::steady_clock::now();
      }
    } catch (const OutputError& e) {
      std::cerr << "rockfit: " << e.what() << "\nRun again with --resume once the disk has room." << std::endl;
      ranks.Abort(kExitCannotWrite);
    }
    const auto now = std::chrono::steady_clock::now();
    if (done == total || now - last_report >= kReportEvery) {
      progress.Report(done, fmt::format("{} overturned of {} simulated now", overturned_this_run, done - resumed));
      last_report = now;
    }
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (ranks.rank() != 0) return kExitOk;

  if (const std::vector<std::int64_t> missing = ledger->Remaining(); !missing.empty()) {
    throw NumericalFailure(fmt::format("sample {} was not run; run again with --resume", missing.front()));
  }
  ledger->journal->Sync();
  const quake::FragilitySummary summary = quake::SummariseFragility(study, ledger->by_index);
  {
    io::hdf5::Transaction tx(cmd.output, {"/fragility"});
    io::WriteFileAttributes(tx.Root(), ROCKFIT_VERSION);
    WriteFragilityHdf5(tx.Root(), study, hash, ledger->by_index, summary);
    tx.Commit();
  }
  ledger->journal.reset();
  std::error_code ec;
  std::filesystem::remove(FragilityJournalPath(cmd.output), ec);

  if (summary.not_counted == static_cast<std::int64_t>(total)) {
    std::map<std::string, std::size_t> reasons;
    for (const quake::SampleOutcome& o : ledger->by_index) ++reasons[EndReasonName(o.end_reason)];
    std::vector<std::string> counts;
    for (const auto& [reason, n] : reasons) counts.push_back(fmt::format("{} {}", n, reason));
    throw NumericalFailure(fmt::format("none of the {} samples gave an outcome that counts ({}), so {} holds no "
                                       "fragility curve; check the levels (--pga, --scale), the parameter spreads "
                                       "(--lambda-sd, --lambda-lat-sd, --lambda-lon-sd), --tail and --rate",
                                       total, fmt::join(counts, ", "), cmd.output));
  }
  const std::size_t simulated = total - resumed;
  const double rate = wall_s > 0.0 ? static_cast<double>(simulated) / wall_s : 0.0;
  if (cmd.json) {
    nlohmann::json j = FragilitySummaryJson(study, summary);
    j.update({{"output", cmd.output},
              {"settings_hash", hash},
              {"complete", true},
              {"samples", total},
              {"simulated", simulated},
              {"resumed", resumed},
              {"not_counted", summary.not_counted},
              {"ranks", ranks.size()},
              {"threads_per_rank", threads},
              {"wall_s", wall_s},
              {"simulations_per_s", rate}});
    PrintJson(j);
  } else {
    std::cout << FragilityTable(study, summary);
    std::cout << fmt::format("samples    {} ({} simulated now, {} from the journal), {} not counted (failed, lift-off)\n",
                             total, simulated, resumed, summary.not_counted);
    std::cout << fmt::format("speed      {:.1f} simulations/s on {} rank(s) × {} thread(s) ({:.1f} s)\n", rate,
                             ranks.size(), threads, wall_s);
    std::cout << "written    " << cmd.output << "\n";
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<FragilityCommand>();
  CLI::App* app = root.add_subcommand(
      "fragility",
      "Overturning fragility of a block: Monte-Carlo `respond` runs over records, intensity levels, incidence angles\n"
      "and the spread of the impact parameters; per level the probability of overturning (and of exceeding peak\n"
      "tilts) with 95 % binomial intervals, and a lognormal curve (median, β) fitted by maximum likelihood. Every\n"
      "sample has its own seed (study seed, index): the result is the same bit for bit on any number of threads or\n"
      "MPI ranks (mpirun -np N rockfit fragility …). Completed samples go to OUTPUT.journal as they finish; after a\n"
      "kill, --resume finishes the study.");
  AddBlockOptions(*app, cmd->study.block);
  app->get_option("--block")->description("Block id in the manifest; several: ID,ID,…");
  const char* model = "Parameters";
  app->add_option("--lambda", cmd->study.lambda, "Mean λ of edge impacts (19)")->capture_default_str()->group(model);
  app->add_option("--lambda-lat", cmd->study.lambda_lat, "Mean λ_lat of facet impacts (21)")->capture_default_str()->group(model);
  app->add_option("--lambda-lon", cmd->study.lambda_lon, "Mean λ_lon of facet impacts (21)")->capture_default_str()->group(model);
  app->add_option("--lambda-sd", cmd->study.lambda_sd, "Standard deviation of λ (normal)")->capture_default_str()->group(model);
  app->add_option("--lambda-lat-sd", cmd->study.lambda_lat_sd, "Standard deviation of λ_lat")->capture_default_str()->group(model);
  app->add_option("--lambda-lon-sd", cmd->study.lambda_lon_sd, "Standard deviation of λ_lon")->capture_default_str()->group(model);
  app->add_option("--tau-edge", cmd->study.tau_edge, "τ of edge impacts [N·m·s]")->capture_default_str()->group(model);
  app->add_option("--facet-tau", cmd->study.facet_tau, "τ of facet impacts: no-spin (24) or fixed (τ = 0, Sect. 5; also zero)")
      ->check(CLI::IsMember({"no-spin", "fixed", "zero"}))->capture_default_str()->group(model);
  auto* fits = app->add_option("--fits", cmd->study.fits,
                  "Take the distribution from the HDF5 file of rockfit batch: per parameter the pooled estimate (else the "
                  "mean) with sd = √(its standard error² + between-trial spread²)")
      ->group(model);
  for (const char* given : {"--lambda", "--lambda-lat", "--lambda-lon", "--lambda-sd", "--lambda-lat-sd",
                            "--lambda-lon-sd", "--tau-edge"}) {
    fits->excludes(app->get_option(given));  // the distribution comes from one place
  }
  app->add_option("--group", cmd->study.group, "With --fits: BLOCK,POSITION of one block")->group(model);
  app->add_option("--position", cmd->study.position, "With --fits and --block ID,ID,…: the position of every block")->group(model);
  const char* ground = "Ground motion";
  app->add_option("--record", cmd->study.records, "A ground-motion record (PEER AT2 or CSV); repeat for several")->group(ground);
  app->add_option("--record-format", cmd->study.record_format, "auto (by extension: .csv is CSV, else AT2), at2 or csv")
      ->check(CLI::IsMember({"auto", "at2", "csv"}))->capture_default_str()->group(ground);
  app->add_option("--units", cmd->study.units, "Units of CSV records: g, m/s2 or cm/s2")
      ->check(CLI::IsMember({"g", "m/s2", "cm/s2"}))->capture_default_str()->group(ground);
  app->add_option("--dt", cmd->study.csv_dt_s, "Time step [s] of CSV records without a time column")->group(ground);
  app->add_option("--synthetic-records", cmd->study.synthetic_records,
                  "Also N generated Clough–Penzien records, seeds --synthetic-seed … +N−1 (as respond --synthetic)")
      ->capture_default_str()->group(ground);
  app->add_option("--synthetic-seed", cmd->study.synthetic_seed, "Seed of the first generated record")->capture_default_str()->group(ground);
  app->add_option("--synthetic-duration", cmd->study.synthetic_duration_s, "Duration of the generated records [s]")
      ->capture_default_str()->group(ground);
  app->add_option("--synthetic-dt", cmd->study.synthetic_dt_s, "Step of the generated records [s]")->capture_default_str()->group(ground);
  const char* levels = "Study";
  auto* pga = app->add_option("--pga", cmd->study.pga,
                              "Intensity levels: peak horizontal ground acceleration [g], as LIST (0.1,0.2,0.3) or "
                              "FROM:TO:N; each record is scaled to it")->group(levels);
  app->add_option("--scale", cmd->study.scale, "Intensity levels: factors multiplying the records as read (LIST or FROM:TO:N)")
      ->excludes(pga)->group(levels);
  app->add_option("--angle", cmd->study.angle, "Incidence angle [deg] of the records from the block's x axis, or random "
                                         "(uniform on [0°, 360°) per sample)")->capture_default_str()->group(levels);
  app->add_option("--tilt", cmd->study.tilts, "Also the probability that the peak tilt reaches these fractions of the critical "
                                        "tilt atan(min(b1,b2)/h), e.g. 0.5,0.8")->group(levels);
  app->add_option("--samples", cmd->study.samples, "Samples per level and block (records used in turn)")->capture_default_str()->group(levels);
  app->add_option("--seed", cmd->study.seed, "Study seed: sample i draws from its own stream (seed, i)")->capture_default_str()->group(levels);
  app->add_option("--tail", cmd->study.tail_s, "Simulate this long after the end of each record [s]")->capture_default_str()->group(levels);
  app->add_option("--rate", cmd->study.rate_hz, "Sample rate of each run [Hz] (peak tilts are taken over the samples and the end)")
      ->capture_default_str()->group(levels);
  app->add_option("--overturn", cmd->study.overturn,
                  "When a block has overturned: support (its COM passes over the support) or side (it comes to lie on a\n"
                  "side; the table may pull it back before), as in `rockfit respond`")
      ->check(CLI::IsMember({"support", "side"}))->capture_default_str()->group(levels);
  const char* run = "Running";
  app->add_option("-j,--jobs", cmd->threads, "Threads per process (0: all cores)")->capture_default_str()->group(run);
  app->add_option("--round", cmd->round, "Samples per rank between journal appends (0: 8 per thread)")
      ->capture_default_str()->group(run);
  app->add_flag("--mpi", cmd->mpi, "Use MPI even when not started by mpirun/srun (fails when this build has none)")->group(run);
  app->add_flag("--resume", cmd->resume, "Continue an interrupted study from OUTPUT.journal (same settings only)")->group(run);
  app->add_option("-o,--output", cmd->output, "HDF5 file for /fragility (created or extended; other groups are kept)")
      ->required()->group("Output");
  app->add_flag("--json", cmd->json, "Print one JSON object instead of the table")->group("Output");
  app->footer(LimitsHelp() + "\nExit codes: 0 done; 1 bad options (or MPI asked of a build without it); 2 unreadable input or a journal of "
              "another study; 3 numerical failure; 4 cannot write.");
  app->callback([cmd] { SetExitCode(RunFragility(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
