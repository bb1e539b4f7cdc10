// Kinematics of the ZYX Euler angles of docs/design.md §2 (R_WB = Rz(φz)·Ry(φy)·Rx(φx), stored as (φz, φy, φx);
// conversions between angles and rotations are in attitude.hpp): body rates from angle rates and back.
#pragma once

#include <Eigen/Core>

namespace rockfit::io {

// Body angular velocity w_B [rad/s] from the angles (φz, φy, φx) and their rates (φ̇z, φ̇y, φ̇x):
//   ω_x = φ̇x − sin φy·φ̇z,  ω_y = cos φx·φ̇y + sin φx cos φy·φ̇z,  ω_z = −sin φx·φ̇y + cos φx cos φy·φ̇z.
Eigen::Vector3d BodyRatesFromEulerZyx(const Eigen::Vector3d& euler_zyx, const Eigen::Vector3d& euler_rates_zyx);

// The inverse: (φ̇z, φ̇y, φ̇x) from the angles and w_B,
//   φ̇y = cos φx·ω_y − sin φx·ω_z,  φ̇z = (sin φx·ω_y + cos φx·ω_z)/cos φy,  φ̇x = ω_x + tan φy·(sin φx·ω_y + cos φx·ω_z).
// Singular at φy = ±π/2 (gimbal lock), far outside rocking; there φ̇z and φ̇x are returned as 0 and the caller
// is expected not to rely on them.
Eigen::Vector3d EulerZyxRates(const Eigen::Vector3d& euler_zyx, const Eigen::Vector3d& w_B);

}  // namespace rockfit::io
