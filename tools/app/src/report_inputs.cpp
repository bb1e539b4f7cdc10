#include "rockfit/app/report_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/fitting/validation_store.hpp"
#include "rockfit/io/content_hash.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/trajectory_hdf5.hpp"
#include "rockfit/quake/lognormal_fragility.hpp"

namespace rockfit::app {
namespace {

// Two blocks are the same size when every dimension agrees to this [m] (the files store the manifest's values).
constexpr double kSameBlockSize_m = 1e-6;

std::string ErrorText(const std::exception& e) { return e.what(); }

InputFile DescribeFile(const std::string& role, const std::filesystem::path& path) {
  InputFile f;
  f.role = role;
  f.path = path;
  std::error_code ec;
  f.size_bytes = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (in) {
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    f.content_hash = io::HashHex(io::Fnv1a64(bytes));
  }
  try {
    const io::hdf5::File file = io::hdf5::File::Open(path);
    f.rockfit_version = file.Root().GetString("rockfit_version").value_or("");
    if (file.Root().IsGroup("fragility")) f.settings_hash = file.Root().GetString("settings_hash", "fragility").value_or("");
  } catch (const std::exception&) {
    // Unreadable files are reported where their content is read.
  }
  return f;
}

TrialFit ReadTrialFit(const io::hdf5::Group& g) {
  TrialFit fit;
  fit.labels = fitting::ReadFitLabels(g);
  if (g.IsGroup("parameters")) fit.parameters = fitting::ReadFitParameters(g);
  if (g.IsDataset("warnings")) fit.warnings = g.ReadStrings("warnings");
  fit.termination = g.GetString("termination").value_or("");
  fit.settings = g.GetString("settings").value_or("");
  if (g.IsDataset("time_s") && g.IsDataset("w_B_measured")) {
    fit.t_s = g.ReadDoubles("time_s");
    fit.w_measured_B = g.ReadVectors("w_B_measured");
    if (g.IsDataset("w_B_simulated")) fit.w_simulated_B = g.ReadVectors("w_B_simulated");
    if (fit.w_measured_B.size() != fit.t_s.size() ||
        (!fit.w_simulated_B.empty() && fit.w_simulated_B.size() != fit.t_s.size())) {
      throw BadInput(fmt::format("{}: time_s, w_B_measured and w_B_simulated differ in length", g.path()));
    }
  }
  if (g.IsDataset("impacts/t_s")) fit.impact_t_s = g.ReadDoubles("impacts/t_s");
  return fit;
}

void ReadFits(const std::filesystem::path& path, ReportData& data) {
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const io::hdf5::Group root = file.Root();
  const std::vector<std::string> stored = fitting::StoredFitTrials(root);
  if (stored.empty()) {
    data.gaps.push_back({"fits file " + path.string(),
                         "holds no /fits group; write it with `rockfit batch MANIFEST -o FILE`"});
    return;
  }
  const std::set<std::string> stored_set(stored.begin(), stored.end());
  std::set<std::string> known;
  const io::hdf5::Group fits = root.OpenGroup("fits");
  for (ReportTrial& t : data.trials) {
    known.insert(t.row.trial_id);
    if (!stored_set.count(t.row.trial_id)) {
      data.gaps.push_back({"trial " + t.row.trial_id,
                           fmt::format("has no fit in {}; run `rockfit batch MANIFEST -o {} --resume` to add it",
                                       path.string(), path.string())});
      continue;
    }
    try {
      t.fit = ReadTrialFit(fits.OpenGroup(t.row.trial_id));
      ReportData::FitSettings& settings =
          data.fit_settings[t.fit->labels.settings_hash.empty() ? "(none)" : t.fit->labels.settings_hash];
      settings.text = t.fit->settings;
      settings.trials.push_back(t.row.trial_id);
    } catch (const std::exception& e) {
      data.gaps.push_back({"trial " + t.row.trial_id, "its fit cannot be read: " + ErrorText(e)});
    }
  }
  for (const std::string& id : stored) {
    if (!known.count(id)) data.fits_not_in_summary.push_back(id);
  }
  if (!data.fits_not_in_summary.empty()) {
    std::string list;
    for (const std::string& id : data.fits_not_in_summary) list += (list.empty() ? "" : ", ") + id;
    data.gaps.push_back({"fits file " + path.string(),
                         "holds fits of trials the summary does not list (left out of the report): " + list});
  }
  if (fitting::HasFitGroupSummaries(root)) {
    try {
      data.fit_groups = fitting::ReadFitGroupSummaries(root);
    } catch (const std::exception& e) {
      data.gaps.push_back({"fits file " + path.string(), "its table /summary/fits/per_group cannot be read: " + ErrorText(e)});
    }
  } else {
    data.gaps.push_back({"fits file " + path.string(),
                         "has no table /summary/fits/per_group (a file of `rockfit fit -o`); the parameter ranges per "
                         "block and position need `rockfit batch`"});
  }
}

std::string BlockOfSize(const io::CampaignSummary& summary, double b1_m, double b2_m, double h_m) {
  for (const io::GroupRow& g : summary.groups) {
    if (std::abs(g.b1_m - b1_m) < kSameBlockSize_m && std::abs(g.b2_m - b2_m) < kSameBlockSize_m &&
        std::abs(g.h_m - h_m) < kSameBlockSize_m) {
      return g.block_id;
    }
  }
  return "";
}

void ReadFragility(const std::filesystem::path& path, ReportData& data) {
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const io::hdf5::Group root = file.Root();
  if (!root.IsGroup("fragility/blocks")) {
    data.gaps.push_back({"fragility file " + path.string(),
                         "has no /fragility/blocks; it is not the output of `rockfit fragility -o FILE`"});
    return;
  }
  std::set<std::string> campaign_blocks;
  for (const io::GroupRow& g : data.summary.groups) campaign_blocks.insert(g.block_id);
  const io::hdf5::Group f = root.OpenGroup("fragility");
  const bool pga = f.GetString("intensity_measure").value_or("pga_g") == "pga_g";
  for (const std::string& id : f.ReadStrings("blocks/id")) {
    if (!campaign_blocks.count(id)) {
      std::string list;
      for (const std::string& b : campaign_blocks) list += (list.empty() ? "" : ", ") + b;
      data.gaps.push_back({"fragility file " + path.string(),
                           fmt::format("is a study of block '{}', which is not a block of this campaign ({}); its "
                                       "curves are left out", id, list)});
      continue;
    }
    FragilityBlock block;
    block.file = path.string();
    block.block_id = id;
    block.intensity_is_pga_g = pga;
    const io::hdf5::Group g = f.OpenGroup("blocks/" + id);
    const std::vector<double> x = g.ReadDoubles("intensity");
    for (const std::string& name : g.ReadStrings("limit_state_names")) {
      const io::hdf5::Group ls = g.OpenGroup("limit_states/" + name);
      FragilityLimitState s;
      s.name = name;
      s.intensity = x;
      s.probability = ls.ReadDoubles("probability");
      s.lower_95 = ls.ReadDoubles("clopper_pearson_95_lower");
      s.upper_95 = ls.ReadDoubles("clopper_pearson_95_upper");
      if (s.probability.size() != x.size() || s.lower_95.size() != x.size() || s.upper_95.size() != x.size()) {
        throw BadInput(fmt::format("{}: /fragility/blocks/{}/limit_states/{} has columns of another length than "
                                   "its intensities", path.string(), id, name));
      }
      const std::vector<std::string> status = ls.ReadStrings("curve/status");
      s.curve_status = status.empty() ? "" : status.front();
      s.curve_ok = CurveStatusIsOk(s.curve_status, fmt::format("{}: /fragility/blocks/{}/limit_states/{}/curve/status",
                                                               path.string(), id, name));
      if (ls.IsDataset("curve/message")) {
        const std::vector<std::string> message = ls.ReadStrings("curve/message");
        s.curve_message = message.empty() ? "" : message.front();
      }
      const std::vector<double> median = ls.ReadDoubles("curve/median"), beta = ls.ReadDoubles("curve/beta");
      s.median = median.empty() ? std::nan("") : median.front();
      s.beta = beta.empty() ? std::nan("") : beta.front();
      block.limit_states.push_back(std::move(s));
    }
    data.fragility.push_back(std::move(block));
  }
}

void ReadResponse(const std::filesystem::path& path, ReportData& data) {
  const io::hdf5::File file = io::hdf5::File::Open(path);
  const io::hdf5::Group root = file.Root();
  if (!root.IsGroup("ground_motion") || !root.IsDataset("samples/tilt_rad")) {
    data.gaps.push_back({"response file " + path.string(),
                         "has no /ground_motion and /samples/tilt_rad; it is not the output of `rockfit respond "
                         "--format hdf5 -o FILE` (of this rockfit version)"});
    return;
  }
  ResponseHistory r;
  r.file = path.string();
  r.t_s = root.ReadDoubles("samples/time_s");
  r.tilt_rad = root.ReadDoubles("samples/tilt_rad");
  r.w_B_rad_s = root.ReadVectors("samples/w_B_rad_s");
  r.ground_t_s = root.ReadDoubles("ground_motion/time_s");
  for (const Eigen::Vector3d& a : root.ReadVectors("ground_motion/a_W_m_s2")) r.ground_a_W_g.push_back(a / core::kRecordGravity);
  if (r.tilt_rad.size() != r.t_s.size() || r.w_B_rad_s.size() != r.t_s.size() ||
      r.ground_a_W_g.size() != r.ground_t_s.size()) {
    throw BadInput(path.string() + ": the samples or the ground motion have columns of different lengths");
  }
  r.critical_tilt_rad = root.GetDouble("critical_tilt_rad", "response").value_or(0.0);
  r.peak_tilt_rad = root.GetDouble("peak_tilt_rad", "response").value_or(std::nan(""));
  r.overturned = root.GetInt("overturned", "response").value_or(0) != 0;
  r.end_reason = root.GetString("end_reason", "result").value_or("");
  if (root.IsGroup("block")) {
    r.block_id = BlockOfSize(data.summary, root.GetDouble("b1_m", "block").value_or(0.0),
                             root.GetDouble("b2_m", "block").value_or(0.0), root.GetDouble("h_m", "block").value_or(0.0));
  }
  if (r.block_id.empty()) {
    data.gaps.push_back({"response file " + path.string(),
                         "is the response of a block whose size matches none of the campaign's blocks; shown unnamed"});
  }
  data.responses.push_back(std::move(r));
}

// Runs `read` and turns a failure into a gap of `where`.
template <typename Read>
void Tolerant(const std::string& where, ReportData& data, Read read) {
  try {
    read();
  } catch (const std::exception& e) {
    data.gaps.push_back({where, "cannot be read: " + ErrorText(e)});
  }
}

}  // namespace

ReportData ReadReportData(const ReportInputs& inputs) {
  if (inputs.summary.empty()) throw InvalidArgument("a report needs the campaign summary (the HDF5 file of `rockfit summary -o`)");
  ReportData data;
  data.summary = io::ReadSummaryHdf5(inputs.summary);  // BadInput names the file and what is wrong
  data.files.push_back(DescribeFile("summary", inputs.summary));
  std::set<std::string> stored_trials;
  try {
    for (const std::string& id : io::ListTrialsHdf5(inputs.summary)) stored_trials.insert(id);
  } catch (const std::exception& e) {
    data.gaps.push_back({"summary file " + inputs.summary.string(), "its trials cannot be listed: " + ErrorText(e)});
  }
  for (const io::TrialRow& row : data.summary.trials) {
    ReportTrial t;
    t.row = row;
    if (stored_trials.count(row.trial_id)) {
      Tolerant("trial " + row.trial_id + " in " + inputs.summary.string(), data, [&] {
        const io::StoredTrial s = io::ReadTrialHdf5(inputs.summary, row.trial_id);
        TrialAngles a;
        a.t_s = s.recording.t_s;
        a.raw_zyx_rad = s.recording.euler_zyx;
        a.corrected_zyx_rad = s.euler_corrected_zyx;
        a.impact_t_s = s.impact_times_s;
        if (a.raw_zyx_rad.size() == a.t_s.size() && a.corrected_zyx_rad.size() == a.t_s.size()) t.angles = std::move(a);
      });
    } else if (row.status != io::MetricsStatus::kLoadError) {
      data.gaps.push_back({"trial " + row.trial_id, "its samples are not in " + inputs.summary.string() +
                                                        " (the angles figure needs /trials/" + row.trial_id + ")"});
    }
    data.trials.push_back(std::move(t));
  }
  if (!inputs.fits.empty()) {
    data.files.push_back(DescribeFile("fits", inputs.fits));
    Tolerant("fits file " + inputs.fits.string(), data, [&] { ReadFits(inputs.fits, data); });
  } else {
    data.gaps.push_back({"fits", "no fits file was given (the output of `rockfit batch`): the report has no fitted "
                                 "parameters, no measured-against-simulated figures and no model error"});
  }
  if (!inputs.validation.empty()) {
    data.files.push_back(DescribeFile("validation", inputs.validation));
    Tolerant("validation file " + inputs.validation.string(), data, [&] {
      const io::hdf5::File file = io::hdf5::File::Open(inputs.validation);
      data.validation = fitting::ReadValidationGroup(file.Root());
    });
  }
  for (const std::filesystem::path& p : inputs.fragility) {
    data.files.push_back(DescribeFile("fragility", p));
    Tolerant("fragility file " + p.string(), data, [&] { ReadFragility(p, data); });
  }
  for (const std::filesystem::path& p : inputs.responses) {
    data.files.push_back(DescribeFile("response", p));
    Tolerant("response file " + p.string(), data, [&] { ReadResponse(p, data); });
  }
  return data;
}

bool CurveStatusIsOk(const std::string& stored, const std::string& where) {
  if (stored.empty()) return false;
  quake::LognormalFitStatus status = quake::LognormalFitStatus::kOk;
  if (!quake::FromString(stored, &status)) {
    throw BadInput(fmt::format("{}: '{}' is no lognormal-fit status; write the file again with this rockfit", where,
                               stored));
  }
  return status == quake::LognormalFitStatus::kOk;
}

}  // namespace rockfit::app
