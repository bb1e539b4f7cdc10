// `rockfit summary MANIFEST`: OPMF and AVRF of every trial of a campaign and their statistics per block and
// position (paper Sect. 3.2, Fig. 6; docs/design.md §6).
#include <algorithm>
#include <iostream>

#include <fmt/format.h>

#include "rockfit/app/campaign_run.hpp"
#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/metrics_options.hpp"
#include "rockfit/app/output_kind.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/csv_export.hpp"
#include "rockfit/io/hdf5_transaction.hpp"

namespace rockfit::tools {
namespace {

struct SummaryCommand {
  std::string manifest;
  std::string output;
  MetricsArgs metrics;
  bool json = false;
};


std::string Cell(const std::optional<double>& v, int decimals) {
  return v ? fmt::format("{:.{}f}", *v, decimals) : std::string("—");
}

std::string MeanStd(const std::optional<double>& mean, const std::optional<double>& stdev, std::size_t n) {
  if (!mean) return "—";
  return fmt::format("{:.4f} ± {} ({})", *mean, stdev ? fmt::format("{:.4f}", *stdev) : std::string("—"), n);
}

// "x,y,z  +0.01 -0.02 +3.00", "auto  +0.01 -0.02 +3.00" (the estimate applied), "x,y,z  —" without an estimate.
std::string MountingCell(const io::TrialRow& t) {
  const io::MountingCheck& c = t.mounting_check;
  const std::string name = c.estimated ? std::string("auto") : t.mounting;
  if (!c.has_estimate()) return name + "  —";
  return fmt::format("{}  {:+.2f} {:+.2f} {:+.2f}{}", name, c.angles_deg.x(), c.angles_deg.y(), c.angles_deg.z(),
                     c.warning.empty() ? "" : "  !");
}

void PrintTables(const io::CampaignSummary& s) {
  std::cout << fmt::format("{:<16} {:<8} {:<4} {:<15} {:>7} {:>7} {:>7} {:>5}  {}\n", "trial", "block", "pos",
                           "status", "OPMF", "AVRF", "λ (6)", "peaks", "mounting (data vs given: x, y, z [°])");
  for (const io::TrialRow& t : s.trials) {
    std::cout << fmt::format("{:<16} {:<8} {:<4} {:<15} {:>7} {:>7} {:>7} {:>5}  {}\n", t.trial_id, t.block_id,
                             t.position, io::ToString(t.status), Cell(t.opmf, 4), Cell(t.avrf, 4), Cell(t.lambda_equivalent, 3),
                             t.avrf_peaks_used, MountingCell(t));
  }
  std::cout << "\n"
            << fmt::format("{:<8} {:<4} {:>7} {:>3}  {:<26} {:<26}\n", "block", "pos", "b2 [m]", "n",
                           "OPMF mean ± std (n)", "AVRF mean ± std (n)");
  for (const io::GroupRow& g : s.groups) {
    std::cout << fmt::format("{:<8} {:<4} {:>7.4f} {:>3}  {:<26} {:<26}\n", g.block_id, g.position, g.b2_m, g.n_trials,
                             MeanStd(g.opmf_mean, g.opmf_std, g.n_opmf), MeanStd(g.avrf_mean, g.avrf_std, g.n_avrf));
  }
}

int RunSummary(const SummaryCommand& cmd) {
  const io::MetricsOptions options = MakeMetricsOptions(cmd.metrics);
  const io::Manifest manifest = io::ReadManifest(cmd.manifest);
  if (manifest.trials.empty()) throw BadInput(fmt::format("{}: the manifest has no [[trials]]", cmd.manifest));

  std::optional<OutputKind> kind;
  if (!cmd.output.empty()) kind = OutputKindFor(cmd.output);

  CampaignRun run;
  std::vector<std::string> written;
  if (kind == OutputKind::kHdf5) {
    std::vector<std::string> replaced{"/summary"};
    for (const auto& b : manifest.blocks) replaced.push_back("/blocks/" + b.id);
    for (const auto& t : manifest.trials) replaced.push_back("/trials/" + t.id);
    io::hdf5::Transaction tx(cmd.output, replaced);
    io::WriteFileAttributes(tx.Root(), ROCKFIT_VERSION);
    for (const auto& b : manifest.blocks) io::WriteBlockHdf5(tx.Root(), b.id, b.ToBlock(), b.notes);
    run = RunCampaign(manifest, options,
                      [&](const io::TrialSpec& trial, const io::BlockSpec& block, const io::Recording& recording,
                          const io::MetricsSummary& metrics) {
                        io::WriteTrialHdf5(tx.Root(), trial.id, {block.id, trial.position, trial.notes}, recording,
                                           metrics, options);
                      });
    io::WriteSummaryHdf5(tx.Root(), run.summary);
    tx.Commit();
    written.push_back(cmd.output);
  } else {
    run = RunCampaign(manifest, options);
    if (kind == OutputKind::kCsv) {
      const std::filesystem::path groups = cmd.output;
      const std::filesystem::path trials = groups.parent_path() / (groups.stem().string() + "_trials.csv");
      io::WriteSummaryCsv(groups, trials, run.summary);
      written = {groups.string(), trials.string()};
    }
  }

  if (cmd.json) {
    nlohmann::json out;
    out["manifest"] = cmd.manifest;
    out["outputs"] = written;
    out["load_errors"] = run.load_errors;
    out["trials"] = nlohmann::json::array();
    for (const io::TrialRow& t : run.summary.trials) {
      out["trials"].push_back({{"trial_id", t.trial_id}, {"block_id", t.block_id}, {"position", t.position},
                               {"b1", t.b1_m}, {"b2", t.b2_m}, {"h", t.h_m}, {"status", io::ToString(t.status)},
                               {"message", t.message}, {"opmf", OrNull(t.opmf)}, {"avrf", OrNull(t.avrf)},
                               {"lambda_equivalent", OrNull(t.lambda_equivalent)},
                               {"avrf_peaks_used", t.avrf_peaks_used}, {"impacts", t.impacts},
                               {"mounting", t.mounting}, {"mounting_estimated", t.mounting_check.estimated},
                               {"mounting_status", io::ToString(t.mounting_check.status)},
                               {"mounting_angles_deg",
                                {OrNull(t.mounting_check.angles_deg.x()), OrNull(t.mounting_check.angles_deg.y()),
                                 OrNull(t.mounting_check.angles_deg.z())}},
                               {"mounting_warning", t.mounting_check.warning}});
    }
    out["groups"] = nlohmann::json::array();
    for (const io::GroupRow& g : run.summary.groups) {
      out["groups"].push_back({{"block_id", g.block_id}, {"position", g.position}, {"b1", g.b1_m}, {"b2", g.b2_m},
                               {"h", g.h_m}, {"n_trials", g.n_trials}, {"n_opmf", g.n_opmf},
                               {"opmf_mean", OrNull(g.opmf_mean)}, {"opmf_std", OrNull(g.opmf_std)},
                               {"n_avrf", g.n_avrf}, {"avrf_mean", OrNull(g.avrf_mean)},
                               {"avrf_std", OrNull(g.avrf_std)}});
    }
    out["units"] = {{"b1", "m"}, {"b2", "m"}, {"h", "m"}, {"opmf", "1"}, {"avrf", "1"}, {"lambda_equivalent", "1"}};
    PrintJson(out);
  } else {
    PrintTables(run.summary);
    for (const auto& path : written) std::cout << "written " << path << "\n";
  }
  for (const io::TrialRow& t : run.summary.trials) {
    if (!t.mounting_check.warning.empty()) {
      std::cerr << "rockfit: warning: trial " << t.trial_id << ": " << t.mounting_check.warning << "\n";
    }
  }
  if (run.load_errors > 0) {
    for (const io::TrialRow& t : run.summary.trials) {
      if (t.status == io::MetricsStatus::kLoadError) std::cerr << "rockfit: trial " << t.trial_id << ": " << t.message << "\n";
    }
    std::cerr << fmt::format("rockfit: {} of {} trials could not be read (listed above, status load_error); fix their "
                             "files or entries in {} and run again\n",
                             run.load_errors, run.summary.trials.size(), cmd.manifest);
    return kExitBadInput;
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<SummaryCommand>();
  CLI::App* app = root.add_subcommand(
      "summary",
      "OPMF and AVRF of every trial of a campaign manifest, and per (block, position) the number of trials, the mean "
      "and the sample standard deviation of both (the paper's Fig. 6)");
  app->add_option("MANIFEST", cmd->manifest, "Campaign manifest (TOML): [[blocks]] and [[trials]]")->required();
  app->add_option("-o,--output", cmd->output,
                  "OUT.h5: /blocks, /trials (samples, corrected angles, impacts, metrics) and /summary; other groups "
                  "already in the file (e.g. /fits) are kept. OUT.csv: the per-group table, and OUT_trials.csv")
      ->group("Output");
  AddMetricsOptions(*app, cmd->metrics);
  app->add_flag("--json", cmd->json,
                "Print one JSON object: manifest, outputs, load_errors, trials (trial_id, block_id, position, b1, b2, h, "
                "status, message, opmf, avrf, lambda_equivalent, avrf_peaks_used, impacts, mounting, mounting_estimated, "
                "mounting_status, mounting_angles_deg, mounting_warning), groups (block_id, "
                "position, b1, b2, h, n_trials, n_opmf, opmf_mean, opmf_std, n_avrf, avrf_mean, avrf_std), units; "
                "missing values are null");
  app->footer("Exit codes: 0 every trial was read (their metric statuses are in the table); 1 bad arguments; 2 bad "
              "manifest, or some trials could not be read (the others are still summarised and written); 4 cannot "
              "write the output.");
  app->callback([cmd] { SetExitCode(RunSummary(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
