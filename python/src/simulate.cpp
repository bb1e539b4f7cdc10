// rockfit.simulate: the hybrid simulator (core/simulator.hpp) with the fields of `rockfit simulate --json`, the
// samples as numpy arrays. The GIL is released while the simulator runs.
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "bindings.hpp"
#include "rockfit/app/option_grammar.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::python {
namespace {

core::StopCondition ParseStop(const std::string& text) {
  core::StopCondition stop = core::StopCondition::kPhase4;
  if (core::FromString(text, &stop)) return stop;
  throw InvalidArgument("stop must be 'phase4', 'rest', 'overturned' or 't_max', got '" + text + "'");
}

py::list ImpactRecords(const std::vector<core::ImpactRecord>& impacts) {
  py::list out;
  for (const core::ImpactRecord& i : impacts) {
    py::dict d;
    d["t"] = i.t_s;
    d["kind"] = core::ToString(i.kind);
    d["contact_before"] = i.contact_before.ToString();
    d["contact_after"] = i.kind == core::ImpactKind::kRest ? std::string("base") : i.contact_after.ToString();
    d["omega_minus_B"] = Vector3Array(i.w_minus_B);
    d["omega_plus_B"] = Vector3Array(i.w_plus_B);
    d["omega_minus_W"] = Vector3Array(i.w_minus_W);
    d["omega_plus_W"] = Vector3Array(i.w_plus_W);
    d["tau"] = i.tau;
    d["delta_energy"] = i.delta_energy_J;
    d["status"] = core::ToString(i.status);
    out.append(MakeRecord("Impact", d));
  }
  return out;
}

py::object Diagnostics(const core::Trajectory& t) {
  py::list segments;
  double min_normal = std::numeric_limits<double>::infinity();
  double max_friction = 0.0;
  double max_drift = 0.0;
  for (const core::SegmentDiagnostics& s : t.segments) {
    py::dict d;
    d["t_begin"] = s.t_begin_s;
    d["t_end"] = s.t_end_s;
    d["mode"] = s.mode.ToString();
    d["min_normal_force"] = s.min_normal_force_N;
    d["max_friction_ratio"] = s.max_friction_ratio;
    d["energy_drift_rel"] = s.energy_drift_rel;
    segments.append(MakeRecord("Segment", d));
    min_normal = std::min(min_normal, s.min_normal_force_N);
    max_friction = std::max(max_friction, s.max_friction_ratio);
    max_drift = std::max(max_drift, s.energy_drift_rel);
  }
  py::dict d;
  d["wall_time_s"] = t.wall_time_s;
  d["num_steps"] = t.num_steps;
  d["num_evaluations"] = t.num_evaluations;
  d["min_normal_force"] = std::isfinite(min_normal) ? py::object(py::float_(min_normal)) : py::none();
  d["max_friction_ratio"] = max_friction;
  d["max_energy_drift_rel"] = max_drift;
  d["segments"] = segments;
  return MakeRecord("Diagnostics", d);
}

py::object Simulate(const core::Block& block, double alpha, double lambda, double tau_edge, double lambda_lat,
                    double lambda_lon, const std::string& facet_tau, std::pair<int, int> release_edge, double rate,
                    const std::string& stop, double t_max, double zeno_dt, double rest_height, double gravity,
                    std::size_t max_impacts, double rel_tol, double abs_tol, double event_tol, double max_step,
                    const py::object& sample_times, bool sample_attitude) {
  core::ModelParameters params;
  params.alpha_rad = alpha;
  params.lambda = lambda;
  params.tau_edge = tau_edge;
  params.lambda_lat = lambda_lat;
  params.lambda_lon = lambda_lon;
  params.facet_tau_rule = app::ParseFacetTauRule(facet_tau);
  core::SimulationOptions options;
  options.rate_hz = rate;
  if (!sample_times.is_none()) options.sample_times_s = ToDoubles(sample_times, "sample_times");
  options.stop = ParseStop(stop);
  options.t_max_s = t_max;
  options.release_edge_first = release_edge.first;
  options.release_edge_second = release_edge.second;
  options.zeno_dt_s = zeno_dt;
  options.rest_energy_height_m = rest_height;
  options.gravity_m_s2 = gravity;
  options.max_impacts = max_impacts;
  options.rel_tol = rel_tol;
  options.abs_tol = abs_tol;
  options.event_time_tol_s = event_tol;
  options.max_step_s = max_step;
  options.sample_attitude = sample_attitude;

  core::Trajectory t;
  {
    py::gil_scoped_release release;
    t = core::Simulate(block, params, options);
  }
  py::dict d;  // the keys of `rockfit simulate --json`, with the samples at the top level
  d["t_end"] = t.t_end_s;
  d["end_reason"] = core::ToString(t.end_reason);
  d["message"] = t.message;
  d["block"] = BlockDict(block);
  d["parameters"] = py::dict(py::arg("alpha") = alpha, py::arg("lambda") = lambda, py::arg("tau_edge") = tau_edge,
                             py::arg("lambda_lat") = lambda_lat, py::arg("lambda_lon") = lambda_lon,
                             py::arg("facet_tau") = core::ToString(params.facet_tau_rule),
                             py::arg("stop") = core::ToString(options.stop));
  d["impacts"] = ImpactRecords(t.impacts);
  std::vector<std::string> modes;
  modes.reserve(t.mode.size());
  for (const core::Mode& mode : t.mode) modes.push_back(mode.ToString());
  d["t"] = OwnedArray(std::move(t.t_s));
  d["w_B"] = OwnedArray(std::move(t.w_B));
  d["q_WB"] = QuaternionArray(t.q_WB);
  d["euler_zyx"] = OwnedArray(std::move(t.euler_zyx));
  d["mode"] = modes;
  d["diagnostics"] = Diagnostics(t);
  return MakeRecord("Simulation", d);
}

}  // namespace

void RegisterSimulate(py::module_& m) {
  const core::ModelParameters p;
  const core::SimulationOptions o;
  m.def("simulate", &Simulate, py::arg("block"), py::kw_only(), py::arg("alpha") = p.alpha_rad,
        py::arg("lambda_") = p.lambda, py::arg("tau_edge") = p.tau_edge, py::arg("lambda_lat") = p.lambda_lat,
        py::arg("lambda_lon") = p.lambda_lon, py::arg("facet_tau") = "no-spin",
        py::arg("release_edge") = std::make_pair(o.release_edge_first, o.release_edge_second),
        py::arg("rate") = o.rate_hz, py::arg("stop") = core::ToString(o.stop), py::arg("t_max") = o.t_max_s,
        py::arg("zeno_dt") = o.zeno_dt_s, py::arg("rest_height") = o.rest_energy_height_m,
        py::arg("gravity") = o.gravity_m_s2, py::arg("max_impacts") = o.max_impacts, py::arg("rel_tol") = o.rel_tol,
        py::arg("abs_tol") = o.abs_tol, py::arg("event_tol") = o.event_time_tol_s, py::arg("max_step") = o.max_step_s,
        py::arg("sample_times") = py::none(), py::arg("sample_attitude") = true,
        "Simulates the free 3D rocking of the block released from rest on a base edge, as `rockfit simulate --json`\n"
        "(edge and vertex rocking joined by facet and edge impacts, Zeno handling, rest, overturning).\n\n"
        "alpha: release tilt [rad] (the +x side lifted for the default release_edge (1, 2)); lambda_: λ of edge\n"
        "impacts (19); tau_edge: τ of edge impacts [N·m·s]; lambda_lat, lambda_lon: (21); facet_tau: 'no-spin'\n"
        "(24) or 'zero'. rate: output rate [Hz] (samples at k/rate) unless sample_times [s] are given; stop:\n"
        "'phase4', 'rest', 'overturned' or 't_max'; t_max [s]; zeno_dt [s]; rest_height [m]; gravity [m/s²];\n"
        "max_impacts; rel_tol, abs_tol, event_tol [s], max_step [s]: integrator; sample_attitude=False fills only\n"
        "t, w_B and mode (faster).\n\n"
        "Returns a Record 'Simulation': t_end [s], end_reason ('phase4', 'rest', 'overturned', 't_max', 'failed'),\n"
        "message, block, parameters, impacts (Records t [s], kind, contact_before, contact_after, omega_minus_B,\n"
        "omega_plus_B, omega_minus_W, omega_plus_W [rad/s], tau [N·m·s], delta_energy [J], status), the samples\n"
        "t [s] (N,), w_B [rad/s] (N, 3), q_WB (N, 4) scalar first, euler_zyx [rad] (N, 3) as (φz, φy, φx), mode\n"
        "(list of 'V1V2', 'V3', 'rest', …), and diagnostics (wall_time_s, num_steps, num_evaluations,\n"
        "min_normal_force [N], max_friction_ratio, max_energy_drift_rel, segments). A failed run is end_reason\n"
        "'failed' with a message, not an exception. The GIL is released while it runs.");
}

}  // namespace rockfit::python
