// Fits in rockfit's HDF5 files (DESIGN §8), next to io's /blocks, /trials and /summary:
//
//   /fits/<trial>     one trial's fit (attributes: status "ok" or "failed", message, block_id, position, b1_m,
//                     b2_m, h_m, method, termination, converged, epsilon_rad_s, epsilon_initial_rad_s, t_end_s,
//                     simulations, wall_time_s, simulations_per_second, model, settings_hash, settings (JSON),
//                     summary (the JSON of `rockfit fit --json`), rest_bias_rad_s_{x,y,z}, fit_schema_version)
//     parameters/     column table, one row per parameter: name, unit, value, lower, upper, fixed, std_error,
//                     identifiable, at_bound, start
//     time_s, w_measured_B_rad_s, w_simulated_B_rad_s   the window [t0, t_end]: measured ω (bias removed)
//                     and the model at the fitted parameters (N, N×3, N×3)
//     impacts/        the model's impact log in the window: time_s, kind
//     measured_impacts_time_s   the |ω_y| peaks detected in the recording
//     stages/         name, epsilon_rad_s, evaluations, wall_time_s, termination
//     warnings/       kind, parameter, message;  failures/ reason, count
//   /fit_summary/trials   one row per stored fit: trial_id, block_id, position, b1_m, b2_m, h_m, status,
//                     message, epsilon_rad_s, and per parameter <name> and <name>_std_error (NaN when missing)
//   /fit_summary/groups   per (block, position): n and, per fitted parameter and ε, mean and sample std (n − 1)
//
// A failed trial of a batch is a /fits/<trial> group with status "failed" and its message only.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/fitting/trial_fit.hpp"
#include "rockfit/io/hdf5_file.hpp"

namespace rockfit::fitting {

inline constexpr std::int64_t kFitSchemaVersion = 1;

struct FitLabels {
  std::string block_id;
  std::string position;
  double b1_m = 0.0, b2_m = 0.0, h_m = 0.0;
};

// Replaces /fits/<trial_id>.
void WriteFitHdf5(const io::hdf5::Group& root, const std::string& trial_id, const FitLabels& labels,
                  const TrialFit& fit, const std::string& settings_json, const std::string& settings_hash);
void WriteFailedFitHdf5(const io::hdf5::Group& root, const std::string& trial_id, const FitLabels& labels,
                        const std::string& message, const std::string& settings_hash);

// A fit read back.
struct StoredFit {
  std::string trial_id;
  FitLabels labels;
  std::string status;  // "ok" or "failed"
  std::string message;
  std::string settings_hash;
  std::string summary_json;
  std::vector<std::string> names;
  std::vector<double> value, lower, upper, std_error;
  std::vector<bool> fixed;
  double epsilon_rad_s = 0.0;
  double epsilon_initial_rad_s = 0.0;
  double t_end_s = 0.0;
  std::vector<double> time_s;
  std::vector<Eigen::Vector3d> w_measured_B;
  std::vector<Eigen::Vector3d> w_simulated_B;
  std::vector<double> impact_time_s;
  std::vector<std::string> impact_kind;
  std::vector<double> measured_impact_time_s;
  std::vector<std::string> warnings;
  std::optional<double> Value(const std::string& name) const;
};

// Trial ids under /fits (empty when there is none).
std::vector<std::string> ListFitsHdf5(const io::hdf5::Group& root);
// BadInput naming the file and the known trials when missing or malformed.
StoredFit ReadFitHdf5(const io::hdf5::Group& root, const std::string& trial_id);
// The settings hash of /fits/<trial_id>, none when missing (or not "ok").
std::optional<std::string> StoredSettingsHash(const io::hdf5::Group& root, const std::string& trial_id);

// Rebuilds /fit_summary from every /fits/* group.
void WriteFitTablesHdf5(const io::hdf5::Group& root);

}  // namespace rockfit::fitting
