// rockfit.metrics: drift correction, OPMF and AVRF of one trial (paper Sect. 3), the fields of `rockfit metrics
// --json` plus the corrected angles as arrays.
#include <cmath>

#include "bindings.hpp"
#include "rockfit/app/mounting_report.hpp"
#include "rockfit/app/metrics_options.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::python {
namespace {

py::object ValueOrNone(bool present, double value) { return present ? py::object(py::float_(value)) : py::none(); }

py::list AnchorRecords(const std::vector<io::Anchor>& anchors) {
  py::list out;
  for (const io::Anchor& a : anchors) {
    py::dict d;
    d["t"] = a.t_s;
    d["index"] = a.index;
    d["value"] = a.value_rad;
    d["source"] = io::ToString(a.source);
    d["peak"] = a.peak_rad_s;
    out.append(MakeRecord("Anchor", d));
  }
  return out;
}

py::object Metrics(const TrialRecording& r, const std::optional<core::Block>& given, double min_prominence,
                   double min_separation, const std::string& anchors, std::size_t peaks, std::size_t min_peaks,
                   const std::string& uplift) {
  const core::Block block = BlockFor(given, r, "the AVRF");
  app::MetricsArgs args;
  args.options.correction.impacts.min_prominence_rad_s = min_prominence;
  args.options.correction.impacts.min_separation_s = min_separation;
  args.options.avrf.max_peaks = peaks;
  args.options.avrf.min_peaks = min_peaks;
  args.anchors = anchors;
  args.uplift = uplift;
  if (anchors != "subsample" && anchors != "sample") throw InvalidArgument("anchors must be 'subsample' or 'sample', got '" + anchors + "'");
  if (uplift != "com" && uplift != "paper") throw InvalidArgument("uplift must be 'com' or 'paper', got '" + uplift + "'");
  const io::MetricsOptions options = app::MakeMetricsOptions(args);
  io::MetricsSummary m;
  {
    py::gil_scoped_release release;
    m = io::ComputeTrialMetrics(r.recording, block, options);
  }
  const io::Recording& rec = r.recording;
  std::vector<double> impact_times, x_anchor_times;
  for (const auto& a : m.correction.impacts_y) impact_times.push_back(a.t_s);
  for (const auto& a : m.correction.anchors_x) x_anchor_times.push_back(a.t_s);

  py::dict d;  // the keys of `rockfit metrics --json`, in its order
  d["trial"] = r.trial;
  d["source"] = rec.source;
  d["format"] = rec.format;
  d["rate_hz"] = rec.rate_hz;
  d["samples"] = rec.size();
  d["status"] = m.status;
  d["message"] = m.message;
  d["opmf"] = ValueOrNone(m.opmf.ok(), m.opmf.opmf);
  d["opmf_status"] = io::ToString(m.opmf.status);
  d["max_abs_phi_x"] = m.opmf.max_abs_phi_x_rad;
  d["max_abs_phi_y"] = m.opmf.max_abs_phi_y_rad;
  d["avrf"] = ValueOrNone(m.avrf.ok(), m.avrf.avrf);
  d["avrf_status"] = io::ToString(m.avrf.status);
  d["avrf_ratios"] = OwnedArray(std::vector<double>(m.avrf.ratios));
  d["avrf_peaks_used"] = m.avrf.peaks_used;
  d["avrf_peak_times"] = OwnedArray(std::vector<double>(m.avrf.peak_times_s));
  d["avrf_peak_angles"] = OwnedArray(std::vector<double>(m.avrf.peak_angles_rad));
  d["lambda_equivalent"] = m.avrf.lambda_equivalent && std::isfinite(*m.avrf.lambda_equivalent)
                               ? py::object(py::float_(*m.avrf.lambda_equivalent))
                               : py::none();
  d["impact_times"] = OwnedArray(std::move(impact_times));
  d["phi_x_anchor_times"] = OwnedArray(std::move(x_anchor_times));
  d["uplift_formula"] = io::ToString(options.avrf.uplift);
  d["anchor_method"] = io::ToString(options.correction.anchor_method);
  d["mounting"] = FromJson(app::MountingJson(rec));
  d["block"] = BlockDict(block);
  d["warnings"] = m.correction.warnings;
  d["units"] = py::dict(py::arg("rate_hz") = "Hz", py::arg("max_abs_phi_x") = "rad", py::arg("max_abs_phi_y") = "rad",
                        py::arg("avrf_peak_times") = "s", py::arg("avrf_peak_angles") = "rad",
                        py::arg("impact_times") = "s", py::arg("phi_x_anchor_times") = "s", py::arg("block") = "m, kg",
                        py::arg("opmf") = "1", py::arg("avrf") = "1", py::arg("lambda_equivalent") = "1");
  // Beyond the program's JSON: the samples and the anchors of the correction.
  d["t"] = OwnedArray(std::vector<double>(rec.t_s));
  d["euler_raw"] = OwnedArray(std::move(m.correction.euler_raw_zyx));
  d["euler_corrected"] = OwnedArray(std::move(m.correction.euler_corrected_zyx));
  d["impacts"] = AnchorRecords(m.correction.impacts_y);
  d["phi_x_anchors"] = AnchorRecords(m.correction.anchors_x);
  d["avrf_uplifts"] = OwnedArray(std::vector<double>(m.avrf.uplifts_m));
  return MakeRecord("Metrics", d);
}

}  // namespace

void RegisterMetrics(py::module_& m) {
  const io::MetricsOptions defaults;
  m.def("metrics", &Metrics, py::arg("recording"), py::arg("block") = py::none(), py::kw_only(),
        py::arg("min_prominence") = defaults.correction.impacts.min_prominence_rad_s,
        py::arg("min_separation") = defaults.correction.impacts.min_separation_s, py::arg("anchors") = "subsample",
        py::arg("peaks") = defaults.avrf.max_peaks, py::arg("min_peaks") = defaults.avrf.min_peaks,
        py::arg("uplift") = "com",
        "Drift correction, OPMF and AVRF of one trial (paper Sect. 3.2), as `rockfit metrics --json`.\n\n"
        "recording: a rockfit.Recording with Euler angles; block: a rockfit.Block (default: the recording's manifest\n"
        "  block).\n"
        "min_prominence: impacts are peaks of |ω_y| (|ω_x|) at least this prominent [rad/s].\n"
        "min_separation: of two peaks closer than this, the lower is ringing [s].\n"
        "anchors: 'subsample' (impact located inside the sample interval) or 'sample' (as in the paper).\n"
        "peaks: number of peak inclinations after the first impact (the paper: 10); min_peaks: fewer is\n"
        "  status 'too_few_peaks'. uplift: 'com' = b1·sin φ − h·(1 − cos φ) or 'paper' (as printed).\n\n"
        "Returns a Record 'Metrics' with the keys of the program's JSON: trial, source, format, rate_hz, samples,\n"
        "status ('ok', 'no_impact', 'no_in_plane_motion', 'too_few_peaks', 'invalid_uplift'), message, opmf (None\n"
        "without a value), opmf_status, max_abs_phi_x [rad], max_abs_phi_y [rad], avrf, avrf_status, avrf_ratios,\n"
        "avrf_peaks_used, avrf_peak_times [s], avrf_peak_angles [rad], lambda_equivalent (λ of (6)), impact_times [s],\n"
        "phi_x_anchor_times [s], uplift_formula, anchor_method, block, warnings, units; and t [s] (N,), euler_raw and\n"
        "euler_corrected [rad] (N, 3) as (φz, φy, φx), impacts and phi_x_anchors (Records t [s], index, value [rad],\n"
        "source, peak [rad/s]), avrf_uplifts [m]. A metric without a value is a status, not an exception.");
}

}  // namespace rockfit::python
