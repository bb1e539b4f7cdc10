// A simulated trajectory (core::Trajectory) as an HDF5 file, readable with h5py and MATLAB (docs/design.md §8).
//
// Layout (schema "rockfit.simulation", version kTrajectorySchemaVersion, attributes on the root group):
//   /block        attributes b1_m, b2_m, h_m, mass_kg, density_kg_m3
//   /parameters   attributes alpha_rad, lambda, tau_edge_N_m_s, lambda_lat, lambda_lon, facet_tau_rule
//   /options      attributes rate_hz, stop, t_max_s, zeno_dt_s, rest_energy_height_m, gravity_m_s2,
//                 release_edge, rel_tol, abs_tol, event_time_tol_s, max_step_s
//   /result       attributes t_end_s, end_reason, message, wall_time_s, num_steps, num_evaluations
//   /samples      t (N) [s], w_B (N×3) [rad/s], q_WB (N×4, scalar first), euler_zyx (N×3: φz, φy, φx) [rad],
//                 mode (N strings such as "V1V2", "V3", "rest")
//   /impacts      t (M) [s], kind, contact_before, contact_after, status (M strings), omega_minus_B,
//                 omega_plus_B, omega_minus_W, omega_plus_W (M×3) [rad/s], tau (M) [N·m·s], delta_energy (M) [J]
//   /segments     t_begin, t_end (S) [s], mode (S strings), min_normal_force (S) [N], max_friction_ratio (S),
//                 energy_drift_rel (S)
// Every dataset has a `units` attribute ("1" for dimensionless numbers, "" for strings).
//
// A response to ground motion (`rockfit respond`, WriteResponseHdf5) has the same layout, `created_by`
// "rockfit respond", and in addition:
//   /ground_motion  t (G) [s], a_W (G×3) [m/s²] (the record as simulated: rotated and scaled), attributes
//                   dt_s, pga_horizontal_m_s2, pga_vertical_m_s2, and `sources` (strings) when given
//   /samples        a_g_W (N×3) [m/s²] (the ground acceleration at the sample times), tilt (N) [rad]
//   /response       attributes overturned (0/1), t_overturn_s (NaN if not), peak_tilt_rad, t_peak_tilt_s,
//                   peak_rotation_rad, peak_rate_rad_s, critical_tilt_rad, num_impacts, max_friction_ratio,
//                   min_normal_force_N; dataset uplift_times (U) [s]
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/core/response.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::io {

inline constexpr int kTrajectorySchemaVersion = 1;
inline constexpr const char* kTrajectorySchemaName = "rockfit.simulation";

// Writes to a temporary file in the directory of `path` and renames it over `path` when complete, so a
// crash never leaves a half-written file and never damages an existing one. Throws OutputError.
void WriteTrajectoryHdf5(const std::filesystem::path& path, const core::Block& block,
                         const core::ModelParameters& params, const core::SimulationOptions& options,
                         const core::Trajectory& trajectory);

// The same for a response to ground motion (layout above), written the same way.
void WriteResponseHdf5(const std::filesystem::path& path, const core::Block& block, const core::ModelParameters& params,
                       const core::SimulationOptions& options, const core::Response& response,
                       const core::GroundMotion& ground, const std::vector<std::string>& sources);

}  // namespace rockfit::io
