#include "rockfit/fitting/window_extension.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "rockfit/core/checks.hpp"

namespace rockfit::fitting {

void WindowExtensionOptions::Validate() const {
  RequireAtLeast(max_extensions, 0, "fit option window_extension.max_extensions");
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
