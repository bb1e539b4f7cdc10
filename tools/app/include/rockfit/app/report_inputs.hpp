// The campaign files a report is built from (`rockfit report`, report_builder.hpp), read into plain data. No
// HTML and no command-line parsing here. A file that cannot be read whole is not fatal: the part that failed is
// recorded as a `Gap` (what is missing and why), which the page shows in words.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/fitting/predictive_check.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/campaign_summary.hpp"

namespace rockfit::app {

// The files of one report. `summary` is required; every other file is optional.
struct ReportInputs {
  std::filesystem::path summary;                 // `rockfit summary -o` (/summary, /trials)
  std::filesystem::path fits;                    // `rockfit batch -o` (/fits, /summary/fits)
  std::filesystem::path validation;              // `rockfit validate -o` (/validation)
  std::vector<std::filesystem::path> fragility;  // `rockfit fragility -o` (/fragility)
  std::vector<std::filesystem::path> responses;  // `rockfit respond --format hdf5 -o`
};

// Something the report cannot show, and why (shown on the page and returned to the caller).
struct Gap {
  std::string where;  // "trial block1-A-2", "fragility file F.h5", …
  std::string what;   // a sentence
};

// One input file for the provenance table.
struct InputFile {
  std::string role;  // "summary", "fits", …
  std::filesystem::path path;
  std::uintmax_t size_bytes = 0;
  std::string content_hash;    // FNV-1a 64 of the bytes, 16 hex digits
  std::string rockfit_version; // root attribute rockfit_version (empty when absent)
  std::string settings_hash;   // of a fragility study (/fragility attribute settings_hash), else empty
};

// The fit of one trial as `rockfit batch` stored it (/fits/<trial>).
struct TrialFit {
  fitting::StoredFitLabels labels;
  fitting::StoredParameters parameters;
  std::vector<std::string> warnings;  // "kind: message"
  std::vector<double> t_s;            // nodes of (28)
  std::vector<Eigen::Vector3d> w_measured_B, w_simulated_B;  // [rad/s]; simulated empty when the model failed
  std::vector<double> impact_t_s;
  std::string termination;
  std::string settings;  // canonical text of every setting that changed the result (hash: labels.settings_hash)
};

// Drift-corrected angles of one trial (/trials/<id> of the summary file), for the paper's Fig. 5.
struct TrialAngles {
  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> raw_zyx_rad, corrected_zyx_rad;  // (φz, φy, φx)
  std::vector<double> impact_t_s;
};

struct ReportTrial {
  io::TrialRow row;                   // from /summary/trials
  std::optional<TrialAngles> angles;  // absent when /trials/<id> cannot be read (see gaps)
  std::optional<TrialFit> fit;        // absent when the fits file has no /fits/<id>
};

// One fragility curve set of one block (`/fragility/blocks/<id>`).
struct FragilityLimitState {
  std::string name;
  std::vector<double> intensity, probability, lower_95, upper_95;  // Clopper–Pearson band
  std::string curve_status, curve_message;  // of the lognormal fit ("ok", "separated", …)
  bool curve_ok = false;                     // curve_status is quake::LognormalFitStatus::kOk
  double median = 0.0, beta = 0.0;           // the lognormal curve Φ(ln(x/θ)/β); meaningful when curve_ok
};

// Whether a stored lognormal-fit status (`curve/status`) is ok; an empty one is not. BadInput naming `where` for a
// name that is no quake::LognormalFitStatus.
bool CurveStatusIsOk(const std::string& stored, const std::string& where);
struct FragilityBlock {
  std::string file, block_id;
  bool intensity_is_pga_g = true;
  std::vector<FragilityLimitState> limit_states;
};

// A response to ground motion (`rockfit respond --format hdf5`).
struct ResponseHistory {
  std::string file, block_id;  // block_id: the campaign block of the same size, or empty
  std::vector<double> t_s, tilt_rad, ground_t_s;
  std::vector<Eigen::Vector3d> w_B_rad_s, ground_a_W_g;
  double critical_tilt_rad = 0.0, peak_tilt_rad = 0.0;
  bool overturned = false;
  std::string end_reason;
};

struct ReportData {
  io::CampaignSummary summary;
  std::vector<ReportTrial> trials;                  // the summary's trials, in its order
  std::vector<fitting::GroupSummary> fit_groups;    // /summary/fits/per_group (empty without)
  std::optional<fitting::ValidationSummary> validation;
  std::vector<FragilityBlock> fragility;
  std::vector<ResponseHistory> responses;
  std::vector<InputFile> files;
  std::vector<Gap> gaps;
  struct FitSettings {
    std::string text;                 // the canonical settings text
    std::vector<std::string> trials;  // the fits made with it
  };
  std::map<std::string, FitSettings> fit_settings;  // settings_hash of the fits → its text and fits
  std::vector<std::string> fits_not_in_summary;     // /fits/<id> of trials the summary lacks
};

// Reads every file. BadInput only when the summary file cannot be read at all (the report has nothing to show);
// every other problem becomes a Gap.
ReportData ReadReportData(const ReportInputs& inputs);

}  // namespace rockfit::app
