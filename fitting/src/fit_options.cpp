#include "rockfit/fitting/fit_options.hpp"

#include <cmath>

#include <fmt/format.h>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/enum_names.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

// z of the two-sided 95 % interval: the signed root the aimed profile points must pass.
constexpr double kZ95 = 1.959963984540054;

}  // namespace

// Calibrated on the tuning families of the coverage studies, 100 trials each (fitting/README.md, "Intervals under
// model error"): with q = 0.5 (half a sample period, the resolution of an impact time on the sample grid),
// c = 1.1 is the smallest c (step 0.05) with which the 95 % intervals of t0, α, the λ's and the release roll
// hold the truth in at least 90 % of the `synth`, rolled-MuJoCo (fitted without and, as by default, with the
// release roll) and gyro-scale trials. The rolled MuJoCo releases fitted with their roll bind (the roll: 89 %
// at 1.05): MuJoCo's soft corner contact biases the roll and α low. Without that family it was 0.75.
const double kDefaultModelErrorWidening = 1.1;
const double kDefaultT0FloorSamples = 0.5;

// The model's exact derivatives in the Ceres stage and in the standard errors and intervals: off, because with them
// the fits of the coverage study did not stay within 0.1 % of ε (fitting/README.md, "Exact derivatives (3D fits)").
const bool kDefaultExactJacobian = false;

// The profile re-fits by Nelder–Mead (fitting/README.md, "Intervals", says what the exact ones were measured to do).
const ProfileRefit kDefaultProfileRefit = ProfileRefit::kNelderMead;

namespace {

// The shared checks (rockfit/core/checks.hpp) with the option's name as the user writes it.
// An option's name as the user writes it, for the messages of the shared checks (rockfit/core/checks.hpp).
std::string FitOption(const char* name) { return fmt::format("fit option {}", name); }

// RequirePositive for the value of every parameter of a per-parameter option.
void RequirePositiveEach(const PerParameter& values, const char* name) {
  for (ParameterId id : kAllParameters) {
    RequirePositive(values[static_cast<std::size_t>(id)], fmt::format("{} for {}", FitOption(name), Name(id)));
  }
}

}  // namespace

const char* ToString(FitMethod method) {
  switch (method) {
    case FitMethod::kNelderMead: return "nelder-mead";
    case FitMethod::kCeres: return "ceres";
    case FitMethod::kAuto: return "auto";
  }
  return "?";
}

bool FromString(std::string_view text, FitMethod* value) {
  static constexpr FitMethod kAll[] = {FitMethod::kNelderMead, FitMethod::kCeres, FitMethod::kAuto};
  return core::FromStringAmong(text, kAll, value);
}

FitMethod ParseFitMethod(const std::string& name) {
  FitMethod method = FitMethod::kAuto;
  if (FromString(name, &method)) return method;
  throw InvalidArgument(fmt::format("unknown fit method '{}'; use nelder-mead, ceres or auto", name));
}

void NelderMeadOptions::Validate() const {
  RequireAtLeast(max_evaluations, 1, FitOption("nelder_mead.max_evaluations"));
  RequirePositive(ftol_abs_rad_s, FitOption("nelder_mead.ftol_abs_rad_s"));
  RequireAtLeast(restarts, 0, FitOption("nelder_mead.restarts"));
  RequirePositiveEach(xtol_abs, "nelder_mead.xtol_abs");
  RequirePositiveEach(initial_step, "nelder_mead.initial_step");
}

void CeresOptions::Validate() const {
  RequireAtLeast(max_iterations, 1, FitOption("ceres.max_iterations"));
  RequirePositive(function_tolerance, FitOption("ceres.function_tolerance"));
  RequirePositive(parameter_tolerance, FitOption("ceres.parameter_tolerance"));
  RequirePositive(gradient_tolerance, FitOption("ceres.gradient_tolerance"));
  RequirePositive(soft_l1_scale_rad_s, FitOption("ceres.soft_l1_scale_rad_s"));
  RequirePositiveEach(difference_step, "ceres.difference_step");
}

void GlobalStageOptions::Validate() const {
  RequireAtLeast(num_samples, 1, FitOption("global.num_samples"));
  RequireAtLeast(num_polished, 1, FitOption("global.num_polished"));
  RequireAtLeast(polish_evaluations, 1, FitOption("global.polish_evaluations"));
  RequireAtLeast(num_continued, 1, FitOption("global.num_continued"));
  RequirePositive(first_window_s, FitOption("global.first_window_s"));
  if (!(continuation_growth > 1.0 && std::isfinite(continuation_growth))) {
    throw InvalidArgument(fmt::format("fit option global.continuation_growth must be above 1, got {}", continuation_growth));
  }
  RequireAtLeast(continuation_evaluations, 1, FitOption("global.continuation_evaluations"));
  if (!(continuation_prune_ratio == 0.0 || continuation_prune_ratio > 1.0)) {
    throw InvalidArgument(fmt::format("fit option global.continuation_prune_ratio must be 0 (no stop rule) or above 1, "
                                      "got {}", continuation_prune_ratio));
  }
  RequireAtLeast(scan_points, 1, FitOption("global.scan_points"));
  if (!(scan_prefix_fraction >= 0.0 && scan_prefix_fraction < 1.0)) {
    throw InvalidArgument(
        fmt::format("fit option global.scan_prefix_fraction must lie in [0, 1), got {}", scan_prefix_fraction));
  }
  RequireAtLeast(joint_scan_lat_points, 0, FitOption("global.joint_scan_lat_points"));
  if (!(joint_scan_lat_fraction >= 0.0 && joint_scan_lat_fraction < 1.0)) {
    throw InvalidArgument(
        fmt::format("fit option global.joint_scan_lat_fraction must lie in [0, 1), got {}", joint_scan_lat_fraction));
  }
  RequireAtLeast(ridge_points, 0, FitOption("global.ridge_points"));
  RequirePositive(ridge_t0_halfwidth_s, FitOption("global.ridge_t0_halfwidth_s"));
  RequirePositive(ridge_lambda_lon_step, FitOption("global.ridge_lambda_lon_step"));
  RequirePositive(ridge_alpha_difference_rad, FitOption("global.ridge_alpha_difference_rad"));
  if (!(continuation_step_fraction > 0.0 && continuation_step_fraction <= 1.0)) {
    throw InvalidArgument(fmt::format("fit option global.continuation_step_fraction must lie in (0, 1], got {}",
                                      continuation_step_fraction));
  }
  RequirePositive(t0_halfwidth_s, FitOption("global.t0_halfwidth_s"));
  if (!(simulation_rel_tol == 0.0 || (simulation_rel_tol >= 1e-14 && simulation_rel_tol <= 1e-3))) {
    throw InvalidArgument(fmt::format(
        "fit option global.simulation_rel_tol must be 0 (the model's own) or lie in [1e-14, 1e-3], got {}",
        simulation_rel_tol));
  }
  RequirePositive(alpha_halfwidth_rad, FitOption("global.alpha_halfwidth_rad"));
}

const char* ToString(IntervalMethod method) {
  switch (method) {
    case IntervalMethod::kNone: return "none";
    case IntervalMethod::kFast: return "fast";
    case IntervalMethod::kThorough: return "thorough";
  }
  return "?";
}

bool FromString(std::string_view text, IntervalMethod* value) {
  static constexpr IntervalMethod kAll[] = {IntervalMethod::kNone, IntervalMethod::kFast, IntervalMethod::kThorough};
  return core::FromStringAmong(text, kAll, value);
}

const char* ToString(ProfileRefit refit) {
  switch (refit) {
    case ProfileRefit::kNelderMead: return "nelder-mead";
    case ProfileRefit::kExact: return "exact";
  }
  return "?";
}

bool FromString(std::string_view text, ProfileRefit* value) {
  static constexpr ProfileRefit kAll[] = {ProfileRefit::kNelderMead, ProfileRefit::kExact};
  return core::FromStringAmong(text, kAll, value);
}

IntervalMethod ParseIntervalMethod(const std::string& name) {
  IntervalMethod method = IntervalMethod::kNone;
  if (FromString(name, &method)) return method;
  throw InvalidArgument(fmt::format("unknown interval method '{}'; use none, fast or thorough", name));
}

void IntervalOptions::Validate() const {
  if (!(std::isfinite(model_error_widening) && model_error_widening >= 0.0)) {
    throw InvalidArgument(fmt::format("intervals: model_error_widening must be a finite coefficient ≥ 0, got {}",
                                      model_error_widening));
  }
  if (!(std::isfinite(t0_floor_samples) && t0_floor_samples >= 0.0)) {
    throw InvalidArgument(fmt::format("intervals: t0_floor_samples must be a finite number of sample periods ≥ 0, got {}",
                                      t0_floor_samples));
  }
  RequirePositive(noise_correlation_window_s, FitOption("intervals.noise_correlation_window_s"));
  if (!(model_error_allowance >= 1.0 && std::isfinite(model_error_allowance))) {
    throw InvalidArgument(fmt::format("fit option intervals.model_error_allowance must be at least 1, got {}",
                                      model_error_allowance));
  }
  RequireAtLeast(profile_evaluations, 1, FitOption("intervals.profile_evaluations"));
  RequireAtLeast(centre_evaluations, 0, FitOption("intervals.centre_evaluations"));
  RequireAtLeast(profile_points, 2, FitOption("intervals.profile_points"));
  if (profile_refit != ProfileRefit::kNelderMead && profile_refit != ProfileRefit::kExact) {
    throw InvalidArgument(fmt::format("fit option intervals.profile_refit must be nelder-mead or exact, got the value {}",
                                      static_cast<int>(profile_refit)));
  }
  RequireAtLeast(refit_iterations, 1, FitOption("intervals.refit_iterations"));
  RequireAtLeast(centre_iterations, 0, FitOption("intervals.centre_iterations"));
  if (!(profile_growth > 1.0 && std::isfinite(profile_growth))) {
    throw InvalidArgument(fmt::format("fit option intervals.profile_growth must be above 1, got {}", profile_growth));
  }
  if (!(profile_aim_rho > kZ95 && std::isfinite(profile_aim_rho))) {
    throw InvalidArgument(fmt::format("fit option intervals.profile_aim_rho must be above 1.96 (the 95 % crossing the "
                                      "points must pass), got {}",
                                      profile_aim_rho));
  }
  if (!(profile_refine_above_rho >= profile_aim_rho && std::isfinite(profile_refine_above_rho))) {
    throw InvalidArgument(fmt::format("fit option intervals.profile_refine_above_rho must be finite and at least "
                                      "profile_aim_rho ({}), got {}",
                                      profile_aim_rho, profile_refine_above_rho));
  }
  RequirePositiveEach(min_step, "intervals.min_step");
  if (!(undetermined_range_fraction > 0.0 && undetermined_range_fraction <= 1.0)) {
    throw InvalidArgument(fmt::format("fit option intervals.undetermined_range_fraction must lie in (0, 1], got {}",
                                      undetermined_range_fraction));
  }
}

void IdentifiabilityOptions::Validate() const {
  RequirePositiveEach(probe_step, "identifiability.probe_step");
  RequirePositive(relative_tolerance, FitOption("identifiability.relative_tolerance"));
}

void FitOptions::Validate() const {
  global.Validate();
  nelder_mead.Validate();
  ceres.Validate();
  identifiability.Validate();
  intervals.Validate();
  lateral_motion.Validate();
  model_error.Validate();
  motion_before_release.Validate();
  lateral_rescan.Validate();
  window_extension.Validate();
  final_stage.Validate();
  RequireAtLeast(num_threads, 0, FitOption("num_threads"));
  RequirePositive(auto_soft_l1_fraction, FitOption("auto_soft_l1_fraction"));
  if (!(at_bound_fraction >= 0.0 && at_bound_fraction < 0.5)) {
    throw InvalidArgument(fmt::format("fit option at_bound_fraction must lie in [0, 0.5), got {}", at_bound_fraction));
  }
}

}  // namespace rockfit::fitting
