#include "rockfit/app/metrics_options.hpp"

#include "rockfit/core/errors.hpp"

namespace rockfit::app {


io::MetricsOptions MakeMetricsOptions(const MetricsArgs& args) {
  io::MetricsOptions o = args.options;
  o.avrf.uplift = args.uplift == "paper" ? io::UpliftFormula::kPaperPrinted : io::UpliftFormula::kComUplift;
  o.correction.anchor_method = args.anchors == "sample" ? io::AnchorMethod::kSample : io::AnchorMethod::kSubsample;
  o.Validate();
  return o;
}

}  // namespace rockfit::app
