#include "metrics_options.hpp"

#include "rockfit/core/errors.hpp"

namespace rockfit::tools {

void AddMetricsOptions(CLI::App& app, MetricsArgs& args) {
  io::MetricsOptions& o = args.options;
  app.add_option("--min-prominence", o.correction.impacts.min_prominence_rad_s,
                 "Impacts: peaks of |ω_y| (|ω_x|) at least this prominent [rad/s]")
      ->capture_default_str()->group("Drift correction");
  app.add_option("--min-separation", o.correction.impacts.min_separation_s,
                 "Impacts: of two peaks closer than this, the lower is ringing [s]")
      ->capture_default_str()->group("Drift correction");
  app.add_option("--anchors", args.anchors,
                 "Drift at an impact: subsample (impact located inside the sample interval) or sample (the angle at the "
                 "|ω| peak sample, as in the paper)")
      ->capture_default_str()->check(CLI::IsMember({"subsample", "sample"}))->group("Drift correction");
  app.add_option("--peaks", o.avrf.max_peaks, "AVRF: number of peak inclinations after the first impact (the paper: 10)")
      ->capture_default_str()->group("AVRF");
  app.add_option("--min-peaks", o.avrf.min_peaks, "AVRF: fewer usable peaks is the status too_few_peaks")
      ->capture_default_str()->group("AVRF");
  app.add_option("--uplift", args.uplift,
                 "AVRF: COM uplift u(φ): com = b1·sin φ − h·(1 − cos φ) (correct), paper = h·sin φ − b1·(1 − cos φ) (as "
                 "printed in the paper's Sect. 3.2)")
      ->capture_default_str()->check(CLI::IsMember({"com", "paper"}))->group("AVRF");
}

io::MetricsOptions MakeMetricsOptions(const MetricsArgs& args) {
  io::MetricsOptions o = args.options;
  o.avrf.uplift = args.uplift == "paper" ? io::UpliftFormula::kPaperPrinted : io::UpliftFormula::kComUplift;
  o.correction.anchor_method = args.anchors == "sample" ? io::AnchorMethod::kSample : io::AnchorMethod::kSubsample;
  o.Validate();
  return o;
}

}  // namespace rockfit::tools
