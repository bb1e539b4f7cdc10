// Out-of-plane motion factor (paper Sect. 3.2, docs/design.md §6):  Φ = max|φ_x| / max|φ_y|  over the corrected
// Euler angles after the first impact. The maxima are taken up to the last detected impact: after it the
// drift is no longer tied down (the correction is constant there) and the block is at rest or nearly so.
#pragma once

#include <string_view>

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rockfit::io {

enum class OpmfStatus { kOk, kNoImpact, kNoInPlaneMotion };
// "ok", "no_impact", "no_in_plane_motion".
const char* ToString(OpmfStatus status);
bool FromString(std::string_view text, OpmfStatus* value);  // the inverse of ToString

struct OpmfResult {
  OpmfStatus status = OpmfStatus::kNoImpact;
  std::string message;            // why there is no value (empty when ok)
  double opmf = 0.0;              // Φ, meaningful only when ok
  double max_abs_phi_x_rad = 0.0;
  double max_abs_phi_y_rad = 0.0;
  double t_phi_x_max_s = 0.0;     // where the maxima are
  double t_phi_y_max_s = 0.0;
  bool ok() const { return status == OpmfStatus::kOk; }
};

// `euler_corrected_zyx` holds (φz, φy, φx); only samples with first_impact_s ≤ t ≤ last_impact_s count.
// Without an impact (has_impact false) the status is kNoImpact.
OpmfResult ComputeOpmf(const std::vector<double>& t_s, const std::vector<Eigen::Vector3d>& euler_corrected_zyx,
                       bool has_impact, double first_impact_s, double last_impact_s);

}  // namespace rockfit::io
