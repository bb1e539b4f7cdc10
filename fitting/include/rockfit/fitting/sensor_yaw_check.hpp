// The sensor's turn about block z, read from the fitted motion where the mounting check could not fix it
// (fitting/README.md, "The turn about z from the fit").
//
// The mounting estimate (io/mounting_estimate.hpp) fixes the turn about block z from the axis of the fall before
// the first impact. A block released on a corner of its release edge falls about a tilted axis, and its roll β
// reads as a turn of up to β/sin α; there the estimate holds z at the mounting given. The fit models the roll, and
// a turned sensor does not move the fitted roll (on `synth` recordings rolled by 6 mrad with the sensor turned by
// 2° or 5°: β within 0.03 mrad, α within 0.2 mrad of the truth) but turns the whole measured rate away from the
// model's: ω_m ≈ Rz(ψ)·ω_s, the misfit growing as ψ·|ω|. The turn that maps the model onto the data best (weighted
// least squares over the nodes of (28), a rotation in the xy plane)
//
//   ψ = atan2(Σ w·(s_x·m_y − s_y·m_x), Σ w·(s_x·m_x + s_y·m_y))
//
// and (28) of the turned model say whether the sensor is turned: beyond kSensorYawWarningDeg, where turning the
// model lowers (28) to at most kSensorYawMaxEpsilonRatio of the fit's, the check warns and gives the mounting that
// would make the data agree (q_BS turned by −ψ about block z before the applied one). It only reports: the fitted
// values are those of the mounting applied.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/io/mounting.hpp"
#include "rockfit/io/mounting_estimate.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::fitting {

struct FitSummary;

// A turn about z smaller than this [deg] is not warned about: the mounting check's own warning threshold.
inline constexpr double kSensorYawWarningDeg = io::kMountingWarningDeg;
// The turn is warned about only where it lowers (28) to this fraction of the fit's or below: a turn that explains
// a fifth of the misfit is the sensor's, not the model error of a soft contact, whose lateral swing a turn of the
// rocking plane's rate does not reproduce (the MuJoCo studies, fitting/README.md).
inline constexpr double kSensorYawMaxEpsilonRatio = 0.8;

struct SensorYawCheck {
  bool available = false;             // a feasible fitted motion with rate in the xy plane
  double yaw_deg = 0.0;               // ψ: the data are the model turned by ψ about block z
  double epsilon_rad_s = 0.0;         // (28) of the fit
  double epsilon_turned_rad_s = 0.0;  // (28) of the model turned by ψ
  bool turned = false;                // |ψ| ≥ kSensorYawWarningDeg and (28) turned ≤ kSensorYawMaxEpsilonRatio × (28)
  std::string corrected_mounting;     // the applied mounting turned by −ψ about block z (Mounting::text())
};

// The check for the nodes of (28) and the model's ω_s at them (one per node), for the mounting that was applied.
SensorYawCheck CheckSensorYaw(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B,
                              const io::Mounting& applied);

// Where the recording's mounting check did not fix the turn about z (determined[2] false, an estimate made), runs
// the model once at the fit's result on its window and adds WarningKind::kSensorTurnedAboutZ when the check says
// the sensor is turned. Nothing otherwise.
void AttachSensorYawCheck(const Objective& objective, const io::Recording& recording, FitSummary* summary);

}  // namespace rockfit::fitting
