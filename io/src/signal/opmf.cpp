#include "rockfit/io/opmf.hpp"

#include <cmath>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::io {

const char* ToString(OpmfStatus status) {
  switch (status) {
    case OpmfStatus::kOk: return "ok";
    case OpmfStatus::kNoImpact: return "no_impact";
    case OpmfStatus::kNoInPlaneMotion: return "no_in_plane_motion";
  }
  return "unknown";
}

bool FromString(std::string_view text, OpmfStatus* value) {
  static constexpr OpmfStatus kAll[] = {OpmfStatus::kOk, OpmfStatus::kNoImpact, OpmfStatus::kNoInPlaneMotion};
  return core::FromStringAmong(text, kAll, value);
}

OpmfResult ComputeOpmf(const std::vector<double>& t_s, const std::vector<Eigen::Vector3d>& euler_corrected_zyx,
                       bool has_impact, double first_impact_s, double last_impact_s) {
  if (t_s.size() != euler_corrected_zyx.size()) {
    throw InvalidArgument("ComputeOpmf: time and Euler angles differ in length");
  }
  OpmfResult result;
  if (!has_impact) {
    result.status = OpmfStatus::kNoImpact;
    result.message = "no impact was detected, so there is no motion after the first impact to measure";
    return result;
  }
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    if (t_s[i] < first_impact_s || t_s[i] > last_impact_s) continue;
    const double phi_y = std::abs(euler_corrected_zyx[i][1]);
    const double phi_x = std::abs(euler_corrected_zyx[i][2]);
    if (phi_y > result.max_abs_phi_y_rad) {
      result.max_abs_phi_y_rad = phi_y;
      result.t_phi_y_max_s = t_s[i];
    }
    if (phi_x > result.max_abs_phi_x_rad) {
      result.max_abs_phi_x_rad = phi_x;
      result.t_phi_x_max_s = t_s[i];
    }
  }
  if (!(result.max_abs_phi_y_rad > 0.0)) {
    result.status = OpmfStatus::kNoInPlaneMotion;
    result.message = "the corrected φ_y is zero between the first and the last impact; Φ = max|φ_x|/max|φ_y| is undefined";
    return result;
  }
  result.status = OpmfStatus::kOk;
  result.opmf = result.max_abs_phi_x_rad / result.max_abs_phi_y_rad;  // Sect. 3.2
  return result;
}

}  // namespace rockfit::io
