#include "rockfit/io/campaign_hdf5.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/load_options.hpp"
#include "rockfit/io/mounting_estimate.hpp"

namespace rockfit::io {

namespace {

// A stored metrics status; BadInput naming the file and the object for a name rockfit never writes.
MetricsStatus ReadMetricsStatus(const std::string& text, const std::filesystem::path& path, const std::string& where) {
  MetricsStatus status = MetricsStatus::kOk;
  if (!FromString(text, &status)) {
    throw BadInput(fmt::format("{}: {} holds the metrics status '{}', which is none of ok, no_impact, "
                               "no_in_plane_motion, too_few_peaks, invalid_uplift, no_block, load_error; rewrite the "
                               "file with `rockfit summary`", path.string(), where, text));
  }
  return status;
}

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
const char* kVectorColumns = "x, y, z";
const char* kEulerColumns = "phi_z, phi_y, phi_x";

double OrMissing(const std::optional<double>& value) { return value ? *value : kMissing; }
std::optional<double> FromStored(double value) { return std::isnan(value) ? std::nullopt : std::optional<double>(value); }

// Opens /trials/<id>, or the only trial when id is empty.
hdf5::Group OpenTrial(const hdf5::Group& root, const std::filesystem::path& path, const std::string& trial_id,
                      std::string* resolved_id) {
  std::vector<std::string> ids;
  if (root.IsGroup("trials")) ids = root.OpenGroup("trials").Children();
  if (trial_id.empty()) {
    if (ids.size() != 1) {
      throw BadInput(fmt::format("{}: holds {} trials ({}); say which one with --trial ID", path.string(), ids.size(),
                                 ids.empty() ? "none" : fmt::format("{}", fmt::join(ids, ", "))));
    }
    *resolved_id = ids.front();
  } else {
    if (std::find(ids.begin(), ids.end(), trial_id) == ids.end()) {
      throw BadInput(fmt::format("{}: no trial '{}'; the file holds: {}", path.string(), trial_id,
                                 ids.empty() ? "no trials" : fmt::format("{}", fmt::join(ids, ", "))));
    }
    *resolved_id = trial_id;
  }
  return root.OpenGroup("trials/" + *resolved_id);
}

}  // namespace

void WriteFileAttributes(const hdf5::Group& root, const std::string& rockfit_version) {
  root.SetInt("rockfit_schema_version", kHdf5SchemaVersion);
  root.SetString("rockfit_version", rockfit_version);
}

void RequireSchemaVersion(const hdf5::Group& root) {
  const std::optional<std::int64_t> version = root.GetInt("rockfit_schema_version");
  if (!version) {
    throw BadInput(fmt::format("{}: not a rockfit file (no root attribute rockfit_schema_version)", root.file_name()));
  }
  if (*version > kHdf5SchemaVersion || *version < 1) {
    throw BadInput(fmt::format("{}: written with rockfit schema version {}, this rockfit reads versions 1 to {}; "
                               "update rockfit",
                               root.file_name(), *version, kHdf5SchemaVersion));
  }
}

void WriteBlockHdf5(const hdf5::Group& root, const std::string& block_id, const core::Block& block,
                    const std::string& notes) {
  const std::string name = "blocks/" + block_id;
  root.Remove(name);
  const hdf5::Group g = root.CreateGroup(name);
  g.SetDouble("b1_m", block.b1());
  g.SetDouble("b2_m", block.b2());
  g.SetDouble("h_m", block.h());
  g.SetDouble("mass_kg", block.mass());
  g.SetDouble("density_kg_m3", block.density());
  g.SetString("notes", notes);
  const Eigen::Matrix3d& theta = block.inertia_C_B();
  std::vector<double> flat;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) flat.push_back(theta(r, c));
  }
  g.WriteMatrix("inertia_com_B_kg_m2", flat, 3, 3, "kg*m^2");
}

void WriteMountingHdf5(const hdf5::Group& g, const Recording& recording) {
  const MountingCheck& c = recording.mounting_check;
  g.SetString("mounting", recording.mounting);
  g.SetString("mounting_given", c.given);
  g.SetInt("mounting_estimated", c.estimated ? 1 : 0);
  g.SetString("mounting_status", ToString(c.status));
  g.SetString("mounting_message", c.message);
  g.SetString("mounting_warning", c.warning);
  g.SetDouble("mounting_disagreement_deg", MountingDisagreementDeg(c));
  g.SetDouble("mounting_turn_before_fall_deg", c.turn_before_fall_deg);
  g.WriteDoubles("mounting_angles_deg", {c.angles_deg.x(), c.angles_deg.y(), c.angles_deg.z()}, "deg");
  g.WriteDoubles("mounting_std_error_deg", {c.std_error_deg.x(), c.std_error_deg.y(), c.std_error_deg.z()}, "deg");
  g.WriteInts("mounting_determined", {c.determined[0] ? 1 : 0, c.determined[1] ? 1 : 0, c.determined[2] ? 1 : 0}, "1");
}

void WriteTrialHdf5(const hdf5::Group& root, const std::string& trial_id, const TrialLabels& labels,
                    const Recording& recording, const MetricsSummary& metrics, const MetricsOptions& options) {
  const std::string name = "trials/" + trial_id;
  root.Remove(name);
  const hdf5::Group g = root.CreateGroup(name);
  g.SetString("block_id", labels.block_id);
  g.SetString("position", labels.position);
  g.SetString("notes", labels.notes);
  g.SetString("source", recording.source);
  g.SetString("format", recording.format);
  g.SetDouble("rate_hz", recording.rate_hz);
  g.SetString("rate_source", ToString(recording.rate_source));

  g.WriteDoubles("time_s", recording.t_s, "s");
  g.WriteVectors("w_B_rad_s", recording.w_B, "rad/s");
  g.SetString("columns", kVectorColumns, "w_B_rad_s");
  g.WriteVectors("euler_zyx_raw_rad", metrics.correction.euler_raw_zyx, "rad");
  g.SetString("columns", kEulerColumns, "euler_zyx_raw_rad");
  g.WriteVectors("euler_zyx_corrected_rad", metrics.correction.euler_corrected_zyx, "rad");
  g.SetString("columns", kEulerColumns, "euler_zyx_corrected_rad");
  if (recording.has_accel()) {
    g.WriteVectors("accel_B_m_s2", recording.accel_B, "m/s^2");
    g.SetString("columns", kVectorColumns, "accel_B_m_s2");
  }
  g.WriteStrings("source_columns", recording.columns);
  g.WriteStrings("warnings", recording.warnings);
  WriteMountingHdf5(g, recording);

  const hdf5::Group gaps = g.CreateGroup("gaps");
  std::vector<std::int64_t> gap_index, gap_missing;
  std::vector<double> gap_t, gap_duration;
  for (const Gap& gap : recording.gaps) {
    gap_index.push_back(static_cast<std::int64_t>(gap.index));
    gap_missing.push_back(static_cast<std::int64_t>(gap.missing));
    gap_t.push_back(gap.t_s);
    gap_duration.push_back(gap.duration_s);
  }
  gaps.WriteInts("sample_index", gap_index, "1");
  gaps.WriteDoubles("time_s", gap_t, "s");
  gaps.WriteDoubles("duration_s", gap_duration, "s");
  gaps.WriteInts("missing_samples", gap_missing, "1");

  const auto write_anchors = [](const hdf5::Group& group, const std::vector<Anchor>& anchors,
                                const std::string& value_name) {
    std::vector<double> t, value, peak;
    std::vector<std::int64_t> index;
    std::vector<std::string> source;
    for (const Anchor& a : anchors) {
      t.push_back(a.t_s);
      value.push_back(a.value_rad);
      peak.push_back(a.peak_rad_s);
      index.push_back(static_cast<std::int64_t>(a.index));
      source.emplace_back(ToString(a.source));
    }
    group.WriteDoubles("time_s", t, "s");
    group.WriteInts("sample_index", index, "1");
    group.WriteDoubles(value_name, value, "rad");
    group.WriteDoubles("omega_peak_rad_s", peak, "rad/s");
    group.WriteStrings("source", source);
  };
  write_anchors(g.CreateGroup("impacts"), metrics.correction.impacts_y, "phi_y_anchor_rad");
  write_anchors(g.CreateGroup("phi_x_anchors"), metrics.correction.anchors_x, "phi_x_anchor_rad");

  const hdf5::Group m = g.CreateGroup("metrics");
  m.SetString("status", ToString(metrics.status));
  m.SetString("message", metrics.message);
  m.SetString("opmf_status", ToString(metrics.opmf.status));
  m.SetString("opmf_message", metrics.opmf.message);
  m.SetDouble("opmf", metrics.opmf.ok() ? metrics.opmf.opmf : kMissing);
  m.SetDouble("max_abs_phi_x_rad", metrics.opmf.max_abs_phi_x_rad);
  m.SetDouble("max_abs_phi_y_rad", metrics.opmf.max_abs_phi_y_rad);
  m.SetString("avrf_status", ToString(metrics.avrf.status));
  m.SetString("avrf_message", metrics.avrf.message);
  m.SetDouble("avrf", metrics.avrf.ok() ? metrics.avrf.avrf : kMissing);
  m.SetDouble("lambda_equivalent", OrMissing(metrics.avrf.lambda_equivalent));
  m.SetInt("avrf_peaks_used", static_cast<std::int64_t>(metrics.avrf.peaks_used));
  m.SetString("uplift_formula", ToString(options.avrf.uplift));
  m.SetString("anchor_method", ToString(options.correction.anchor_method));
  m.SetDouble("impact_min_prominence_rad_s", options.correction.impacts.min_prominence_rad_s);
  m.SetDouble("impact_min_separation_s", options.correction.impacts.min_separation_s);
  m.SetDouble("avrf_min_peak_prominence_rad", options.avrf.min_peak_prominence_rad);
  m.WriteDoubles("avrf_ratios", metrics.avrf.ratios, "1");
  m.WriteDoubles("avrf_peak_time_s", metrics.avrf.peak_times_s, "s");
  m.WriteDoubles("avrf_peak_angle_rad", metrics.avrf.peak_angles_rad, "rad");
  m.WriteDoubles("avrf_uplift_m", metrics.avrf.uplifts_m, "m");
  m.WriteStrings("warnings", metrics.correction.warnings);
}

std::vector<std::string> ListTrialsHdf5(const std::filesystem::path& path) {
  const hdf5::File file = hdf5::File::Open(path);
  const hdf5::Group root = file.Root();
  RequireSchemaVersion(root);
  return root.IsGroup("trials") ? root.OpenGroup("trials").Children() : std::vector<std::string>{};
}

StoredTrial ReadTrialHdf5(const std::filesystem::path& path, const std::string& trial_id) {
  const hdf5::File file = hdf5::File::Open(path);
  const hdf5::Group root = file.Root();
  RequireSchemaVersion(root);
  StoredTrial stored;
  const hdf5::Group g = OpenTrial(root, path, trial_id, &stored.id);
  stored.labels.block_id = g.GetString("block_id").value_or("");
  stored.labels.position = g.GetString("position").value_or("");
  stored.labels.notes = g.GetString("notes").value_or("");

  Recording& rec = stored.recording;
  rec.format = FormatName(RecordingFormat::kRockfitHdf5);
  rec.source = path.string() + "#" + stored.id;
  rec.rate_source = RateSource::kFile;
  rec.rate_hz = g.GetDouble("rate_hz").value_or(0.0);
  rec.t_s = g.ReadDoubles("time_s");
  rec.w_B = g.ReadVectors("w_B_rad_s");
  rec.euler_zyx = g.ReadVectors("euler_zyx_raw_rad");
  if (g.Exists("accel_B_m_s2")) rec.accel_B = g.ReadVectors("accel_B_m_s2");
  if (g.Exists("source_columns")) rec.columns = g.ReadStrings("source_columns");
  if (g.Exists("warnings")) rec.warnings = g.ReadStrings("warnings");
  rec.mounting = g.GetString("mounting").value_or("identity");
  if (g.IsGroup("gaps")) {
    const hdf5::Group gaps = g.OpenGroup("gaps");
    const auto index = gaps.ReadInts("sample_index");
    const auto t = gaps.ReadDoubles("time_s");
    const auto duration = gaps.ReadDoubles("duration_s");
    const auto missing = gaps.ReadInts("missing_samples");
    if (t.size() != index.size() || duration.size() != index.size() || missing.size() != index.size()) {
      throw BadInput(fmt::format("{}: the datasets of {}/gaps differ in length", path.string(), g.path()));
    }
    for (std::size_t i = 0; i < index.size(); ++i) {
      rec.gaps.push_back({static_cast<std::size_t>(std::max<std::int64_t>(0, index[i])), t[i], duration[i],
                          static_cast<std::size_t>(std::max<std::int64_t>(0, missing[i]))});
    }
  }
  stored.euler_corrected_zyx = g.ReadVectors("euler_zyx_corrected_rad");

  const std::size_t n = rec.t_s.size();
  const auto check_rows = [&](std::size_t rows, const char* name) {
    if (rows != n) {
      throw BadInput(fmt::format("{}: {}/{} has {} rows but time_s has {}", path.string(), g.path(), name, rows, n));
    }
  };
  check_rows(rec.w_B.size(), "w_B_rad_s");
  check_rows(rec.euler_zyx.size(), "euler_zyx_raw_rad");
  check_rows(stored.euler_corrected_zyx.size(), "euler_zyx_corrected_rad");
  if (rec.has_accel()) check_rows(rec.accel_B.size(), "accel_B_m_s2");
  if (!(rec.rate_hz > 0.0) || !std::isfinite(rec.rate_hz)) {
    throw BadInput(fmt::format("{}: {} has no valid rate_hz attribute", path.string(), g.path()));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(rec.t_s[i]) || (i > 0 && !(rec.t_s[i] > rec.t_s[i - 1]))) {
      throw BadInput(fmt::format("{}: {}/time_s is not finite and strictly increasing at row {}", path.string(),
                                 g.path(), i));
    }
    if (!rec.w_B[i].allFinite() || !rec.euler_zyx[i].allFinite()) {
      throw BadInput(fmt::format("{}: {} has a non-finite angular velocity or Euler angle at row {}", path.string(),
                                 g.path(), i));
    }
    if (rec.has_accel() && !rec.accel_B[i].allFinite()) {
      throw BadInput(fmt::format("{}: {}/accel_B_m_s2 is not finite at row {}", path.string(), g.path(), i));
    }
  }
  for (std::size_t i = 0; i < rec.gaps.size(); ++i) {
    const Gap& gap = rec.gaps[i];
    if (gap.index >= n || !(std::isfinite(gap.duration_s) && gap.duration_s > 0.0)) {
      throw BadInput(fmt::format("{}: {}/gaps row {} is not a gap inside the recording (sample_index {} of {} "
                                 "samples, duration_s {})", path.string(), g.path(), i, gap.index, n, gap.duration_s));
    }
  }
  if (g.IsGroup("impacts")) stored.impact_times_s = g.OpenGroup("impacts").ReadDoubles("time_s");
  if (g.IsGroup("phi_x_anchors")) stored.phi_x_anchor_times_s = g.OpenGroup("phi_x_anchors").ReadDoubles("time_s");
  if (g.IsGroup("metrics")) {
    const hdf5::Group m = g.OpenGroup("metrics");
    stored.status = ReadMetricsStatus(m.GetString("status").value_or("ok"), path, g.path() + "/metrics");
    stored.message = m.GetString("message").value_or("");
    if (const auto v = m.GetDouble("opmf")) stored.opmf = FromStored(*v);
    if (const auto v = m.GetDouble("avrf")) stored.avrf = FromStored(*v);
    if (const auto v = m.GetDouble("lambda_equivalent")) stored.lambda_equivalent = FromStored(*v);
  }
  return stored;
}

Recording ReadRecordingHdf5(const std::filesystem::path& path, const std::string& trial_id) {
  return ReadTrialHdf5(path, trial_id).recording;
}

void WriteSummaryHdf5(const hdf5::Group& root, const CampaignSummary& summary) {
  root.Remove("summary");
  const hdf5::Group s = root.CreateGroup("summary");
  s.SetString("description", "OPMF and AVRF per trial (trials) and per block and position (groups): n, mean and "
                             "sample standard deviation (n - 1); NaN where a value is missing");

  const hdf5::Group t = s.CreateGroup("trials");
  std::vector<std::string> trial_id, block_id, position, status, message;
  std::vector<double> b1, b2, h, opmf, avrf, lambda;
  std::vector<std::int64_t> peaks, impacts, mounting_estimated;
  std::vector<std::string> mounting, mounting_status;
  std::vector<double> mounting_x, mounting_y, mounting_z;
  for (const TrialRow& r : summary.trials) {
    mounting.push_back(r.mounting), mounting_status.push_back(ToString(r.mounting_check.status));
    mounting_estimated.push_back(r.mounting_check.estimated ? 1 : 0);
    mounting_x.push_back(r.mounting_check.angles_deg.x()), mounting_y.push_back(r.mounting_check.angles_deg.y());
    mounting_z.push_back(r.mounting_check.angles_deg.z());
    trial_id.push_back(r.trial_id), block_id.push_back(r.block_id), position.push_back(r.position);
    status.push_back(ToString(r.status)), message.push_back(r.message);
    b1.push_back(r.b1_m), b2.push_back(r.b2_m), h.push_back(r.h_m);
    opmf.push_back(OrMissing(r.opmf)), avrf.push_back(OrMissing(r.avrf)), lambda.push_back(OrMissing(r.lambda_equivalent));
    peaks.push_back(static_cast<std::int64_t>(r.avrf_peaks_used)), impacts.push_back(static_cast<std::int64_t>(r.impacts));
  }
  t.WriteStrings("trial_id", trial_id);
  t.WriteStrings("block_id", block_id);
  t.WriteStrings("position", position);
  t.WriteDoubles("b1_m", b1, "m");
  t.WriteDoubles("b2_m", b2, "m");
  t.WriteDoubles("h_m", h, "m");
  t.WriteDoubles("opmf", opmf, "1");
  t.WriteDoubles("avrf", avrf, "1");
  t.WriteDoubles("lambda_equivalent", lambda, "1");
  t.WriteInts("avrf_peaks_used", peaks, "1");
  t.WriteInts("impacts", impacts, "1");
  t.WriteStrings("status", status);
  t.WriteStrings("message", message);
  t.WriteStrings("mounting", mounting);
  t.WriteInts("mounting_estimated", mounting_estimated, "1");
  t.WriteStrings("mounting_status", mounting_status);
  t.WriteDoubles("mounting_angle_x_deg", mounting_x, "deg");
  t.WriteDoubles("mounting_angle_y_deg", mounting_y, "deg");
  t.WriteDoubles("mounting_angle_z_deg", mounting_z, "deg");
  t.SetString("columns", "trial_id, block_id, position, b1_m, b2_m, h_m, opmf, avrf, lambda_equivalent, "
                         "avrf_peaks_used, impacts, status, message, mounting, mounting_estimated, mounting_status, "
                         "mounting_angle_x_deg, mounting_angle_y_deg, mounting_angle_z_deg");

  const hdf5::Group gr = s.CreateGroup("groups");
  std::vector<std::string> g_block, g_position;
  std::vector<double> g_b1, g_b2, g_h, o_mean, o_std, a_mean, a_std;
  std::vector<std::int64_t> n_trials, n_opmf, n_avrf;
  for (const GroupRow& g : summary.groups) {
    g_block.push_back(g.block_id), g_position.push_back(g.position);
    g_b1.push_back(g.b1_m), g_b2.push_back(g.b2_m), g_h.push_back(g.h_m);
    n_trials.push_back(static_cast<std::int64_t>(g.n_trials));
    n_opmf.push_back(static_cast<std::int64_t>(g.n_opmf)), n_avrf.push_back(static_cast<std::int64_t>(g.n_avrf));
    o_mean.push_back(OrMissing(g.opmf_mean)), o_std.push_back(OrMissing(g.opmf_std));
    a_mean.push_back(OrMissing(g.avrf_mean)), a_std.push_back(OrMissing(g.avrf_std));
  }
  gr.WriteStrings("block_id", g_block);
  gr.WriteStrings("position", g_position);
  gr.WriteDoubles("b1_m", g_b1, "m");
  gr.WriteDoubles("b2_m", g_b2, "m");
  gr.WriteDoubles("h_m", g_h, "m");
  gr.WriteInts("n_trials", n_trials, "1");
  gr.WriteInts("n_opmf", n_opmf, "1");
  gr.WriteDoubles("opmf_mean", o_mean, "1");
  gr.WriteDoubles("opmf_std", o_std, "1");
  gr.WriteInts("n_avrf", n_avrf, "1");
  gr.WriteDoubles("avrf_mean", a_mean, "1");
  gr.WriteDoubles("avrf_std", a_std, "1");
  gr.SetString("columns", "block_id, position, b1_m, b2_m, h_m, n_trials, n_opmf, opmf_mean, opmf_std, n_avrf, "
                          "avrf_mean, avrf_std");
}

CampaignSummary ReadSummaryHdf5(const std::filesystem::path& path) {
  const hdf5::File file = hdf5::File::Open(path);
  const hdf5::Group root = file.Root();
  RequireSchemaVersion(root);
  if (!root.IsGroup("summary")) {
    throw BadInput(fmt::format("{}: no /summary group; write one with `rockfit summary MANIFEST -o {}`", path.string(),
                               path.filename().string()));
  }
  const hdf5::Group s = root.OpenGroup("summary");
  CampaignSummary summary;
  {
    const hdf5::Group t = s.OpenGroup("trials");
    const auto trial_id = t.ReadStrings("trial_id"), block_id = t.ReadStrings("block_id");
    const auto position = t.ReadStrings("position"), status = t.ReadStrings("status"), message = t.ReadStrings("message");
    const auto b1 = t.ReadDoubles("b1_m"), b2 = t.ReadDoubles("b2_m"), h = t.ReadDoubles("h_m");
    const auto opmf = t.ReadDoubles("opmf"), avrf = t.ReadDoubles("avrf"), lambda = t.ReadDoubles("lambda_equivalent");
    const auto peaks = t.ReadInts("avrf_peaks_used"), impacts = t.ReadInts("impacts");
    // Files written before the mounting columns existed have none.
    const auto mounting = t.Exists("mounting") ? t.ReadStrings("mounting") : std::vector<std::string>{};
    std::vector<std::vector<double>> mounting_angles;
    for (const char* name : {"mounting_angle_x_deg", "mounting_angle_y_deg", "mounting_angle_z_deg"}) {
      if (t.Exists(name)) mounting_angles.push_back(t.ReadDoubles(name));
    }
    const std::size_t n = trial_id.size();
    for (std::size_t size : {block_id.size(), position.size(), status.size(), message.size(), b1.size(), b2.size(),
                             h.size(), opmf.size(), avrf.size(), lambda.size(), peaks.size(), impacts.size()}) {
      if (size != n) throw BadInput(fmt::format("{}: the columns of /summary/trials differ in length", path.string()));
    }
    for (std::size_t i = 0; i < n; ++i) {
      TrialRow r;
      r.trial_id = trial_id[i], r.block_id = block_id[i], r.position = position[i];
      r.status = ReadMetricsStatus(status[i], path, "/summary/trials/status"), r.message = message[i];
      r.b1_m = b1[i], r.b2_m = b2[i], r.h_m = h[i];
      r.opmf = FromStored(opmf[i]), r.avrf = FromStored(avrf[i]), r.lambda_equivalent = FromStored(lambda[i]);
      r.avrf_peaks_used = static_cast<std::size_t>(std::max<std::int64_t>(0, peaks[i]));
      r.impacts = static_cast<std::size_t>(std::max<std::int64_t>(0, impacts[i]));
      if (mounting.size() == n) r.mounting = mounting[i];
      if (mounting_angles.size() == 3 && mounting_angles[0].size() == n && mounting_angles[1].size() == n &&
          mounting_angles[2].size() == n) {
        r.mounting_check.angles_deg = {mounting_angles[0][i], mounting_angles[1][i], mounting_angles[2][i]};
      }
      summary.trials.push_back(r);
    }
  }
  {
    const hdf5::Group gr = s.OpenGroup("groups");
    const auto block_id = gr.ReadStrings("block_id"), position = gr.ReadStrings("position");
    const auto b1 = gr.ReadDoubles("b1_m"), b2 = gr.ReadDoubles("b2_m"), h = gr.ReadDoubles("h_m");
    const auto n_trials = gr.ReadInts("n_trials"), n_opmf = gr.ReadInts("n_opmf"), n_avrf = gr.ReadInts("n_avrf");
    const auto o_mean = gr.ReadDoubles("opmf_mean"), o_std = gr.ReadDoubles("opmf_std");
    const auto a_mean = gr.ReadDoubles("avrf_mean"), a_std = gr.ReadDoubles("avrf_std");
    const std::size_t n = block_id.size();
    for (std::size_t size : {position.size(), b1.size(), b2.size(), h.size(), n_trials.size(), n_opmf.size(),
                             n_avrf.size(), o_mean.size(), o_std.size(), a_mean.size(), a_std.size()}) {
      if (size != n) throw BadInput(fmt::format("{}: the columns of /summary/groups differ in length", path.string()));
    }
    for (std::size_t i = 0; i < n; ++i) {
      GroupRow g;
      g.block_id = block_id[i], g.position = position[i];
      g.b1_m = b1[i], g.b2_m = b2[i], g.h_m = h[i];
      g.n_trials = static_cast<std::size_t>(std::max<std::int64_t>(0, n_trials[i]));
      g.n_opmf = static_cast<std::size_t>(std::max<std::int64_t>(0, n_opmf[i]));
      g.n_avrf = static_cast<std::size_t>(std::max<std::int64_t>(0, n_avrf[i]));
      g.opmf_mean = FromStored(o_mean[i]), g.opmf_std = FromStored(o_std[i]);
      g.avrf_mean = FromStored(a_mean[i]), g.avrf_std = FromStored(a_std[i]);
      summary.groups.push_back(g);
    }
  }
  return summary;
}

}  // namespace rockfit::io

