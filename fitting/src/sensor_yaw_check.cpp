#include "rockfit/fitting/sensor_yaw_check.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::fitting {

SensorYawCheck CheckSensorYaw(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                              const io::Mounting& applied) {
  SensorYawCheck c;
  if (w_s_B.size() != nodes.size() || nodes.size() == 0) return c;
  // Σ w·(s × m)_z and Σ w·(s · m) over the xy components: the turn of the weighted least-squares fit m ≈ Rz(ψ)·s.
  double cross = 0.0, dot = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double w = nodes.weight_s[i];
    const Eigen::Vector3d& s = w_s_B[i];
    const Eigen::Vector3d& m = nodes.w_m_B[i];
    cross += w * (s.x() * m.y() - s.y() * m.x());
    dot += w * (s.x() * m.x() + s.y() * m.y());
  }
  if (!(dot > 0.0) || !std::isfinite(cross)) return c;  // no rate in the plane, or the model against the data
  const double yaw_rad = std::atan2(cross, dot);
  const Eigen::AngleAxisd turn(yaw_rad, Eigen::Vector3d::UnitZ());
  std::vector<Eigen::Vector3d> turned(w_s_B.size());
  for (std::size_t i = 0; i < w_s_B.size(); ++i) turned[i] = turn * w_s_B[i];
  c.epsilon_rad_s = TrajectoryError(nodes, w_s_B);
  c.epsilon_turned_rad_s = TrajectoryError(nodes, turned);
  if (!std::isfinite(c.epsilon_rad_s) || !std::isfinite(c.epsilon_turned_rad_s)) return c;
  c.available = true;
  c.yaw_deg = yaw_rad / io::kRadPerDeg;
  c.turned = std::abs(c.yaw_deg) >= kSensorYawWarningDeg &&
             c.epsilon_turned_rad_s <= kSensorYawMaxEpsilonRatio * c.epsilon_rad_s;
  // ω_B as read = R_BS,applied·R_BS,trueᵀ·ω_B = Rz(ψ)·ω_B, so R_BS,true = Rz(−ψ)·R_BS,applied.
  const Eigen::Quaterniond q_BS =
      (Eigen::Quaterniond(Eigen::AngleAxisd(-yaw_rad, Eigen::Vector3d::UnitZ())) * applied.q_BS()).normalized();
  c.corrected_mounting = io::Mounting::FromRotation(q_BS.toRotationMatrix()).text();
  return c;
}

void AttachSensorYawCheck(const Objective& objective, const io::Recording& recording, FitSummary* summary) {
  const io::MountingCheck& mounting = recording.mounting_check;
  if (!mounting.has_estimate() || mounting.determined[2] || !summary->feasible) return;
  const Objective window = objective.WithWindowEnd(summary->t_end_s);  // the fit's window, extended or not
  ErrorNodes nodes;
  ModelOutput output;
  if (!window.EvaluateDetailed(summary->parameters, &nodes, &output).feasible) return;
  const SensorYawCheck c = CheckSensorYaw(nodes, output.w_B, io::Mounting::Parse(recording.mounting));
  if (!c.turned) return;
  summary->warnings.push_back(
      {WarningKind::kSensorTurnedAboutZ, "",
       fmt::format("the sensor looks turned on the block by {:+.2f}° about block z: so turned, the fitted motion meets "
                   "the data ((28) {:.4g} → {:.4g} rad/s); the mounting check left that turn open (its message says "
                   "why). Give the mounting as --mounting={} (manifest: mounting = \"{}\") and fit again",
                   -c.yaw_deg, c.epsilon_rad_s, c.epsilon_turned_rad_s, c.corrected_mounting, c.corrected_mounting)});
}

}  // namespace rockfit::fitting
