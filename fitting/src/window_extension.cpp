#include "rockfit/fitting/window_extension.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/checks.hpp"

namespace rockfit::fitting {

void WindowExtensionOptions::Validate() const {
  RequireAtLeast(max_extensions, 0, "fit option window_extension.max_extensions");
  RequireAtLeast(lambda_lon_scan_points, 0, "fit option window_extension.lambda_lon_scan_points");
}

ParameterSet StartOnLongerWindow(const Objective& longer, const ParameterSet& previous,
                                 const WindowExtensionOptions& options) {
  if (options.lambda_lon_scan_points == 0 || !longer.IsFree(ParameterId::kLambdaLon)) return previous;
  ParameterSet best = previous;
  const Evaluation at_previous = longer.Evaluate(previous);
  double best_epsilon = at_previous.feasible ? at_previous.epsilon_rad_s : std::numeric_limits<double>::infinity();
  ParameterSet trial = previous;
  if (longer.IsFree(ParameterId::kLambdaLat)) {
    const Parameter& lat = trial[ParameterId::kLambdaLat];
    trial[ParameterId::kLambdaLat].value = std::clamp(0.0, lat.lower, lat.upper);
  }
  const Parameter& lon = previous[ParameterId::kLambdaLon];
  const int n = options.lambda_lon_scan_points;
  for (int i = 0; i < n; ++i) {
    trial[ParameterId::kLambdaLon].value =
        n == 1 ? 0.5 * (lon.lower + lon.upper) : lon.lower + (lon.upper - lon.lower) * i / (n - 1);
    const Evaluation e = longer.Evaluate(trial);
    if (e.feasible && e.epsilon_rad_s < best_epsilon) {
      best_epsilon = e.epsilon_rad_s;
      best = trial;
    }
  }
  return best;
}

std::string WindowReportJson(const WindowReport& report) {
  return nlohmann::json{{"first_t_end", report.first_t_end_s},
                        {"t_end", report.t_end_s},
                        {"extensions", report.extensions},
                        {"extensions_tried", report.extensions_tried},
                        {"tried_t_end", report.tried_t_end_s},
                        {"reason", report.reason}}
      .dump();
}

std::string WindowReportText(const WindowReport& report) {
  std::string text = fmt::format("ends at {:.4f} s", report.t_end_s);
  if (report.extensions > 0) {
    text += fmt::format(", extended from {:.4f} s by {} later return impact(s)", report.first_t_end_s, report.extensions);
  } else if (report.extensions_tried > 0) {
    text += fmt::format(", the first window (longer windows tried: {})", report.extensions_tried);
  }
  return report.reason.empty() ? text : text + ": " + report.reason;
}

}  // namespace rockfit::fitting
