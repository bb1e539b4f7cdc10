#include "rockfit/io/csv_export.hpp"

#include <cmath>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "rockfit/io/atomic_file.hpp"

namespace rockfit::io {

namespace {

std::string Number(const std::optional<double>& value) { return value ? fmt::format("{}", *value) : std::string(); }

// RFC 4180: quote fields with commas, quotes or line breaks; double the quotes inside.
std::string Text(const std::string& value) {
  if (value.find_first_of(",\"\n\r") == std::string::npos) return value;
  std::string quoted = "\"";
  for (char c : value) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

void WriteCorrectedCsv(const std::filesystem::path& path, const std::filesystem::path& impacts_path,
                       const Recording& recording, const MetricsSummary& metrics) {
  const DriftCorrection& c = metrics.correction;
  std::set<std::size_t> impact_samples, anchor_samples;
  for (const Anchor& a : c.impacts_y) impact_samples.insert(a.index);
  for (const Anchor& a : c.anchors_x) anchor_samples.insert(a.index);
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "time_s,w_x_rad_s,w_y_rad_s,w_z_rad_s,phi_z_raw_rad,phi_y_raw_rad,phi_x_raw_rad,phi_z_corrected_rad,"
           "phi_y_corrected_rad,phi_x_corrected_rad,impact_y,anchor_x\n";
    for (std::size_t i = 0; i < recording.size(); ++i) {
      const Eigen::Vector3d& w = recording.w_B[i];
      const Eigen::Vector3d& raw = c.euler_raw_zyx[i];
      const Eigen::Vector3d& cor = c.euler_corrected_zyx[i];
      out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", recording.t_s[i], w.x(), w.y(), w.z(), raw[0], raw[1],
                         raw[2], cor[0], cor[1], cor[2], impact_samples.count(i), anchor_samples.count(i));
    }
  });
  WriteFileAtomically(impacts_path, [&](std::ostream& out) {
    out << "angle,time_s,sample_index,anchor_rad,source,omega_peak_rad_s\n";
    for (const Anchor& a : c.impacts_y) {
      out << fmt::format("phi_y,{},{},{},{},{}\n", a.t_s, a.index, a.value_rad, ToString(a.source), a.peak_rad_s);
    }
    for (const Anchor& a : c.anchors_x) {
      out << fmt::format("phi_x,{},{},{},{},{}\n", a.t_s, a.index, a.value_rad, ToString(a.source), a.peak_rad_s);
    }
  });
}

void WriteSummaryCsv(const std::filesystem::path& groups_path, const std::filesystem::path& trials_path,
                     const CampaignSummary& summary) {
  WriteFileAtomically(groups_path, [&](std::ostream& out) {
    out << "block_id,position,b1_m,b2_m,h_m,n_trials,n_opmf,opmf_mean,opmf_std,n_avrf,avrf_mean,avrf_std\n";
    for (const GroupRow& g : summary.groups) {
      out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", Text(g.block_id), Text(g.position), g.b1_m, g.b2_m,
                         g.h_m, g.n_trials, g.n_opmf, Number(g.opmf_mean), Number(g.opmf_std), g.n_avrf,
                         Number(g.avrf_mean), Number(g.avrf_std));
    }
  });
  WriteFileAtomically(trials_path, [&](std::ostream& out) {
    out << "trial_id,block_id,position,b1_m,b2_m,h_m,status,opmf,avrf,lambda_equivalent,avrf_peaks_used,impacts,"
           "message,mounting,mounting_estimated,mounting_angle_x_deg,mounting_angle_y_deg,mounting_angle_z_deg\n";
    for (const TrialRow& t : summary.trials) {
      const Eigen::Vector3d& a = t.mounting_check.angles_deg;
      const auto angle = [](double v) { return std::isfinite(v) ? std::optional<double>(v) : std::nullopt; };
      out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", Text(t.trial_id), Text(t.block_id),
                         Text(t.position), t.b1_m, t.b2_m, t.h_m, Text(ToString(t.status)), Number(t.opmf), Number(t.avrf),
                         Number(t.lambda_equivalent), t.avrf_peaks_used, t.impacts, Text(t.message), Text(t.mounting),
                         t.mounting_check.estimated ? 1 : 0, Number(angle(a.x())), Number(angle(a.y())),
                         Number(angle(a.z())));
    }
  });
}

}  // namespace rockfit::io
