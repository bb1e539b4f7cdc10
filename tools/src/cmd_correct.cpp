// `rockfit correct PATH -o OUT`: drift correction of the Euler angles (paper Sect. 3.1, docs/design.md §6), written as
// rockfit HDF5 (/trials/<id>, with the raw and corrected angles, the impacts and the metrics) or as CSV.
#include <algorithm>
#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/metrics_options.hpp"
#include "rockfit/app/output_kind.hpp"
#include "rockfit/app/mounting_report.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/csv_export.hpp"
#include "rockfit/io/hdf5_transaction.hpp"

namespace rockfit::tools {
namespace {

struct CorrectCommand {
  RecordingArgs input;
  BlockArgs block;
  MetricsArgs metrics;
  std::string output;
  std::string trial_name;
  bool json = false;
};

// OUT.csv → OUT_impacts.csv
std::filesystem::path ImpactsPathFor(const std::filesystem::path& output) {
  return output.parent_path() / (output.stem().string() + "_impacts.csv");
}

int RunCorrect(const CorrectCommand& cmd) {
  const OutputKind kind = OutputKindFor(cmd.output);
  const io::MetricsOptions options = MakeMetricsOptions(cmd.metrics);
  const TrialInput input = LoadTrialInput(cmd.input);
  PrintMountingWarning(input.recording);
  std::optional<core::Block> block = MakeOptionalBlock(cmd.block);
  std::string block_id = cmd.block.block_id;
  if (!block && input.manifest_block) {
    block = input.manifest_block->ToBlock();
    block_id = input.manifest_block->id;
  }
  if (block && block_id.empty()) block_id = "block";
  const std::string trial_id = cmd.trial_name.empty() ? input.trial_id : TrialNameFrom(cmd.trial_name);
  const io::MetricsSummary m = io::ComputeTrialMetrics(input.recording, block, options);
  const io::DriftCorrection& c = m.correction;

  if (c.impacts_y.empty()) {
    if (cmd.json) PrintJson({{"trial", trial_id}, {"status", "no_impact"}, {"output", nullptr}, {"impacts", 0}});
    std::cerr << fmt::format("rockfit: no impact found in {} (no peak of |ω_y| with prominence ≥ {:g} rad/s), so there "
                             "is nothing to anchor the correction; nothing was written. Check the recording with "
                             "`rockfit inspect`, or lower --min-prominence.\n",
                             input.recording.source, options.correction.impacts.min_prominence_rad_s);
    return kExitNumerical;
  }

  std::filesystem::path impacts_output;
  if (kind == OutputKind::kHdf5) {
    std::vector<std::string> replaced{"/trials/" + trial_id};
    if (block) replaced.push_back("/blocks/" + block_id);
    io::hdf5::Transaction tx(cmd.output, replaced);
    io::WriteFileAttributes(tx.Root(), ROCKFIT_VERSION);
    io::TrialLabels labels = input.labels;
    if (block) {
      io::WriteBlockHdf5(tx.Root(), block_id, *block, input.manifest_block ? input.manifest_block->notes : "");
      labels.block_id = block_id;
    }
    io::WriteTrialHdf5(tx.Root(), trial_id, labels, input.recording, m, options);
    tx.Commit();
  } else {
    impacts_output = ImpactsPathFor(cmd.output);
    io::WriteCorrectedCsv(cmd.output, impacts_output, input.recording, m);
  }

  double max_drift_y = 0.0, max_drift_x = 0.0;
  for (const auto& a : c.impacts_y) max_drift_y = std::max(max_drift_y, std::abs(a.value_rad));
  for (const auto& a : c.anchors_x) max_drift_x = std::max(max_drift_x, std::abs(a.value_rad));
  std::vector<double> impact_times;
  for (const auto& a : c.impacts_y) impact_times.push_back(a.t_s);
  if (cmd.json) {
    nlohmann::json out;
    out["trial"] = trial_id;
    out["status"] = "ok";
    out["output"] = cmd.output;
    out["impacts_output"] = impacts_output.empty() ? nlohmann::json() : nlohmann::json(impacts_output.string());
    out["samples"] = input.recording.size();
    out["impacts"] = c.impacts_y.size();
    out["impact_times"] = impact_times;
    out["phi_x_anchors"] = c.anchors_x.size();
    out["omega_x_peaks"] = c.omega_x_peaks;
    out["max_drift_phi_y"] = max_drift_y;
    out["max_drift_phi_x"] = max_drift_x;
    out["anchor_method"] = io::ToString(options.correction.anchor_method);
    out["warnings"] = c.warnings;
    out["units"] = {{"impact_times", "s"}, {"max_drift_phi_y", "rad"}, {"max_drift_phi_x", "rad"}};
    PrintJson(out);
  } else {
    std::cout << fmt::format("trial     {}  ({} samples, {} Hz)\n", trial_id, input.recording.size(),
                             input.recording.rate_hz)
              << fmt::format("impacts   {} between {:.3f} s and {:.3f} s\n", c.impacts_y.size(), impact_times.front(),
                             impact_times.back())
              << fmt::format("φy drift  up to {:.4g} rad removed at the impacts\n", max_drift_y)
              << fmt::format("φx drift  up to {:.4g} rad removed at {} anchors ({} from |ω_x| peaks)\n", max_drift_x,
                             c.anchors_x.size(), c.omega_x_peaks)
              << "written   " << cmd.output << (impacts_output.empty() ? "" : ", " + impacts_output.string()) << "\n";
  }
  for (const std::string& w : c.warnings) std::cerr << "rockfit: warning: " << w << "\n";
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<CorrectCommand>();
  CLI::App* app = root.add_subcommand(
      "correct",
      "Drift correction of the Euler angles as in the paper (Sect. 3.1): the impacts are the peaks of |ω_y| where the "
      "gyro shows φ_y = 0; φ_y minus the piecewise-linear line through its values at the impacts; φ_x likewise at the "
      "peaks of |ω_x|, and at the impacts where ω_x has none (planar rocking). Writes raw and corrected angles and "
      "the impacts as rockfit HDF5 or CSV.");
  AddRecordingOptions(*app, cmd->input);
  app->add_option("-o,--output", cmd->output,
                  "OUT.h5 (adds or replaces /trials/<id>, keeps everything else in the file) or OUT.csv (one row per "
                  "sample, and OUT_impacts.csv with the impacts)")
      ->required()
      ->group("Output");
  app->add_option("--name", cmd->trial_name, "Trial id in the output (default: --trial or the input's file name)")
      ->group("Output");
  AddBlockOptions(*app, cmd->block);
  AddMetricsOptions(*app, cmd->metrics);
  app->add_flag("--json", cmd->json,
                "Print one JSON object: trial, status, output, impacts_output, samples, impacts, impact_times, "
                "phi_x_anchors, omega_x_peaks, max_drift_phi_y, max_drift_phi_x, anchor_method, warnings, units");
  app->footer("A block (optional) adds the AVRF to the stored metrics. Exit codes: 0 written; 1 bad arguments; 2 "
              "unreadable recording; 3 no impact found (nothing written); 4 cannot write the output.");
  app->callback([cmd] { SetExitCode(RunCorrect(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
