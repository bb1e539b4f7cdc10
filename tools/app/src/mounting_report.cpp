#include "rockfit/app/mounting_report.hpp"

#include <cmath>
#include <iostream>

#include <fmt/format.h>

#include "rockfit/app/block_args.hpp"
#include "rockfit/app/json_values.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/io/mounting_estimate.hpp"

namespace rockfit::app {

nlohmann::json MountingJson(const io::Recording& r) {
  const io::MountingCheck& c = r.mounting_check;
  const auto triple = [](const Eigen::Vector3d& v) {
    return nlohmann::json::array({OrNull(v.x()), OrNull(v.y()), OrNull(v.z())});
  };
  return {{"applied", r.mounting},
          {"given", c.given},
          {"estimated", c.estimated},
          {"status", io::ToString(c.status)},
          {"message", c.message},
          {"angles_deg", triple(c.angles_deg)},
          {"std_error_deg", triple(c.std_error_deg)},
          {"determined", {c.determined[0], c.determined[1], c.determined[2]}},
          {"disagreement_deg", OrNull(io::MountingDisagreementDeg(c))},
          {"release_tilt_rad", OrNull(c.release_tilt_rad)},
          {"release_tilt_std_error_rad", OrNull(c.release_tilt_std_error_rad)},
          {"turn_before_fall_deg", OrNull(c.turn_before_fall_deg)},
          {"warning", c.warning}};
}

std::string MountingText(const io::Recording& r) {
  const io::MountingCheck& c = r.mounting_check;
  const std::string applied = c.estimated ? fmt::format("auto from {} → {}", c.given, r.mounting) : r.mounting;
  if (!c.has_estimate()) {
    return c.status == io::MountingStatus::kNotChecked ? applied : fmt::format("{}  (not checked: {})", applied, c.message);
  }
  std::string angles;
  for (int i = 0; i < 3; ++i) {
    angles += fmt::format("{}{} {:+.2f}° ± {:.2f}°{}", i ? ", " : "", "xyz"[i], c.angles_deg[i], c.std_error_deg[i],
                          c.determined[static_cast<std::size_t>(i)] ? "" : " (open)");
  }
  return fmt::format("{}  (data vs given, about block {}; {})", applied, angles,
                     c.estimated ? "applied" : (c.warning.empty() ? "agree within 1°" : "NOT applied"));
}

void PrintMountingWarning(const io::Recording& r) {
  if (!r.mounting_check.warning.empty()) std::cerr << "rockfit: warning: " << r.mounting_check.warning << "\n";
}

}  // namespace rockfit::app
