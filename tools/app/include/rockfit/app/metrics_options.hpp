// Command-line options of drift correction and metrics shared by `correct`, `metrics`, `summary` and
// `plot euler` (defaults from io: impact_detection.hpp, drift_correction.hpp, avrf.hpp).
#pragma once


#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::app {

struct MetricsArgs {
  io::MetricsOptions options;
  std::string uplift = "com";
  std::string anchors = "subsample";
};
// Validated options; InvalidArgument naming the option.
io::MetricsOptions MakeMetricsOptions(const MetricsArgs& args);

}  // namespace rockfit::app
