// A simulated trajectory (core::Trajectory) as an HDF5 file, readable with h5py and MATLAB (DESIGN §8).
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
#pragma once

#include <filesystem>

#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::io {

inline constexpr int kTrajectorySchemaVersion = 1;
inline constexpr const char* kTrajectorySchemaName = "rockfit.simulation";

// Writes to a temporary file in the directory of `path` and renames it over `path` when complete, so a
// crash never leaves a half-written file and never damages an existing one. Throws OutputError.
void WriteTrajectoryHdf5(const std::filesystem::path& path, const core::Block& block,
                         const core::ModelParameters& params, const core::SimulationOptions& options,
                         const core::Trajectory& trajectory);

}  // namespace rockfit::io
