#include "rockfit/app/metrics_document.hpp"

#include <vector>

#include "rockfit/app/json_values.hpp"
#include "rockfit/app/mounting_report.hpp"

namespace rockfit::app {
namespace {

nlohmann::json ValueOrNull(bool present, double value) { return present ? nlohmann::json(value) : nlohmann::json(); }

std::vector<double> Times(const std::vector<io::Anchor>& anchors) {
  std::vector<double> times;
  for (const io::Anchor& a : anchors) times.push_back(a.t_s);
  return times;
}

}  // namespace

nlohmann::json MetricsJson(const std::string& trial_id, const io::Recording& rec, const core::Block& block,
                           const io::MetricsOptions& options, const io::MetricsSummary& m) {
  nlohmann::json out;
  out["trial"] = trial_id;
  out["source"] = rec.source;
  out["format"] = rec.format;
  out["rate_hz"] = rec.rate_hz;
  out["samples"] = rec.size();
  out["status"] = io::ToString(m.status);
  out["message"] = m.message;
  out["opmf"] = ValueOrNull(m.opmf.ok(), m.opmf.opmf);
  out["opmf_status"] = io::ToString(m.opmf.status);
  out["max_abs_phi_x"] = m.opmf.max_abs_phi_x_rad;
  out["max_abs_phi_y"] = m.opmf.max_abs_phi_y_rad;
  out["avrf"] = ValueOrNull(m.avrf.ok(), m.avrf.avrf);
  out["avrf_status"] = io::ToString(m.avrf.status);
  out["avrf_ratios"] = m.avrf.ratios;
  out["avrf_peaks_used"] = m.avrf.peaks_used;
  out["avrf_peak_times"] = m.avrf.peak_times_s;
  out["avrf_peak_angles"] = m.avrf.peak_angles_rad;
  out["lambda_equivalent"] = OrNull(m.avrf.lambda_equivalent);
  out["impact_times"] = Times(m.correction.impacts_y);
  out["phi_x_anchor_times"] = Times(m.correction.anchors_x);
  out["uplift_formula"] = io::ToString(options.avrf.uplift);
  out["anchor_method"] = io::ToString(options.correction.anchor_method);
  out["mounting"] = MountingJson(rec);
  out["block"] = {{"b1", block.b1()}, {"b2", block.b2()}, {"h", block.h()}, {"mass", block.mass()}};
  out["warnings"] = m.correction.warnings;
  out["units"] = {{"rate_hz", "Hz"},         {"max_abs_phi_x", "rad"},   {"max_abs_phi_y", "rad"},
                  {"avrf_peak_times", "s"},  {"avrf_peak_angles", "rad"}, {"impact_times", "s"},
                  {"phi_x_anchor_times", "s"}, {"block", "m, kg"},       {"opmf", "1"},
                  {"avrf", "1"},             {"lambda_equivalent", "1"}};
  return out;
}

}  // namespace rockfit::app
