#include "rockfit/fitting/fitter.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/final_stage.hpp"
#include "rockfit/fitting/global_stage.hpp"
#include "rockfit/fitting/gyro_scale_estimate.hpp"
#include "rockfit/fitting/identifiability.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/lateral_motion_check.hpp"
#include "rockfit/fitting/lateral_rescan.hpp"
#include "rockfit/fitting/model_error.hpp"
#include "rockfit/fitting/model_error_widening.hpp"
#include "rockfit/fitting/uncertainty.hpp"
#include "rockfit/fitting/window_extension.hpp"

namespace rockfit::fitting {
namespace {

// The problem the global stage searches: the same one, at the stage's looser simulator tolerance when the model
// has one (GlobalStageOptions::simulation_rel_tol).
Objective GlobalStageObjective(const Objective& objective, const GlobalStageOptions& g) {
  if (g.simulation_rel_tol == 0.0) return objective;
  std::shared_ptr<const TrajectoryModel> loose = objective.model().WithLooserTolerance(g.simulation_rel_tol);
  return loose ? objective.WithModel(std::move(loose)) : objective;
}

// ε above this fraction of the mean measured |ω| over the window is reported as a poor fit. Fits of the
// synthetic sample trials reach 1–2 % (gyro noise and ringing); a wrong block, mounting or window gives tens of
// percent.
constexpr double kPoorFitFraction = 0.2;

struct Candidate {
  std::string stage;
  Eigen::VectorXd x;
  double epsilon_rad_s = 0.0;
  bool feasible = false;
  bool converged = false;
  TerminationType termination_type = TerminationType::kNotASearch;
  std::string termination;
};

// Feasible beats infeasible; then lower ε; ties keep the earlier stage.
bool Better(const Candidate& a, const Candidate& b) {
  if (a.feasible != b.feasible) return a.feasible;
  return a.epsilon_rad_s < b.epsilon_rad_s;
}

Candidate FromLocal(const std::string& stage, const LocalResult& r) {
  return {stage, r.x, r.epsilon_rad_s, r.feasible, r.converged, r.termination_type, r.termination};
}

std::string FailureList(const std::map<std::string, std::int64_t>& failures) {
  std::string list;
  for (const auto& [reason, count] : failures) list += fmt::format("{}{} × {}", list.empty() ? "" : ", ", count, reason);
  return list;
}

double SecondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The stages of `options` from x_start (start point, global stage, the local back ends) in turn; the summary keeps
// the best point by (28), whatever the back end optimised. Returns the global stage's candidates.
std::vector<std::pair<Eigen::VectorXd, double>> RunStages(const Objective& objective, const Eigen::VectorXd& x_start,
                                                         const FitOptions& options, FitSummary* summary) {
  std::vector<Candidate> candidates;
  {
    const auto t = std::chrono::steady_clock::now();
    const Evaluation e = objective.EvaluateFree(x_start);
    summary->epsilon_initial_rad_s = e.epsilon_rad_s;
    candidates.push_back({"start", x_start, e.epsilon_rad_s, e.feasible, false, TerminationType::kNotASearch, "start point"});
    summary->stages.push_back({"start", e.epsilon_rad_s, 1, SecondsSince(t), TerminationType::kNotASearch,
                               e.feasible ? "evaluated" : e.failure_category()});
  }
  Eigen::VectorXd x_current = x_start;
  std::vector<std::pair<Eigen::VectorXd, double>> global_candidates;

  if (options.global.enabled) {
    GlobalStageResult g = RunGlobalStage(GlobalStageObjective(objective, options.global), x_start, options);
    // The stage's ε came from its own tolerance: every candidate is evaluated again at the model's.
    for (auto& [x, epsilon] : g.candidates) epsilon = objective.EvaluateFree(x).epsilon_rad_s;
    g.evaluations += static_cast<std::int64_t>(g.candidates.size());
    if (g.feasible) {
      const Evaluation best = objective.EvaluateFree(g.best_x);
      g.best_epsilon_rad_s = best.epsilon_rad_s;
      g.feasible = best.feasible;
      ++g.evaluations;
    }
    global_candidates = g.candidates;
    const std::string termination =
        fmt::format("{} of {} first-window starts feasible, {} continued to the full window", g.num_feasible_samples,
                    g.num_samples, g.num_continued);
    Candidate c{"global", g.best_x, g.best_epsilon_rad_s, g.feasible, g.converged, TerminationType::kNotASearch, termination};
    summary->stages.push_back(
        {"global", g.best_epsilon_rad_s, g.evaluations, g.wall_time_s, TerminationType::kNotASearch, termination});
    if (Better(c, candidates.front())) x_current = c.x;
    candidates.push_back(c);
  }
  auto run_nelder_mead = [&] {
    const LocalResult r = MakeNelderMead(options.nelder_mead)->Minimize(objective, x_current);
    summary->stages.push_back({"nelder-mead", r.epsilon_rad_s, r.evaluations, r.wall_time_s, r.termination_type, r.termination});
    if (r.feasible) x_current = r.x;
    candidates.push_back(FromLocal("nelder-mead", r));
  };
  auto run_ceres = [&](const CeresOptions& ceres_options) {
    const LocalResult r = MakeCeres(ceres_options)->Minimize(objective, x_current);
    summary->stages.push_back({"ceres", r.epsilon_rad_s, r.evaluations, r.wall_time_s, r.termination_type, r.termination});
    candidates.push_back(FromLocal("ceres", r));
    return r;
  };
  if (options.method == FitMethod::kAuto && options.auto_exact_ceres_first && options.ceres.exact_jacobian) {
    // The exact Ceres stage first; Nelder–Mead (from the better of the two points) only where Ceres could not
    // use exact derivatives throughout, failed, or ended above the point it started from.
    const Candidate before = *std::min_element(candidates.begin(), candidates.end(),
                                               [](const Candidate& a, const Candidate& b) { return Better(a, b); });
    // Its soft-L1 scale well below the residuals at the start: the Ceres cost is then nearly c·T_ref·(28) and its
    // minimum that of (28), not of the sum of squares (fitting/README.md, "The back ends").
    CeresOptions exact_options = options.ceres;
    if (before.feasible && before.epsilon_rad_s > 0.0) {
      exact_options.soft_l1_scale_rad_s =
          std::min(exact_options.soft_l1_scale_rad_s, options.auto_soft_l1_fraction * before.epsilon_rad_s);
    }
    const LocalResult r = run_ceres(exact_options);
    const bool ceres_enough = r.exact_derivatives && r.feasible && r.termination_type != TerminationType::kFailure &&
                              r.epsilon_rad_s <= before.epsilon_rad_s;
    if (!ceres_enough) {
      if (r.feasible && r.epsilon_rad_s < before.epsilon_rad_s) x_current = r.x;
      run_nelder_mead();
    }
  } else {
    if (options.method == FitMethod::kNelderMead || options.method == FitMethod::kAuto) run_nelder_mead();
    if (options.method == FitMethod::kCeres || options.method == FitMethod::kAuto) run_ceres(options.ceres);
  }

  // Keep the best point by (28), whatever the back end optimised.
  const Candidate* best = &candidates.front();
  for (const Candidate& c : candidates) {
    if (Better(c, *best)) best = &c;
  }
  if (options.final_stage.enabled && best->feasible) {
    // The grids and short searches around the best point that make its end less dependent on the start
    // (final_stage.hpp), at the global stage's tolerance as the global stage (they only have to find a basin); the
    // point they end at is evaluated again at the model's and kept only where (28) is lower there.
    const Objective loose = GlobalStageObjective(objective, options.global);
    const FinalStageResult f = RunFinalStage(loose, best->x, loose.EvaluateFree(best->x).epsilon_rad_s, true,
                                             options.final_stage, options.nelder_mead);
    const Evaluation at_model = f.improved ? objective.EvaluateFree(f.x) : Evaluation{};
    const bool lower = f.improved && at_model.feasible && at_model.epsilon_rad_s < best->epsilon_rad_s;
    summary->stages.push_back({"final", lower ? at_model.epsilon_rad_s : best->epsilon_rad_s,
                               f.evaluations + 1 + (f.improved ? 1 : 0), f.wall_time_s,
                               lower ? TerminationType::kConvergence : TerminationType::kNotASearch, f.termination});
    if (lower) {
      const Candidate moved{"final", f.x, at_model.epsilon_rad_s, true, best->converged, best->termination_type,
                            best->termination};
      candidates.push_back(moved);
      best = &candidates.back();
    }
  }
  summary->parameters = objective.WithFree(best->x);
  summary->epsilon_rad_s = best->epsilon_rad_s;
  summary->feasible = best->feasible;
  summary->termination_type = best->termination_type;
  summary->termination = best->termination;
  summary->kept_stage = best->stage;
  // The start and the global stage are not convergence tests of their own; a local stage that ran from the
  // kept point and could not improve it has converged there.
  summary->converged = best->converged;
  for (const Candidate& c : candidates) {
    if (c.converged && c.feasible && c.epsilon_rad_s == best->epsilon_rad_s) summary->converged = true;
  }

  return global_candidates;
}

// A kept point that leaves the recorded out-of-plane motion unexplained, or has weak lateral motion whose
// out-of-plane signal the check cannot judge, may lie on the plateau next to the needle-shaped basin of λ_lat:
// λ_lat is rescanned over growing windows (lateral_rescan.hpp) and polished by Nelder–Mead on the full window;
// the fit moves there when (28) is lower. The point it leaves stays among the candidates (the intervals and the
// second-solution check see it).
// On an extended window (window_extension.hpp) the rescan runs whatever the check says: the window was extended
// because λ_lat was not determined, and the facet impacts it now holds make λ_lat's basin a needle again.
void RescanUnexplainedLateralMotion(const Objective& objective, const FitOptions& options, bool extended_window,
                                    FitSummary* summary, std::vector<std::pair<Eigen::VectorXd, double>>* candidates) {
  // A search of its own: not with --no-global (a local search from the estimate only was asked for).
  if (!options.lateral_rescan.enabled || !options.global.enabled || !summary->feasible) return;
  const LateralMotionCheck check = CheckLateralMotion(objective, summary->parameters, options.lateral_motion);
  const bool unexplained = check.unexplained;
  // Weak lateral motion whose out-of-plane signal is too close to the noise for the check to judge.
  const double lambda_lat = summary->parameters.value(ParameterId::kLambdaLat);
  const bool weak_unjudged = std::abs(lambda_lat) < options.lateral_rescan.below_abs_lambda_lat && !check.judged;
  if (!unexplained && !weak_unjudged && !extended_window) return;
  const LateralRescanResult rescan =
      RunLateralRescan(objective, summary->parameters, options.lateral_rescan, options.nelder_mead, options.num_threads);
  if (!rescan.ran || !rescan.feasible) return;
  LocalResult polish = MakeNelderMead(options.nelder_mead)->Minimize(objective, objective.FreeValues(rescan.at));
  if (!(polish.feasible && polish.epsilon_rad_s <= rescan.epsilon_rad_s)) {
    // The polish did not improve on the rescan (or failed): keep the rescan's point, unconverged.
    polish.x = objective.FreeValues(rescan.at);
    polish.epsilon_rad_s = rescan.epsilon_rad_s;
    polish.converged = false;
    polish.termination_type = TerminationType::kNoConvergence;
    polish.termination = "the polish did not improve on the rescan: " + polish.termination;
  }
  summary->stages.push_back({"lateral-rescan", polish.epsilon_rad_s, rescan.evaluations + polish.evaluations,
                             rescan.wall_time_s + polish.wall_time_s, polish.termination_type,
                             fmt::format("{} windows; {}", rescan.windows, polish.termination)});
  if (!(polish.epsilon_rad_s < summary->epsilon_rad_s)) return;
  const ParameterSet moved = objective.WithFree(polish.x);
  candidates->emplace_back(objective.FreeValues(summary->parameters), summary->epsilon_rad_s);
  summary->warnings.push_back(
      {WarningKind::kMovedByLateralRescan, "",
       fmt::format("{}; a rescan of λ_lat over growing windows found a lower (28): ε {:.6g} → {:.6g} rad/s, λ_lat "
                   "{:.5g} → {:.5g}; the fit moved there",
                   unexplained      ? "the search's result left the recorded out-of-plane motion unexplained"
                   : !weak_unjudged ? "the window was extended for λ_lat"
                                    : fmt::format("the search's result had weak lateral motion (|λ_lat| < {:g}) with an "
                                             "out-of-plane signal too close to the noise for the lateral-motion check",
                                             options.lateral_rescan.below_abs_lambda_lat),
                   summary->epsilon_rad_s, polish.epsilon_rad_s, summary->parameters.value(ParameterId::kLambdaLat),
                   moved.value(ParameterId::kLambdaLat))});
  summary->parameters = moved;
  summary->epsilon_rad_s = polish.epsilon_rad_s;
  summary->termination_type = polish.termination_type;
  summary->termination = polish.termination;
  summary->kept_stage = "lateral-rescan";
  summary->converged = polish.converged;
}

// Identifiability, bounds, standard errors and intervals at the kept point. The profiles of the intervals may
// meet a point with a lower (28) (they leave the basin of the fit along a valley the global stage did not
// follow to its end): the fit then moves there by Nelder–Mead and everything is computed once more.
void AssessKeptPoint(const Objective& objective, const FitOptions& options,
                     const std::vector<std::pair<Eigen::VectorXd, double>>& global_candidates, FitSummary* summary) {
  for (int pass = 0; pass < 2; ++pass) {
    // Identifiability and bounds.
    const std::size_t warnings_before = summary->warnings.size();
    const IdentifiabilityReport ident = CheckIdentifiability(objective, summary->parameters, options.identifiability);
    summary->identifiable = ident.identifiable;
    summary->std_error.fill(std::numeric_limits<double>::quiet_NaN());
    ParameterSet for_covariance = summary->parameters;
    for (ParameterId id : objective.free_ids()) {
      const std::size_t k = static_cast<std::size_t>(id);
      const Parameter& p = summary->parameters[id];
      const double range = p.upper - p.lower;
      const double margin = std::isfinite(range) ? options.at_bound_fraction * range : 0.0;
      summary->at_bound[k] = p.value <= p.lower + margin || p.value >= p.upper - margin;
      if (summary->at_bound[k]) {
        summary->warnings.push_back({WarningKind::kAtBound, Name(id),
                                    fmt::format("{} = {:.6g} {} is at its {} bound; the optimum may lie beyond it", Name(id),
                                                p.value, Unit(id), p.value <= p.lower + margin ? "lower" : "upper")});
      }
      if (!ident.identifiable[k]) summary->warnings.push_back({WarningKind::kNotIdentifiable, Name(id), ident.reason[k]});
      if (summary->at_bound[k] || !ident.identifiable[k]) for_covariance[id].fixed = true;
    }

    // Standard errors of the identifiable parameters that are not at a bound.
    Linearisation lin;
    const bool want_covariance = options.compute_std_errors || options.intervals.method != IntervalMethod::kNone;
    if (want_covariance && summary->feasible && !for_covariance.FreeIds().empty()) {
      const Objective restricted = objective.WithParameters(for_covariance);
      const StandardErrors se =
          ComputeStandardErrors(restricted, restricted.FreeValues(summary->parameters), options.ceres);
      if (options.compute_std_errors) {
        for (std::size_t i = 0; i < restricted.num_free(); ++i) {
          summary->std_error[static_cast<std::size_t>(restricted.free_ids()[i])] = se.std_error[static_cast<Eigen::Index>(i)];
        }
      }
      if (se.inverse_normal_matrix.rows() > 0) {
        lin = {restricted.free_ids(), se.inverse_normal_matrix, se.jacobian, se.residuals};
      }
      if (!se.available && options.compute_std_errors) summary->warnings.push_back({WarningKind::kStdErrorUnavailable, "", "standard errors: " + se.message});
    }

    std::vector<ParameterSet> alternatives;
    for (const auto& c : global_candidates) alternatives.push_back(objective.WithFree(c.first));
    summary->uncertainty = ComputeUncertainty(objective, summary->parameters, summary->epsilon_rad_s, summary->identifiable,
                                             lin, alternatives, options.intervals, options.num_threads);
    if (!summary->feasible || !summary->uncertainty.better_point || pass == 1) break;
    const LocalResult r =
        MakeNelderMead(options.nelder_mead)->Minimize(objective, objective.FreeValues(*summary->uncertainty.better_point));
    summary->stages.push_back(
        {"interval-restart", r.epsilon_rad_s, r.evaluations, r.wall_time_s, r.termination_type, r.termination});
    if (!(r.feasible && r.epsilon_rad_s < summary->epsilon_rad_s)) break;
    summary->warnings.resize(warnings_before);
    summary->warnings.push_back(
        {WarningKind::kMovedByIntervals, "",
         fmt::format("the profiles of the intervals met a lower (28) than the global stage's result: ε {:.6g} → {:.6g} "
                     "rad/s; the fit moved there", summary->epsilon_rad_s, r.epsilon_rad_s)});
    summary->parameters = objective.WithFree(r.x);
    summary->epsilon_rad_s = r.epsilon_rad_s;
    summary->termination_type = r.termination_type;
    summary->termination = r.termination;
    summary->kept_stage = "interval-restart";
    summary->converged = r.converged;
  }
}

void AddSecondSolutionWarning(const Objective& objective, FitSummary* summary) {
  // A second solution: a candidate of the global stage in another basin that the data do not exclude.
  if (summary->feasible && summary->uncertainty.second_solution) {
    const ParameterSet& other = *summary->uncertainty.second_solution;
    const double epsilon = summary->uncertainty.second_solution_epsilon_rad_s;
    std::string values;
    for (ParameterId id : objective.free_ids()) {
      values += fmt::format("{}{} = {:.5g}", values.empty() ? "" : ", ", Name(id), other.value(id));
    }
    summary->warnings.push_back(
        {WarningKind::kSecondBasin, "",
         fmt::format("a second solution in another basin fits nearly as well: {} with ε = {:.6g} rad/s ({:+.2f} % of "
                     "the result's); the data do not decide between them, the intervals include both",
                     values, epsilon, 100.0 * (epsilon / summary->epsilon_rad_s - 1.0))});
  }
}

void ApplyLateralMotionCheck(const Objective& objective, const FitOptions& options, FitSummary* summary) {
  // A fit that leaves the recorded out-of-plane motion unexplained sits on the plateau next to a needle-shaped
  // basin of λ_lat (lateral_motion_check.hpp): its λ and λ_lat are those of the plateau, not fixed by the data.
  if (summary->feasible) summary->lateral_motion = CheckLateralMotion(objective, summary->parameters, options.lateral_motion);
  if (summary->lateral_motion.unexplained) {
    const LateralMotionCheck& c = summary->lateral_motion;
    summary->warnings.push_back(
        {WarningKind::kLateralMotionUnexplained, "",
         fmt::format("the model at the fit leaves {:.0f} % of the recorded out-of-plane motion unexplained (RMS of "
                     "ω_x, ω_z {:.3g} rad/s measured, {:.3g} rad/s residual, noise at rest {:.3g} rad/s): the fit "
                     "lies on the plateau of nearly planar motion, and the truth may lie in a narrow basin of λ_lat "
                     "that the search missed; λ and λ_lat are not determined by this fit",
                     100.0 * c.unexplained_fraction, c.measured_rms_rad_s, c.residual_rms_rad_s, c.rest_noise_rad_s)});
    for (ParameterId id : {ParameterId::kLambda, ParameterId::kLambdaLat}) {
      auto& d = summary->uncertainty.determined[static_cast<std::size_t>(id)];
      if (d) d = Determination::kNo;
    }
    summary->uncertainty.statements = DescribeUncertainty(summary->uncertainty, summary->parameters);
  }
}

void AddModelErrorStatement(const Objective& objective, const FitOptions& options, FitSummary* summary) {
  // How much of ε the noise at rest explains; a warning when the rest is model error and dominates.
  if (!summary->feasible) return;
  summary->model_error = AssessModelError(objective, summary->epsilon_rad_s, options.model_error);
  const ModelErrorStatement& m = summary->model_error;
  if (!m.dominates) return;
  summary->warnings.push_back(
      {WarningKind::kModelErrorDominates, "",
       fmt::format("model error dominates the fit: ε = {:.4g} rad/s is {:.2f} × the noise floor at rest ({:.4g} rad/s), "
                   "so the noise explains {:.0f} % of ε² and {:.4g} rad/s is structure the model does not reproduce "
                   "(a body, base or contact other than the rigid cuboid, sensor scale, axes, clock or ringing, or a "
                   "missed minimum)",
                   m.epsilon_rad_s, m.ratio, m.noise_floor_rad_s, 100.0 * m.noise_share, m.model_error_rad_s)});
}

void AddMotionBeforeRelease(const Objective& objective, const FitOptions& options, FitSummary* summary) {
  summary->motion_before_release = MeasureMotionBeforeRelease(
      objective.signal(), summary->parameters.value(ParameterId::kT0), options.motion_before_release);
  if (summary->motion_before_release.moving) {
    summary->warnings.push_back(
        {WarningKind::kMovingAtRelease, "", MotionBeforeReleaseWarning(summary->motion_before_release)});
  }
}

void WidenForModelError(const Objective& objective, const FitOptions& options, FitSummary* summary) {
  // Intervals under model error (model_error_widening.hpp): the 95 % half-widths × f(ε/ε_noise), t0's with a
  // floor of t0_floor_samples sample periods in quadrature, clipped to the bounds.
  const IntervalOptions& io = options.intervals;
  const ModelErrorStatement& m = summary->model_error;
  const double factor =
      m.available ? ModelErrorWideningFactor(m.ratio, io.model_error_widening) : 1.0;
  const std::vector<double>& t_s = objective.signal().t_s;
  const double sample_period_s =
      t_s.size() > 1 ? (t_s.back() - t_s.front()) / static_cast<double>(t_s.size() - 1) : 0.0;
  const double t0_floor_s = io.t0_floor_samples * sample_period_s;
  if (factor == 1.0 && !(t0_floor_s > 0.0)) return;
  UncertaintySummary& u = summary->uncertainty;
  bool widened_any = false;
  for (ParameterId id : objective.free_ids()) {
    const std::size_t i = static_cast<std::size_t>(id);
    if (!u.determined[i]) continue;
    const Parameter& p = summary->parameters[id];
    const double floor = id == ParameterId::kT0 ? t0_floor_s : 0.0;
    if (factor == 1.0 && floor == 0.0) continue;
    u.interval_95[i] = WidenInterval(u.interval_95[i], p.value, factor, floor, p.lower, p.upper);
    widened_any = true;
    const Determination widened = Determine(u.interval_95[i], p.lower, p.upper, io.undetermined_range_fraction);
    if (static_cast<int>(widened) > static_cast<int>(*u.determined[i])) u.determined[i] = widened;
  }
  if (!widened_any) return;
  u.description += fmt::format("; 95 % intervals widened for model error × {:.3g} (ε = {} the noise floor, "
                               "coefficient {:.3g}), t0's with a floor of {:.3g} ms",
                               factor, m.available ? fmt::format("{:.3g} ×", m.ratio) : std::string("? ×, no rest for"),
                               io.model_error_widening, 1e3 * t0_floor_s);
  u.statements = DescribeUncertainty(u, summary->parameters);
}

void AddGyroScaleEstimate(const Objective& objective, const FitOptions& options, FitSummary* summary) {
  // The scale projected out of the fit and its interval, with the widening factor of the other 95 % intervals.
  if (options.gyro_scale == GyroScaleMode::kOff || !summary->feasible) {
    summary->gyro_scale.mode = options.gyro_scale;
    return;
  }
  const ModelErrorStatement& m = summary->model_error;
  const double factor = m.available ? ModelErrorWideningFactor(m.ratio, options.intervals.model_error_widening) : 1.0;
  summary->gyro_scale = EstimateGyroScale(objective, summary->parameters, summary->uncertainty, factor, options);
}

void AddNotDeterminedWarnings(const Objective& objective, FitSummary* summary) {
  for (ParameterId id : objective.free_ids()) {
    const auto& d = summary->uncertainty.determined[static_cast<std::size_t>(id)];
    if (d && *d != Determination::kYes && summary->identifiable[static_cast<std::size_t>(id)]) {
      summary->warnings.push_back({WarningKind::kNotDetermined, Name(id),
                                  fmt::format("{}: the data fix {} (see the intervals)", Name(id),
                                              *d == Determination::kSignOnly ? "only its sign" : "no useful range")});
    }
  }

}

void AddFailureWarning(const Objective& objective, const std::map<std::string, std::int64_t>& failures_before,
                       FitSummary* summary) {
  // Model failures during this fit.
  std::map<std::string, std::int64_t> failures = objective.counters().failures_by_reason();
  for (const auto& [reason, count] : failures_before) failures[reason] -= count;
  for (auto it = failures.begin(); it != failures.end();) it = it->second == 0 ? failures.erase(it) : std::next(it);
  summary->failures_by_reason = failures;
  if (!failures.empty()) {
    std::int64_t total = 0;
    for (const auto& entry : failures) total += entry.second;
    summary->warnings.push_back({WarningKind::kSimulationFailures, "",
                                fmt::format("{} trial point(s) were infeasible and penalised: {}", total, FailureList(failures))});
  }
}

void AddPoorFitAndConvergenceWarnings(const Objective& objective, FitSummary* summary) {
  // A fit whose mean error is a large part of the motion itself does not describe the recording.
  if (summary->feasible) {
    ErrorNodes nodes;
    if (BuildErrorNodes(objective.signal(), summary->parameters.value(ParameterId::kT0), objective.t_end_s(), &nodes)) {
      const double mean_rate = TrajectoryError(nodes, std::vector<Eigen::Vector3d>(nodes.size(), Eigen::Vector3d::Zero()));
      if (summary->epsilon_rad_s > kPoorFitFraction * mean_rate) {
        summary->warnings.push_back(
            {WarningKind::kPoorFit, "",
             fmt::format("ε is {:.0f} % of the mean measured |ω| ({:.3g} rad/s) in the window: the model does not "
                         "describe this recording; check the block size, the sensor mounting and the window",
                         100.0 * summary->epsilon_rad_s / mean_rate, mean_rate)});
      }
    }
  }
  if (!summary->feasible) {
    summary->warnings.push_back({WarningKind::kInfeasible, "", "no feasible point found: the model fails everywhere it was tried"});
  } else if (!summary->converged) {
    summary->warnings.push_back({WarningKind::kNotConverged, "", "the local search stopped before convergence: " + summary->termination});
  }

}

// The whole fit on the objective's window: the stages, the rescan, the kept point's assessment and warnings.
// `extended_window`: the window was extended for λ_lat (the lateral rescan then always runs).
// `rest_reference`: the same window with the data estimate's t0 as its start value, where the model-error
// statement's rest ends (a longer window holds t0 at a fitted value that model error can have moved far).
FitSummary FitOnWindow(const Objective& objective, const Eigen::VectorXd& x_start, const FitOptions& options,
                       bool extended_window, const Objective& rest_reference) {
  const auto clock_start = std::chrono::steady_clock::now();
  const std::int64_t runs_before = objective.counters().runs();
  const auto failures_before = objective.counters().failures_by_reason();

  FitSummary summary;
  summary.method = options.method;
  summary.t_end_s = objective.t_end_s();
  summary.model_description = objective.model().Describe();
  summary.start = objective.WithFree(x_start);

  auto global_candidates = RunStages(objective, x_start, options, &summary);
  RescanUnexplainedLateralMotion(objective, options, extended_window, &summary, &global_candidates);
  AssessKeptPoint(objective, options, global_candidates, &summary);
  AddSecondSolutionWarning(objective, &summary);
  ApplyLateralMotionCheck(objective, options, &summary);
  AddModelErrorStatement(rest_reference, options, &summary);
  AddMotionBeforeRelease(objective, options, &summary);
  WidenForModelError(objective, options, &summary);
  AddGyroScaleEstimate(objective, options, &summary);
  AddNotDeterminedWarnings(objective, &summary);
  AddFailureWarning(objective, failures_before, &summary);
  AddPoorFitAndConvergenceWarnings(objective, &summary);

  summary.simulations = objective.counters().runs() - runs_before;
  summary.wall_time_s = SecondsSince(clock_start);
  summary.window.first_t_end_s = summary.t_end_s;
  summary.window.t_end_s = summary.t_end_s;
  return summary;
}

// The release: what the fall before the first impact fixes.
constexpr ParameterId kReleaseParameters[] = {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kReleaseRoll};

bool LambdaLatDetermined(const FitSummary& summary) {
  const auto& d = summary.uncertainty.determined[static_cast<std::size_t>(ParameterId::kLambdaLat)];
  return summary.feasible && d && *d == Determination::kYes;
}

// A window that leaves λ_lat undetermined holds no facet impact that fixes it (window_extension.hpp): the fit is
// made again on windows ending before the next return impacts, each from the previous fit's point, and the first
// that determines λ_lat is kept with its stages after the earlier fits'. When none does, the first window's fit
// stays. A fit whose λ_lat the first window determines is returned unchanged.
FitSummary ExtendWindowWhileLambdaLatUndetermined(const Objective& objective, const FitOptions& options, FitSummary first) {
  WindowReport& report = first.window;
  if (!options.window_extension.enabled) {
    report.reason = "extension off";
    return first;
  }
  // A search of its own, judged by the intervals: not with --no-global (a local search from the estimate only was
  // asked for) nor without intervals (no determination to judge).
  if (!options.global.enabled || options.intervals.method == IntervalMethod::kNone) {
    report.reason = "extension off";
    return first;
  }
  if (!objective.IsFree(ParameterId::kLambdaLat)) {
    report.reason = "lambda_lat fixed";
    return first;
  }
  if (LambdaLatDetermined(first)) {
    report.reason = "lambda_lat determined";
    return first;
  }
  const std::vector<double>& later = objective.later_window_ends_s();
  if (later.empty() || options.window_extension.max_extensions == 0) {
    report.reason = "no later return impact";
    return first;
  }
  std::vector<StageReport> stages = first.stages;
  std::int64_t simulations = first.simulations;
  double wall_time_s = first.wall_time_s;
  ParameterSet from = first.parameters;
  const std::size_t tries = std::min(later.size(), static_cast<std::size_t>(options.window_extension.max_extensions));
  // The release (t0, α, the roll) is fixed by the fall, which the first window holds; over a longer window the
  // model error of a real block (its contact, its corners) would pull them and narrow their intervals around the
  // pulled values. The longer windows fit the impact parameters with the release held at the first fit's values,
  // and the kept fit reports the release as the first fit did.
  ParameterSet held = objective.parameters();
  for (ParameterId id : kReleaseParameters) {
    if (!held[id].fixed) {
      held[id].value = first.parameters.value(id);
      held[id].fixed = true;
    }
  }
  for (std::size_t n = 0; n < tries; ++n) {
    const Objective longer = objective.WithWindowEnd(later[n]).WithParameters(held);
    const ParameterSet start = StartOnLongerWindow(longer, from, options.window_extension);
    const Eigen::VectorXd x_from = longer.FreeValues(start).cwiseMax(longer.FreeLower()).cwiseMin(longer.FreeUpper());
    FitSummary extended = FitOnWindow(longer, x_from, options, true, objective.WithWindowEnd(later[n]));
    simulations += extended.simulations;
    wall_time_s += extended.wall_time_s;
    const bool determined = LambdaLatDetermined(extended);
    stages.push_back({"window-extension", extended.epsilon_rad_s, extended.simulations, extended.wall_time_s,
                      extended.termination_type,
                      fmt::format("window extended to {:.4f} s ({} later return impact(s)): λ_lat {}", later[n], n + 1,
                                  determined ? "determined" : "not determined")});
    report.extensions_tried = static_cast<int>(n + 1);
    report.tried_t_end_s.push_back(later[n]);
    if (determined) {
      for (ParameterId id : kReleaseParameters) {
        if (!objective.IsFree(id)) continue;
        const std::size_t k = static_cast<std::size_t>(id);
        extended.parameters[id] = first.parameters[id];
        extended.std_error[k] = first.std_error[k];
        extended.identifiable[k] = first.identifiable[k];
        extended.at_bound[k] = first.at_bound[k];
        extended.uncertainty.interval_68[k] = first.uncertainty.interval_68[k];
        extended.uncertainty.interval_95[k] = first.uncertainty.interval_95[k];
        extended.uncertainty.determined[k] = first.uncertainty.determined[k];
      }
      extended.uncertainty.statements = DescribeUncertainty(extended.uncertainty, extended.parameters);
      stages.insert(stages.end(), extended.stages.begin(), extended.stages.end());
      extended.stages = std::move(stages);
      // The kept fit started from the data estimate, through the first window's fit.
      extended.start = first.start;
      extended.epsilon_initial_rad_s = longer.Evaluate(first.start).epsilon_rad_s;
      extended.simulations = simulations;
      extended.wall_time_s = wall_time_s;
      extended.window = report;
      extended.window.t_end_s = later[n];
      extended.window.extensions = static_cast<int>(n + 1);
      extended.window.reason = "lambda_lat determined by the extension";
      extended.warnings.push_back(
          {WarningKind::kWindowExtended, "",
           fmt::format("the window ending at {:.4f} s left λ_lat undetermined (no facet impact fixes it there); "
                       "extended to {:.4f} s ({} later return impact(s)), where it is determined",
                       report.first_t_end_s, later[n], n + 1)});
      return extended;
    }
    if (!extended.feasible) break;
    from = extended.parameters;
  }
  first.stages = std::move(stages);
  first.simulations = simulations;
  first.wall_time_s = wall_time_s;
  report.reason = "lambda_lat not determined by any extension";
  return first;
}

}  // namespace

FitSummary Fit(const Objective& given, const ParameterSet& start_in, const FitOptions& given_options) {
  given_options.Validate();
  // The model's exact derivatives do not include a projected gyro scale's dependence on the parameters: under a
  // scale estimate every Jacobian is differenced (and `auto` runs Nelder–Mead, then Ceres).
  FitOptions options = given_options;
  if (options.gyro_scale != GyroScaleMode::kOff) options.ceres.exact_jacobian = false;
  // Every stage evaluates the objective with the gyro scale of the options projected out (or none).
  const Objective objective =
      given.options().gyro_scale == options.gyro_scale ? given : given.WithGyroScale(options.gyro_scale);
  if (objective.num_free() == 0) {
    throw InvalidArgument("every parameter is fixed: free at least one (e.g. --free alpha) or use --evaluate");
  }
  const Eigen::VectorXd x_start =
      objective.FreeValues(start_in).cwiseMax(objective.FreeLower()).cwiseMin(objective.FreeUpper());
  FitSummary summary = ExtendWindowWhileLambdaLatUndetermined(objective, options, FitOnWindow(objective, x_start, options, false, objective));
  summary.simulations_per_second =
      summary.wall_time_s > 0.0 ? static_cast<double>(summary.simulations) / summary.wall_time_s : 0.0;
  return summary;
}

}  // namespace rockfit::fitting
