// A simulated trajectory (core::Trajectory) as an HDF5 file, readable with h5py and MATLAB (docs/file-formats.md §6,
// which also lists the names of schema version 1).
//
// Layout (root attributes: schema "rockfit.simulation", rockfit_schema_version kTrajectorySchemaVersion, created_by);
// names carry their units and every numeric dataset a `units` attribute, as in every rockfit file:
//   /block        attributes b1_m, b2_m, h_m, mass_kg, density_kg_m3
//   /parameters   attributes alpha_rad, lambda, tau_edge_N_m_s, lambda_lat, lambda_lon, facet_tau_rule
//   /options      attributes rate_hz, stop, t_max_s, zeno_dt_s, rest_energy_height_m, gravity_m_s2,
//                 release_edge, rel_tol, abs_tol, event_time_tol_s, max_step_s
//   /result       attributes t_end_s, end_reason, message, wall_time_s, num_steps, num_evaluations
//   /samples      time_s (N), w_B_rad_s (N×3), q_WB (N×4, scalar first), euler_zyx_rad (N×3: φz, φy, φx),
//                 mode (N strings such as "V1V2", "V3", "rest")
//   /impacts      t_s (M), kind, contact_before, contact_after, status (M strings), w_minus_B_rad_s, w_plus_B_rad_s,
//                 w_minus_W_rad_s, w_plus_W_rad_s (M×3), tau_N_m_s (M), delta_energy_J (M)
//   /segments     t_begin_s, t_end_s (S), mode (S strings), min_normal_force_N (S), max_friction_ratio (S),
//                 energy_drift_rel (S)
//
// A response to ground motion (`rockfit respond`, WriteResponseHdf5) has the same layout, `created_by`
// "rockfit respond", and in addition:
//   /ground_motion  time_s (G), a_W_m_s2 (G×3) (the record as simulated: rotated and scaled), attributes
//                   dt_s, pga_horizontal_m_s2, pga_vertical_m_s2, and `sources` (strings) when given
//   /samples        a_g_W_m_s2 (N×3) (the ground acceleration at the sample times), tilt_rad (N)
//   /response       attributes overturned (0/1), t_overturn_s (NaN if not), peak_tilt_rad, t_peak_tilt_s,
//                   peak_rotation_rad, peak_rate_rad_s, critical_tilt_rad, num_impacts, max_friction_ratio,
//                   min_normal_force_N, max_discarded_rate_rad_s; dataset uplift_times_s (U)
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/core/response.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::io {

// 2: names with units and the root attribute rockfit_schema_version, as in every rockfit file (1: `schema_version`,
// `samples/t`, `impacts/omega_minus_B`, … without units in the names; still read by `plot response`).
inline constexpr int kTrajectorySchemaVersion = 2;
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
