// rockfit.metrics: drift correction, OPMF and AVRF of one trial (paper Sect. 3), the fields of `rockfit metrics
// --json` plus the corrected angles as arrays.
#include <cmath>

#include "bindings.hpp"
#include "rockfit/app/metrics_document.hpp"
#include "rockfit/app/metrics_options.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/trial_metrics.hpp"

namespace rockfit::python {
namespace {

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
  const io::MetricsOptions options = app::MakeMetricsOptions(args);
  io::MetricsSummary m;
  {
    py::gil_scoped_release release;
    m = io::ComputeTrialMetrics(r.recording, block, options);
  }
  const io::Recording& rec = r.recording;
  py::dict d = FromJson(app::MetricsJson(r.trial, rec, block, options, m));  // the keys of `rockfit metrics --json`
  for (const char* key : {"avrf_ratios", "avrf_peak_times", "avrf_peak_angles", "impact_times", "phi_x_anchor_times"}) {
    d[key] = OwnedArray(d[key].cast<std::vector<double>>());
  }
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
