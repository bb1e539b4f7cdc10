#include "rockfit/app/metrics_options.hpp"

#include "rockfit/core/errors.hpp"

namespace rockfit::app {

io::MetricsOptions MakeMetricsOptions(const MetricsArgs& args) {
  io::MetricsOptions o = args.options;
  if (!io::FromString(args.uplift, &o.avrf.uplift)) {
    throw InvalidArgument("the uplift formula is com (the height gained by the COM) or paper (as printed in the "
                          "paper's Sect. 3.2), got '" + args.uplift + "'");
  }
  if (!io::FromString(args.anchors, &o.correction.anchor_method)) {
    throw InvalidArgument("the drift anchors are subsample (the impact inside the sample interval) or sample (the "
                          "angle at the |ω| peak sample, as in the paper), got '" + args.anchors + "'");
  }
  o.Validate();
  return o;
}

}  // namespace rockfit::app
