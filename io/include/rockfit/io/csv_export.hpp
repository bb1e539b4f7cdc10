// CSV exports of corrected recordings and campaign summaries (for spreadsheets and other tools). Written
// atomically; numbers in the shortest form that reads back to the same double; missing values empty.
#pragma once

#include <filesystem>
#include <vector>

#include "rockfit/io/campaign_summary.hpp"
#include "rockfit/io/recording.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::io {

// `path`: one row per sample —
//   time_s, w_x_rad_s, w_y_rad_s, w_z_rad_s, phi_z_raw_rad, phi_y_raw_rad, phi_x_raw_rad,
//   phi_z_corrected_rad, phi_y_corrected_rad, phi_x_corrected_rad, impact_y, anchor_x
// where impact_y / anchor_x are 1 on the sample that marked an impact of φ_y / an anchor of φ_x, else 0.
// `impacts_path`: one row per anchor — angle (phi_y or phi_x), time_s, sample_index, anchor_rad, source,
// omega_peak_rad_s — with the sub-sample impact times.
void WriteCorrectedCsv(const std::filesystem::path& path, const std::filesystem::path& impacts_path,
                       const Recording& recording, const MetricsSummary& metrics);

// `groups_path`: block_id, position, b1_m, b2_m, h_m, n_trials, n_opmf, opmf_mean, opmf_std, n_avrf, avrf_mean,
// avrf_std. `trials_path`: trial_id, block_id, position, b1_m, b2_m, h_m, status, opmf, avrf,
// lambda_equivalent, avrf_peaks_used, impacts, message.
void WriteSummaryCsv(const std::filesystem::path& groups_path, const std::filesystem::path& trials_path,
                     const CampaignSummary& summary);

}  // namespace rockfit::io
