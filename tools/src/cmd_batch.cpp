// `rockfit batch MANIFEST`: fit every trial of a campaign in parallel into one HDF5 file (DESIGN §7, §8), with
// a progress bar on a terminal, failures isolated and listed, and --resume after an interruption.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "fit_cli.hpp"
#include "recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/batch.hpp"
#include "rockfit/io/manifest.hpp"

namespace rockfit::tools {
namespace {

struct BatchCommand {
  std::string manifest;
  std::string output = "fits.h5";
  FitArgs fit;
  int jobs = 0;
  bool resume = false;
  std::vector<std::string> trials;
  bool json = false;
  bool no_progress = false;
};

std::string Clock(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60) : fmt::format("{}:{:02}", s / 60, s % 60);
}

// Progress on stderr: a bar redrawn in place on a terminal, one line per trial otherwise.
class ProgressReporter {
 public:
  ProgressReporter(bool terminal, bool quiet) : terminal_(terminal), quiet_(quiet), start_(std::chrono::steady_clock::now()) {}

  void operator()(const fitting::BatchTrialResult& r, std::size_t finished, std::size_t total) {
    if (r.status == "failed") ++failed_;
    if (quiet_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (r.status != "skipped") ++fitted_;
    const std::size_t remaining = total - finished;
    // ETA from the trials fitted in this run (skipped ones cost nothing).
    const std::string eta = fitted_ > 0 ? Clock(elapsed / static_cast<double>(fitted_) * static_cast<double>(remaining)) : "?";
    if (terminal_) {
      constexpr int kWidth = 30;
      const int filled = static_cast<int>(kWidth * finished / std::max<std::size_t>(total, 1));
      std::fprintf(stderr, "\r[%s%s] %zu/%zu trials, %zu failed, elapsed %s, ETA %s   ", std::string(filled, '#').c_str(),
                   std::string(kWidth - filled, '.').c_str(), finished, total, failed_, Clock(elapsed).c_str(), eta.c_str());
      if (finished == total) std::fprintf(stderr, "\n");
      if (r.status == "failed") std::fprintf(stderr, "\r%-80s\n", fmt::format("trial {} failed: {}", r.trial_id, r.message).c_str());
    } else {
      std::string what = r.status == "ok"        ? fmt::format("ok, ε = {:.5g} rad/s, {:.2f} s", r.epsilon_rad_s, r.wall_time_s)
                         : r.status == "skipped" ? std::string("skipped (already fitted with the same settings)")
                                                 : "failed: " + r.message;
      std::fprintf(stderr, "[%zu/%zu] %s %s (ETA %s)\n", finished, total, r.trial_id.c_str(), what.c_str(), eta.c_str());
    }
    std::fflush(stderr);
  }

 private:
  bool terminal_;
  bool quiet_;
  std::chrono::steady_clock::time_point start_;
  std::size_t failed_ = 0;
  std::size_t fitted_ = 0;
};

int RunBatchCommand(const BatchCommand& cmd) {
  if (cmd.fit.t_end_s) throw InvalidArgument("--t-end is a time of one recording; batches detect each window end");
  const io::Manifest manifest = io::ReadManifest(cmd.manifest);
  fitting::BatchOptions options;
  options.parameters = MakeParameterSet(cmd.fit);
  options.trial = MakeTrialFitOptions(cmd.fit);
  options.jobs = cmd.jobs;
  options.resume = cmd.resume;
  options.rockfit_version = ROCKFIT_VERSION;
  options.only_trials = cmd.trials;
  const int jobs = cmd.jobs > 0 ? cmd.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  ProgressReporter progress(::isatty(STDERR_FILENO) != 0, cmd.no_progress);
  if (!cmd.no_progress) {
    std::fprintf(stderr, "fitting %zu trial(s) of %s with %d job(s) into %s%s\n",
                 cmd.trials.empty() ? manifest.trials.size() : cmd.trials.size(), cmd.manifest.c_str(), jobs,
                 cmd.output.c_str(), cmd.resume ? " (resuming)" : "");
  }
  const fitting::BatchReport report =
      fitting::RunBatch(manifest, cmd.output, options, LoadManifestTrial,
                        [&](const fitting::BatchTrialResult& r, std::size_t finished, std::size_t total) {
                          progress(r, finished, total);
                        });

  if (cmd.json) {
    nlohmann::json trials = nlohmann::json::array();
    for (const auto& r : report.trials) {
      trials.push_back({{"trial", r.trial_id},
                        {"status", r.status},
                        {"message", r.message},
                        {"epsilon", r.status == "ok" ? nlohmann::json(r.epsilon_rad_s) : nlohmann::json()},
                        {"wall_s", r.wall_time_s},
                        {"simulations", r.simulations},
                        {"warnings", r.warnings}});
    }
    PrintJson({{"manifest", cmd.manifest},
               {"output", cmd.output},
               {"trials", trials},
               {"ok", report.ok},
               {"failed", report.failed},
               {"skipped", report.skipped},
               {"jobs", jobs},
               {"wall_s", report.wall_time_s}});
  } else {
    std::cout << fmt::format("{} trial(s): {} fitted, {} skipped (already fitted), {} failed in {:.1f} s; written {}\n",
                             report.trials.size(), report.ok, report.skipped, report.failed, report.wall_time_s,
                             cmd.output);
    for (const auto& r : report.trials) {
      if (r.status == "failed") std::cout << "  failed: " << r.trial_id << ": " << r.message << "\n";
    }
  }
  if (report.failed > 0) {
    std::cerr << "rockfit: " << report.failed << " trial(s) failed (listed above); the others are in " << cmd.output
              << ". Fix their input and run again with --resume to fit only what is missing.\n";
    return kExitNumerical;
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<BatchCommand>();
  CLI::App* app = root.add_subcommand("batch", "Fit every trial of a campaign manifest in parallel into one HDF5 file");
  app->add_option("MANIFEST", cmd->manifest, "Campaign manifest (TOML)")->required();
  app->add_option("-o,--output", cmd->output, "HDF5 file: /fits/<trial> and the tables /fit_summary/{trials,groups}")
      ->capture_default_str()
      ->group("Output");
  app->add_option("-j,--jobs", cmd->jobs, "Trials fitted at a time (0: all cores)")->capture_default_str();
  app->add_flag("--resume", cmd->resume,
                "Skip trials already fitted with the same settings (in the output or left by an interrupted run)");
  app->add_option("--trial", cmd->trials, "Fit only these trials (repeatable)");
  AddFitOptions(*app, cmd->fit, false);
  app->add_flag("--no-progress", cmd->no_progress, "No progress output on stderr")->group("Output");
  app->add_flag("--json", cmd->json,
                "Print one JSON object: manifest, output, trials (trial, status, message, epsilon, wall_s, simulations, "
                "warnings), ok, failed, skipped, jobs, wall_s")
      ->group("Output");
  app->callback([cmd] { SetExitCode(RunBatchCommand(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
