#include "rockfit/fitting/fit_summary.hpp"
#include "rockfit/core/enum_names.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace rockfit::fitting {
namespace {

nlohmann::json NumberOrNull(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

}  // namespace

const char* ToString(WarningKind kind) {
  switch (kind) {
    case WarningKind::kAtBound: return "at_bound";
    case WarningKind::kNotIdentifiable: return "not_identifiable";
    case WarningKind::kSimulationFailures: return "simulation_failures";
    case WarningKind::kNotConverged: return "not_converged";
    case WarningKind::kStdErrorUnavailable: return "std_error_unavailable";
    case WarningKind::kInfeasible: return "infeasible";
    case WarningKind::kPoorFit: return "poor_fit";
    case WarningKind::kSecondBasin: return "second_basin";
    case WarningKind::kNotDetermined: return "not_determined";
    case WarningKind::kMovedByIntervals: return "moved_by_intervals";
    case WarningKind::kLateralMotionUnexplained: return "lateral_motion_unexplained";
    case WarningKind::kMovedByLateralRescan: return "moved_by_lateral_rescan";
    case WarningKind::kWindowExtended: return "window_extended";
    case WarningKind::kModelErrorDominates: return "model_error_dominates";
    case WarningKind::kReleaseTiltDisagrees: return "release_tilt_disagrees";
    case WarningKind::kTurnedBeforeFall: return "turned_before_fall";
    case WarningKind::kMovingAtRelease: return "moving_at_release";
    case WarningKind::kSensorTurnedAboutZ: return "sensor_turned_about_z";
  }
  return "?";
}

bool FromString(std::string_view text, WarningKind* value) {
  static constexpr WarningKind kAll[] = {WarningKind::kAtBound, WarningKind::kNotIdentifiable, WarningKind::kSimulationFailures, WarningKind::kNotConverged, WarningKind::kStdErrorUnavailable, WarningKind::kInfeasible, WarningKind::kPoorFit, WarningKind::kSecondBasin, WarningKind::kNotDetermined, WarningKind::kMovedByIntervals, WarningKind::kLateralMotionUnexplained, WarningKind::kMovedByLateralRescan, WarningKind::kModelErrorDominates, WarningKind::kWindowExtended, WarningKind::kReleaseTiltDisagrees, WarningKind::kTurnedBeforeFall, WarningKind::kMovingAtRelease, WarningKind::kSensorTurnedAboutZ};
  return core::FromStringAmong(text, kAll, value);
}

bool FitSummary::HasWarning(WarningKind kind, const std::string& parameter) const {
  for (const FitWarning& w : warnings) {
    if (w.kind == kind && (parameter.empty() || w.parameter == parameter)) return true;
  }
  return false;
}

std::string FitSummary::BriefReport() const {
  return fmt::format("ε = {:.6g} rad/s (start {:.6g}), {} simulations in {:.3f} s ({:.0f}/s), {}, {} warning(s)",
                     epsilon_rad_s, epsilon_initial_rad_s, simulations, wall_time_s, simulations_per_second,
                     termination, warnings.size());
}

std::string FitSummary::FullReport() const {
  std::ostringstream out;
  out << fmt::format("{:<11} {:>12} {:>12} {:>10} {:>10}  {:<25} {:<25} {:<9} {}\n", "parameter", "value", "std error",
                     "lower", "upper", "68 % interval", "95 % interval", "determined", "");
  for (ParameterId id : parameters.ReportedIds()) {
    const Parameter& p = parameters[id];
    const std::size_t k = static_cast<std::size_t>(id);
    std::string flags = p.fixed ? "fixed" : "";
    if (!p.fixed && at_bound[k]) flags += "at bound ";
    if (!p.fixed && !identifiable[k]) flags += "not identifiable";
    const std::string se = std::isfinite(std_error[k]) ? fmt::format("{:12.5g}", std_error[k]) : fmt::format("{:>12}", "-");
    auto end = [](double v) { return std::isnan(v) ? std::string("open") : fmt::format("{:.6g}", v); };
    auto interval = [&](const Interval& i) {
      return p.fixed ? std::string("—") : fmt::format("[{}, {}]", end(i[0]), end(i[1]));
    };
    const auto& d = uncertainty.determined[k];
    out << fmt::format("{:<11} {:12.6g} {} {:10.4g} {:10.4g}  {:<25} {:<25} {:<9} {} {}\n", Name(id), p.value, se, p.lower,
                       p.upper, interval(uncertainty.interval_68[k]), interval(uncertainty.interval_95[k]),
                       d ? ToString(*d) : "—", Unit(id), flags);
  }
  out << fmt::format("ε (28)      {:.6g} rad/s (at the start {:.6g} rad/s), window ends at t_end = {:.4f} s\n",
                     epsilon_rad_s, epsilon_initial_rad_s, t_end_s);
  out << "window      " << WindowReportText(window) << "\n";
  out << "model error " << ModelErrorText(model_error) << "\n";
  out << "before release " << MotionBeforeReleaseText(motion_before_release) << "\n";
  if (gyro_scale.mode != GyroScaleMode::kOff) out << "gyro scale  " << GyroScaleText(gyro_scale) << "\n";
  if (release_roll_choice) out << "release roll " << ReleaseRollChoiceText(*release_roll_choice) << "\n";
  if (release_tilt) out << "release tilt " << ReleaseTiltCheckText(*release_tilt) << "\n";
  out << fmt::format("effort      {} simulations in {:.3f} s ({:.0f} per second), method {}\n", simulations,
                     wall_time_s, simulations_per_second, ToString(method));
  for (const StageReport& s : stages) {
    out << fmt::format("  stage {:<14} ε = {:<11.6g} {:>6} evaluations {:8.3f} s  {}\n", s.name, s.epsilon_rad_s,
                       s.evaluations, s.wall_time_s, s.termination);
  }
  out << fmt::format("termination {} (kept: {})\n", termination, kept_stage);
  const std::string with_sensitivities =
      uncertainty.sensitivity_runs > 0 ? fmt::format(", {} with sensitivities", uncertainty.sensitivity_runs) : "";
  out << fmt::format("intervals   {} ({} simulations{}, {:.3f} s)\n", uncertainty.description, uncertainty.evaluations,
                     with_sensitivities, uncertainty.wall_time_s);
  for (const std::string& s : uncertainty.statements) out << "data fix    " << s << "\n";
  for (const FitWarning& w : warnings) out << "warning     " << w.message << "\n";
  return out.str();
}

std::string FitSummary::ToJson(const std::string& trial) const {
  nlohmann::json j;
  if (!trial.empty()) j["trial"] = trial;
  nlohmann::json params = nlohmann::json::object();
  for (ParameterId id : parameters.ReportedIds()) {
    const Parameter& p = parameters[id];
    const std::size_t k = static_cast<std::size_t>(id);
    params[Name(id)] = {{"value", p.value},
                        {"lower", NumberOrNull(p.lower)},
                        {"upper", NumberOrNull(p.upper)},
                        {"fixed", p.fixed},
                        {"std_error", NumberOrNull(std_error[k])},
                        {"identifiable", identifiable[k]},
                        {"at_bound", at_bound[k]},
                        {"interval_68", nlohmann::json::parse(IntervalJson(uncertainty.interval_68[k], p.fixed))},
                        {"interval_95", nlohmann::json::parse(IntervalJson(uncertainty.interval_95[k], p.fixed))},
                        {"determined", uncertainty.determined[k] ? nlohmann::json(ToString(*uncertainty.determined[k]))
                                                                 : nlohmann::json()},
                        {"start", start.value(id)},
                        {"unit", Unit(id)}};
  }
  j["parameters"] = params;
  j["correlation"] = nlohmann::json::parse(CorrelationJson(uncertainty, parameters));
  j["uncertainty_method"] = ToString(uncertainty.method);
  j["uncertainty"] = {{"description", uncertainty.description},
                      {"correlation_factor", uncertainty.correlation_factor},
      {"noise_inflation", nlohmann::json::parse(NoiseInflationJson(uncertainty, parameters))},
                      {"noise_inflation_68", std::isnan(uncertainty.bulk_inflation) ? nlohmann::json()
                                                                                    : nlohmann::json(uncertainty.bulk_inflation)},
                      {"noise_rms_rad_s", uncertainty.noise_rms_rad_s},
                      {"statements", uncertainty.statements},
                      {"simulations", uncertainty.evaluations},
                      {"wall_s", uncertainty.wall_time_s}};
  // Only with clipped samples (censored_noise_level.hpp): the documents of other fits keep their keys.
  if (uncertainty.censored_noise_factor != 1.0) j["uncertainty"]["censored_noise_factor"] = uncertainty.censored_noise_factor;
  // Only with the exact profile re-fits (IntervalOptions::profile_refit): the documents of other fits keep their keys.
  if (uncertainty.sensitivity_runs > 0) {
    j["uncertainty"]["simulations_with_sensitivities"] = uncertainty.sensitivity_runs;
    j["uncertainty"]["exact_refits"] = uncertainty.exact_refits;
    j["uncertainty"]["nelder_mead_refits"] = uncertainty.nelder_mead_refits;
  }
  j["lateral_motion"] = nlohmann::json::parse(LateralMotionJson(lateral_motion));
  j["model_error"] = nlohmann::json::parse(ModelErrorJson(model_error));
  j["motion_before_release"] = nlohmann::json::parse(MotionBeforeReleaseJson(motion_before_release));
  // Only when estimated: the documents of fits without it keep their keys.
  if (gyro_scale.mode != GyroScaleMode::kOff) j["gyro_scale"] = nlohmann::json::parse(GyroScaleJson(gyro_scale));
  if (release_roll_choice) j["release_roll_choice"] = nlohmann::json::parse(ReleaseRollChoiceJson(*release_roll_choice));
  if (release_tilt) j["release_tilt"] = nlohmann::json::parse(ReleaseTiltCheckJson(*release_tilt));
  j["epsilon"] = epsilon_rad_s;
  j["epsilon_initial"] = epsilon_initial_rad_s;
  j["feasible"] = feasible;
  j["t_end"] = t_end_s;
  j["window"] = nlohmann::json::parse(WindowReportJson(window));
  j["simulations"] = simulations;
  j["simulations_per_second"] = simulations_per_second;
  j["wall_s"] = wall_time_s;
  j["method"] = ToString(method);
  j["termination"] = termination;
  j["termination_type"] = ToString(termination_type);
  j["converged"] = converged;
  j["kept_stage"] = kept_stage;
  nlohmann::json warnings_json = nlohmann::json::array();
  for (const FitWarning& w : warnings) {
    warnings_json.push_back({{"kind", ToString(w.kind)}, {"parameter", w.parameter}, {"message", w.message}});
  }
  j["warnings"] = warnings_json;
  j["failures"] = failures_by_reason;
  nlohmann::json stages_json = nlohmann::json::array();
  for (const StageReport& s : stages) {
    stages_json.push_back({{"name", s.name},
                           {"epsilon", s.epsilon_rad_s},
                           {"evaluations", s.evaluations},
                           {"wall_s", s.wall_time_s},
                           {"termination_type", ToString(s.termination_type)},
                           {"termination", s.termination}});
  }
  j["stages"] = stages_json;
  j["model"] = model_description;
  return j.dump();
}

}  // namespace rockfit::fitting
