// `rockfit metrics PATH`: drift correction, OPMF and AVRF of one trial (paper Sect. 3, docs/design.md §6).
#include <iostream>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/metrics_document.hpp"
#include "rockfit/app/metrics_options.hpp"
#include "rockfit/app/mounting_report.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::tools {
namespace {

struct MetricsCommand {
  RecordingArgs input;
  BlockArgs block;
  MetricsArgs metrics;
  bool json = false;
};

std::string List(const std::vector<double>& values, const char* format) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + fmt::format(fmt::runtime(format), v);
  return out;
}

int RunMetrics(const MetricsCommand& cmd) {
  const TrialInput input = LoadTrialInput(cmd.input);
  std::optional<core::Block> block = MakeOptionalBlock(cmd.block);
  if (!block && input.manifest_block) block = input.manifest_block->ToBlock();
  if (!block) {
    throw InvalidArgument("the AVRF needs the block geometry: give --b1 --b2 --h with --density or --mass, or "
                          "--manifest FILE --block ID (or PATH a manifest with --trial ID)");
  }
  const io::MetricsOptions options = MakeMetricsOptions(cmd.metrics);
  const io::MetricsSummary m = io::ComputeTrialMetrics(input.recording, block, options);
  const io::Recording& rec = input.recording;

  std::vector<double> impact_times, x_anchor_times;
  for (const auto& a : m.correction.impacts_y) impact_times.push_back(a.t_s);
  for (const auto& a : m.correction.anchors_x) x_anchor_times.push_back(a.t_s);
  const int exit_code = m.ok() ? kExitOk : kExitNumerical;

  if (cmd.json) {
    PrintJson(MetricsJson(input.trial_id, rec, *block, options, m));
  } else {
    std::cout << fmt::format("trial      {}  ({}, {} Hz, {} samples, {:.2f} s)\n", input.trial_id, rec.source,
                             rec.rate_hz, rec.size(), rec.duration_s());
    std::cout << "mounting   " << MountingText(rec) << "\n";
    if (!impact_times.empty()) {
      std::cout << fmt::format("impacts    {} (first {:.3f} s, last {:.3f} s); φx anchored at {} ({} from |ω_x| peaks)\n",
                               impact_times.size(), impact_times.front(), impact_times.back(), x_anchor_times.size(),
                               m.correction.omega_x_peaks);
    } else {
      std::cout << "impacts    none\n";
    }
    if (m.opmf.ok()) {
      std::cout << fmt::format("OPMF       {:.4f}   (max|φx| {:.4g} rad / max|φy| {:.4g} rad after the first impact)\n",
                               m.opmf.opmf, m.opmf.max_abs_phi_x_rad, m.opmf.max_abs_phi_y_rad);
    } else {
      std::cout << fmt::format("OPMF       —        ({})\n", io::ToString(m.opmf.status));
    }
    if (m.avrf.ok()) {
      std::cout << fmt::format("AVRF       {:.4f}   (median of {} ratios from {} peak inclinations, uplift '{}')\n",
                               m.avrf.avrf, m.avrf.ratios.size(), m.avrf.peaks_used, io::ToString(options.avrf.uplift))
                << fmt::format("λ of (6)   {:.4f}   (b = b1 = {} m, θ = Θ_yy)\n", *m.avrf.lambda_equivalent, block->b1())
                << "ratios     " << List(m.avrf.ratios, "{:.4f}") << "\n";
    } else {
      std::cout << fmt::format("AVRF       —        ({})\n", io::ToString(m.avrf.status));
    }
    std::cout << "status     " << io::ToString(m.status) << (m.message.empty() ? "" : ": " + m.message) << "\n";
  }
  PrintMountingWarning(rec);
  for (const std::string& w : m.correction.warnings) std::cerr << "rockfit: warning: " << w << "\n";
  if (exit_code != kExitOk) {
    std::cerr << "rockfit: " << m.message
              << "\nCheck the recording with `rockfit plot euler`; thresholds: --min-prominence, --min-separation, "
                 "--min-peaks.\n";
  }
  return exit_code;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<MetricsCommand>();
  CLI::App* app = root.add_subcommand(
      "metrics",
      "OPMF and AVRF of one trial (paper Sect. 3.2): detect the impacts (peaks of |ω_y|), correct the drift of φ_y "
      "and φ_x, then Φ = max|φx|/max|φy| after the first impact and the AVRF as the median of √(u_(i+1)/u_i) over "
      "the first ten peak inclinations, with λ of (6) for the same AVRF");
  AddRecordingOptions(*app, cmd->input);
  AddBlockOptions(*app, cmd->block);
  AddMetricsOptions(*app, cmd->metrics);
  app->add_flag("--json", cmd->json,
                "Print one JSON object: opmf, avrf, avrf_ratios, avrf_peaks_used, lambda_equivalent, impact_times, "
                "status (ok, no_impact, no_in_plane_motion, too_few_peaks, invalid_uplift), message, opmf_status, "
                "avrf_status, max_abs_phi_x, max_abs_phi_y, avrf_peak_times, avrf_peak_angles, phi_x_anchor_times, "
                "trial, source, format, rate_hz, samples, uplift_formula, anchor_method, block, mounting (as `inspect --json` "
                "mounting_check), warnings, units; "
                "missing values are null");
  app->footer("Exit codes: 0 both metrics computed; 1 bad arguments; 2 unreadable recording or manifest; 3 a metric "
              "has no value (the status says why; the output is still printed).");
  app->callback([cmd] { SetExitCode(RunMetrics(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
