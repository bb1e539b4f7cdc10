// rockfit's HDF5 layout for recordings, drift correction, metrics and campaign summaries (docs/design.md §8). The full
// schema (names, shapes, units) is in io/README.md, "HDF5 layout". Writers take a group of an open file (use
// hdf5::Transaction for atomic rewrites); readers take a path. /fits belongs to the fitting library and
// /simulations to the simulator: these functions never touch them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/io/campaign_summary.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/manifest.hpp"
#include "rockfit/io/recording.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::io {

// Root attribute `rockfit_schema_version`. Readers accept files up to this version.
inline constexpr std::int64_t kHdf5SchemaVersion = 1;

// Sets the root attributes rockfit_schema_version and rockfit_version.
void WriteFileAttributes(const hdf5::Group& root, const std::string& rockfit_version);
// BadInput unless the root carries a schema version this rockfit can read.
void RequireSchemaVersion(const hdf5::Group& root);

// /blocks/<id>: attributes b1_m, b2_m, h_m, mass_kg, density_kg_m3, notes; dataset inertia_com_B_kg_m2 (3×3).
// Replaces an existing group of that id.
void WriteBlockHdf5(const hdf5::Group& root, const std::string& block_id, const core::Block& block,
                    const std::string& notes = "");

// What a trial is, besides its samples.
struct TrialLabels {
  std::string block_id;  // empty when the trial was processed without a block
  std::string position;
  std::string notes;
};

// /trials/<id>: the samples, the raw and corrected Euler angles, the detected impacts and the metrics with the
// options that produced them. Replaces an existing group of that id.
void WriteTrialHdf5(const hdf5::Group& root, const std::string& trial_id, const TrialLabels& labels,
                    const Recording& recording, const MetricsSummary& metrics, const MetricsOptions& options);

// The mounting of a recording on `group` (/trials/<id> and /fits/<id>): attributes mounting (applied, text),
// mounting_given, mounting_estimated (1 for --mounting auto), mounting_status, mounting_message,
// mounting_warning, mounting_disagreement_deg; datasets mounting_angles_deg and mounting_std_error_deg (3: about
// block x, y, z, the rotation from the given mounting to the data's, NaN without an estimate) and
// mounting_determined (3, 1 where the data fix that angle).
void WriteMountingHdf5(const hdf5::Group& group, const Recording& recording);

// A trial read back.
struct StoredTrial {
  std::string id;
  TrialLabels labels;
  Recording recording;  // raw samples; format "rockfit-hdf5"
  std::vector<Eigen::Vector3d> euler_corrected_zyx;
  std::vector<double> impact_times_s;        // anchors of φ_y
  std::vector<double> phi_x_anchor_times_s;  // anchors of φ_x
  MetricsStatus status = MetricsStatus::kOk;
  std::string message;
  std::optional<double> opmf;
  std::optional<double> avrf;
  std::optional<double> lambda_equivalent;
};

// Trial ids stored in the file (BadInput when it is not a rockfit file).
std::vector<std::string> ListTrialsHdf5(const std::filesystem::path& path);
// The trial `trial_id`; with an empty id the file must hold exactly one trial. BadInput with the known ids
// otherwise, and for missing datasets, wrong shapes, non-finite or non-increasing times.
StoredTrial ReadTrialHdf5(const std::filesystem::path& path, const std::string& trial_id);
// rockfit's own HDF5 as an input format: the raw recording of a trial (see ReadTrialHdf5).
Recording ReadRecordingHdf5(const std::filesystem::path& path, const std::string& trial_id);

// /summary/trials and /summary/groups: column tables (one 1-D dataset per column, same length), missing
// values NaN. Replaces an existing /summary.
void WriteSummaryHdf5(const hdf5::Group& root, const CampaignSummary& summary);
CampaignSummary ReadSummaryHdf5(const std::filesystem::path& path);

}  // namespace rockfit::io
