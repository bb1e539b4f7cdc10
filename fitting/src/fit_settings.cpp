#include "rockfit/fitting/fit_settings.hpp"

#include <cstdint>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace rockfit::fitting {
namespace {

nlohmann::json PerParameterJson(const PerParameter& values) {
  nlohmann::json j;
  for (ParameterId id : kAllParameters) j[Name(id)] = values[static_cast<std::size_t>(id)];
  return j;
}

}  // namespace

std::string FitSettingsJson(const ParameterSet& parameters, const TrialFitOptions& o, const std::string& extra_json) {
  nlohmann::json j;  // nlohmann::json objects keep their keys sorted: the text is canonical
  j["fit_schema_version"] = 1;
  for (ParameterId id : kAllParameters) {
    const Parameter& p = parameters[id];
    nlohmann::json q = {{"fixed", p.fixed}, {"lower", std::isfinite(p.lower) ? nlohmann::json(p.lower) : nlohmann::json()},
                        {"upper", std::isfinite(p.upper) ? nlohmann::json(p.upper) : nlohmann::json()}};
    // The value matters for fixed parameters and for starting points given by the caller.
    if (p.fixed || !o.fit.start_from_data) q["value"] = p.value;
    j["parameters"][Name(id)] = q;
  }
  j["facet_tau_rule"] = core::ToString(parameters.facet_tau_rule());
  const FitOptions& f = o.fit;
  j["method"] = ToString(f.method);
  j["start_from_data"] = f.start_from_data;
  j["global"] = {{"enabled", f.global.enabled},
                 {"num_samples", f.global.num_samples},
                 {"num_polished", f.global.num_polished},
                 {"polish_evaluations", f.global.polish_evaluations},
                 {"num_continued", f.global.num_continued},
                 {"first_window_s", f.global.first_window_s},
                 {"continuation_growth", f.global.continuation_growth},
                 {"continuation_evaluations", f.global.continuation_evaluations},
                 {"continuation_step_fraction", f.global.continuation_step_fraction},
                 {"scan_points", f.global.scan_points},
                 {"final_scan", f.global.final_scan},
                 {"seed", f.global.seed},
                 {"t0_halfwidth_s", f.global.t0_halfwidth_s},
                 {"alpha_halfwidth_rad", f.global.alpha_halfwidth_rad}};
  j["nelder_mead"] = {{"max_evaluations", f.nelder_mead.max_evaluations},
                      {"ftol_abs_rad_s", f.nelder_mead.ftol_abs_rad_s},
                      {"xtol_abs", PerParameterJson(f.nelder_mead.xtol_abs)},
                      {"initial_step", PerParameterJson(f.nelder_mead.initial_step)},
                      {"restarts", f.nelder_mead.restarts}};
  j["ceres"] = {{"max_iterations", f.ceres.max_iterations},
                {"function_tolerance", f.ceres.function_tolerance},
                {"parameter_tolerance", f.ceres.parameter_tolerance},
                {"gradient_tolerance", f.ceres.gradient_tolerance},
                {"soft_l1_scale_rad_s", f.ceres.soft_l1_scale_rad_s},
                {"difference_step", PerParameterJson(f.ceres.difference_step)}};
  j["identifiability"] = {{"probe_step", PerParameterJson(f.identifiability.probe_step)},
                          {"relative_tolerance", f.identifiability.relative_tolerance}};
  j["compute_std_errors"] = f.compute_std_errors;
  j["at_bound_fraction"] = f.at_bound_fraction;
  const EstimateOptions& e = o.estimate;
  j["estimate"] = {{"min_prominence_rad_s", e.impacts.min_prominence_rad_s},
                   {"min_separation_s", e.impacts.min_separation_s},
                   {"t_end_impact", e.t_end_impact},
                   {"t_end_margin_s", e.t_end_margin_s},
                   {"side_samples", e.side_samples},
                   {"post_impact_samples", e.post_impact_samples},
                   {"rest_margin_s", e.rest_margin_s},
                   {"rest_min_duration_s", e.rest_min_duration_s},
                   {"t0_halfwidth_s", e.t0_halfwidth_s}};
  const core::SimulationOptions& s = o.simulation.simulation;
  j["simulation"] = {{"release_edge", fmt::format("{},{}", s.release_edge_first, s.release_edge_second)},
                     {"zeno_dt_s", s.zeno_dt_s},
                     {"rest_energy_height_m", s.rest_energy_height_m},
                     {"gravity_m_s2", s.gravity_m_s2},
                     {"rel_tol", s.rel_tol},
                     {"abs_tol", s.abs_tol},
                     {"event_time_tol_s", s.event_time_tol_s},
                     {"max_step_s", s.max_step_s},
                     {"max_impacts", s.max_impacts}};
  j["t_end_s"] = o.t_end_s ? nlohmann::json(*o.t_end_s) : nlohmann::json();
  j["subtract_rest_bias"] = o.subtract_rest_bias;
  j["input"] = nlohmann::json::parse(extra_json);
  return j.dump();
}

std::string SettingsHash(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a 64 offset basis
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;  // FNV prime
  }
  return fmt::format("{:016x}", hash);
}

}  // namespace rockfit::fitting
