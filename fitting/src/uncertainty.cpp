#include "rockfit/fitting/uncertainty.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>
#include <tuple>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <nlopt.hpp>

#include "parallel_for.hpp"
#include "rockfit/fitting/censored_noise_level.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/profile_steps.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// z of the two-sided 68.27 % and 95 % intervals of a normal variable; z² is the χ²₁ quantile the profile uses.
constexpr double kZ68 = 1.0;
constexpr double kZ95 = 1.959963984540054;
// A pair of parameters with |correlation| at least this is reported as "only a combination is fixed".
constexpr double kStrongCorrelation = 0.95;
// The sum of squares of an infeasible point: far above any real one, finite for Nelder–Mead.
constexpr double kInfeasibleSumOfSquares = 1e30;
// A point met while profiling whose (28) is lower than the fit's by more than this fraction moves the fit
// there: ε differences below it are within the round-off of the local searches.
constexpr double kBetterPointFraction = 1e-3;
// Initial simplex of the re-fits where no linearised σ is available: a quarter of the Nelder–Mead default,
// as the continuation of the global stage uses.
constexpr PerParameter kFallbackStep = {1e-3, 1.25e-3, 0.05, 0.075, 0.0125, 2.5e-4, 5e-4};
// Relative tolerance of the least-squares re-fits: changes of S below it are round-off of the sum.
constexpr double kSumOfSquaresFtolRel = 1e-7;

struct SumOfSquaresValue {
  double sum_sq = kInfeasibleSumOfSquares;
  double epsilon_rad_s = std::numeric_limits<double>::infinity();
  bool feasible = false;
};

SumOfSquaresValue SumOfSquares(const Objective& objective, const ParameterSet& at) {
  std::vector<Eigen::Vector3d> r;
  SumOfSquaresValue v;
  if (!WeightedResiduals(objective, at, &r, &v.epsilon_rad_s)) return v;
  v.sum_sq = 0.0;
  for (const Eigen::Vector3d& x : r) v.sum_sq += x.squaredNorm();
  v.feasible = std::isfinite(v.sum_sq);
  if (!v.feasible) v.sum_sq = kInfeasibleSumOfSquares;
  return v;
}

// The lowest (28) met by a search, with its point.
struct BestEpsilon {
  double epsilon_rad_s = std::numeric_limits<double>::infinity();
  std::optional<ParameterSet> at;
  void Offer(double epsilon, const ParameterSet& set) {
    if (epsilon < epsilon_rad_s) {
      epsilon_rad_s = epsilon;
      at = set;
    }
  }
  void Merge(const BestEpsilon& other) {
    if (other.at) Offer(other.epsilon_rad_s, *other.at);
  }
};

struct SearchProblem {
  const Objective* objective = nullptr;
  ParameterSet best;
  SumOfSquaresValue best_value;
  BestEpsilon* best_epsilon = nullptr;
  std::int64_t evaluations = 0;
};

double SearchObjective(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  auto* p = static_cast<SearchProblem*>(data);
  ++p->evaluations;
  const ParameterSet set = p->objective->WithFree(Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())));
  const SumOfSquaresValue v = SumOfSquares(*p->objective, set);
  if (v.feasible) p->best_epsilon->Offer(v.epsilon_rad_s, set);
  if (v.sum_sq < p->best_value.sum_sq) {
    p->best_value = v;
    p->best = set;
  }
  return v.sum_sq;
}

// Minimises S over the free parameters of `objective` from `start` by Nelder–Mead (NLopt), at most
// `max_evaluations`; returns the best point evaluated (the start when nothing is better).
ParameterSet MinimizeSumOfSquares(const Objective& objective, const ParameterSet& start, const PerParameter& step,
                                  int max_evaluations, SumOfSquaresValue* value, BestEpsilon* best_epsilon,
                                  std::int64_t* evaluations) {
  SearchProblem problem;
  problem.objective = &objective;
  problem.best = start;
  problem.best_value = SumOfSquares(objective, start);
  problem.best_epsilon = best_epsilon;
  ++problem.evaluations;
  if (problem.best_value.feasible) best_epsilon->Offer(problem.best_value.epsilon_rad_s, start);
  const std::size_t n = objective.num_free();
  if (n > 0 && max_evaluations > 1) {
    const Eigen::VectorXd lower = objective.FreeLower(), upper = objective.FreeUpper();
    const Eigen::VectorXd x0 = objective.FreeValues(start);
    std::vector<double> x(n), lb(n), ub(n), dx(n), xtol(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      lb[i] = lower[k];
      ub[i] = upper[k];
      x[i] = std::clamp(x0[k], lb[i], ub[i]);
      dx[i] = std::min(step[static_cast<std::size_t>(objective.free_ids()[i])], 0.5 * (ub[i] - lb[i]));
      xtol[i] = 1e-3 * dx[i];
    }
    try {
      nlopt::opt opt(nlopt::LN_NELDERMEAD, static_cast<unsigned>(n));
      opt.set_lower_bounds(lb);
      opt.set_upper_bounds(ub);
      opt.set_min_objective(SearchObjective, &problem);
      opt.set_initial_step(dx);
      opt.set_xtol_abs(xtol);
      opt.set_ftol_rel(kSumOfSquaresFtolRel);
      opt.set_maxeval(max_evaluations - 1);
      double f = 0.0;
      opt.optimize(x, f);
    } catch (const std::exception&) {
      // roundoff_limited, forced_stop, …: the best point evaluated is the answer.
    }
  }
  *value = problem.best_value;
  *evaluations += problem.evaluations;
  return problem.best;
}

// What the exact re-fits did (IntervalOptions::profile_refit kExact).
struct RefitStats {
  std::int64_t sensitivity_runs = 0;  // model runs with sensitivities (Ceres)
  std::int64_t exact = 0;             // re-fits ended by Ceres
  std::int64_t fallback = 0;          // re-fits by Nelder–Mead (after Ceres, or without exact Jacobian)
  std::int64_t without_jacobian = 0;  // Ceres re-fits whose start had no exact Jacobian
  void Merge(const RefitStats& other) {
    sensitivity_runs += other.sensitivity_runs;
    without_jacobian += other.without_jacobian;
    exact += other.exact;
    fallback += other.fallback;
  }
};

// How to re-fit S: Nelder–Mead with `evaluations`, or first Ceres with the exact Jacobian (`exact`) for
// `iterations`, and Nelder–Mead from the same start where Ceres fails, stops at its iteration limit, ends above its
// start or ends above check_above_sum_sq.
struct RefitRule {
  bool exact = false;
  int iterations = 0;
  int evaluations = 0;
  bool checked = true;  // IntervalOptions::refit_checked: also where Ceres stops at its limit or past check_above_sum_sq
  // An exact re-fit that ends above this S is checked by Nelder–Mead (the profile points past the 95 % crossing,
  // which set the interval's end): Ceres stops where the rippled S is locally flat or on a kink (measured on the
  // analytic test model: S 8 times the simplex's), and the simplex, whose steps span the ripples, goes on there.
  double check_above_sum_sq = std::numeric_limits<double>::infinity();
};

// Re-fits the free parameters of `objective` from `start` by `rule`; returns the point, its S in `value` (never
// above the start's: Ceres' trust region and the simplex keep the best point met).
ParameterSet RefitSumOfSquares(const Objective& objective, const ParameterSet& start, const PerParameter& step,
                               const RefitRule& rule, SumOfSquaresValue* value, BestEpsilon* best_epsilon,
                               std::int64_t* evaluations, RefitStats* stats) {
  if (!rule.exact || objective.num_free() == 0) {
    if (rule.exact) ++stats->fallback;
    return MinimizeSumOfSquares(objective, start, step, rule.evaluations, value, best_epsilon, evaluations);
  }
  const ExactLeastSquaresResult r = MinimizeSumOfSquaresExact(objective, objective.FreeValues(start), rule.iterations);
  *evaluations += r.runs;
  stats->sensitivity_runs += r.runs;
  if (r.best_epsilon_x.size() > 0) best_epsilon->Offer(r.best_epsilon_rad_s, objective.WithFree(r.best_epsilon_x));
  if (!r.exact_at_start && std::isfinite(r.sum_sq_start)) ++stats->without_jacobian;
  // Kept where Ceres converged below the start and, past the crossing, below the check level; otherwise
  // (a failure, the iteration limit: steps rejected on the ripples) Nelder–Mead.
  const bool kept = r.exact_at_start && !r.failed && r.feasible && r.sum_sq <= r.sum_sq_start &&
                    (!rule.checked || (r.converged && !(r.sum_sq > rule.check_above_sum_sq)));
  if (kept) {
    ++stats->exact;
    value->sum_sq = r.sum_sq;
    value->epsilon_rad_s = r.epsilon_rad_s;
    value->feasible = std::isfinite(r.sum_sq);
    if (!value->feasible) value->sum_sq = kInfeasibleSumOfSquares;
    return objective.WithFree(r.x);
  }
  // Nelder–Mead from the warm start (Ceres' end may sit on a kink the simplex does not leave either); the better of
  // its end and Ceres'.
  ++stats->fallback;
  const ParameterSet simplex_end =
      MinimizeSumOfSquares(objective, start, step, rule.evaluations, value, best_epsilon, evaluations);
  if (r.feasible && std::isfinite(r.sum_sq) && r.sum_sq < value->sum_sq) {
    value->sum_sq = r.sum_sq;
    value->epsilon_rad_s = r.epsilon_rad_s;
    value->feasible = true;
    return objective.WithFree(r.x);
  }
  return simplex_end;
}

struct ProfilePoint {
  double value = 0.0;
  double sum_sq = kInfeasibleSumOfSquares;
  bool feasible = false;
  bool at_bound = false;
};

// The scale of one profile: S at its centre and the effective noise variance κ_j·s² of its signed root.
struct ProfileScale {
  double sum_sq_centre = 0.0;
  double s2_eff = 1.0;
  double Rho(const SumOfSquaresValue& v) const {
    return v.feasible ? std::sqrt(std::max(0.0, v.sum_sq - sum_sq_centre) / s2_eff) : std::numeric_limits<double>::infinity();
  }
  // `rule` with its check level at ρ = z₉₅: the profile points past the crossing set the interval's end.
  RefitRule CheckedPast95(const RefitRule& rule) const {
    RefitRule checked = rule;
    checked.check_above_sum_sq = sum_sq_centre + kZ95 * kZ95 * s2_eff;
    return checked;
  }
};

// `from` with `id` moved to `value` and held, the others as `from` (the profile point's problem and start).
ParameterSet HeldAt(const Objective& objective, const ParameterSet& from, ParameterId id, double value) {
  ParameterSet set = objective.parameters();
  for (ParameterId other : kAllParameters) set[other].value = from.value(other);
  set[id].value = value;
  set[id].fixed = true;
  return set;
}

// The fixed grid (IntervalOptions::profile_aimed false): offsets of 1, 2, then growing by options.profile_growth
// times `step` from the centre, the other free parameters re-fitted at each (warm-started from the previous point),
// until S rises above 1.5·z²·κ_j·s² (margin to interpolate the crossing), the model fails, or the bound is reached.
std::vector<ProfilePoint> ProfileSideOnGrid(const Objective& objective, const ParameterSet& centre, ParameterId id,
                                            double direction, double step, const ProfileScale& scale,
                                            const PerParameter& refit_step, const RefitRule& rule,
                                            const IntervalOptions& options, BestEpsilon* best_epsilon,
                                            std::int64_t* evaluations, RefitStats* stats) {
  const double stop_sum_sq = scale.sum_sq_centre + 1.5 * kZ95 * kZ95 * scale.s2_eff;
  std::vector<ProfilePoint> points;
  const Parameter& p = objective.parameters()[id];
  const double bound = direction > 0 ? p.upper : p.lower;
  ParameterSet previous = centre;
  double offset = 1.0;
  for (int i = 0; i < options.profile_points; ++i) {
    ProfilePoint point;
    point.value = centre.value(id) + direction * offset * step;
    if (direction * (point.value - bound) >= 0.0) {
      point.value = bound;
      point.at_bound = true;
    }
    if (point.value == centre.value(id)) break;  // the centre sits on the bound
    const ParameterSet set = HeldAt(objective, previous, id, point.value);
    const Objective held = objective.WithParameters(set);
    SumOfSquaresValue v;
    previous = RefitSumOfSquares(held, set, refit_step, scale.CheckedPast95(rule), &v, best_epsilon, evaluations, stats);
    point.sum_sq = v.sum_sq;
    point.feasible = v.feasible;
    points.push_back(point);
    if (!v.feasible || v.sum_sq > stop_sum_sq || point.at_bound) break;
    offset = i == 0 ? 2.0 : offset * options.profile_growth;
  }
  return points;
}

// Aimed points (IntervalOptions::profile_aimed, profile_steps.hpp), offsets in units of `step` (the linearised σ_j)
// and never below `min_offset` (the model's resolution): the first at profile_aim_rho, each next one by the secant
// of the signed root ρ, until ρ passes z = 1.96 (the crossing is bracketed), the model fails or the bound is reached;
// a first bracket looser than profile_refine_above_rho (or ended by a failed model run) gets one point inside it
// where that point is not below `min_offset`. Every re-fit starts from the better (lower S) of the re-fitted neighbour inside it and that point
// moved along the linearised ridge (`ridge_slope`: dθ_o/dθ_j, per parameter; 0 where unknown).
std::vector<ProfilePoint> ProfileSideAimed(const Objective& objective, const ParameterSet& centre, ParameterId id,
                                           double direction, double step, double min_offset, const ProfileScale& scale,
                                           const PerParameter& ridge_slope, const PerParameter& refit_step,
                                           const RefitRule& rule, const IntervalOptions& options,
                                           BestEpsilon* best_epsilon, std::int64_t* evaluations, RefitStats* stats) {
  struct Point {
    ProfilePoint profile;
    ProfileStepPoint step;
    ParameterSet refit;
  };
  std::vector<Point> points;  // in the order evaluated (outwards, then the refinement)
  const Parameter& p = objective.parameters()[id];
  const double bound = direction > 0 ? p.upper : p.lower;
  const double c = centre.value(id);
  const ProfileAim aim{options.profile_aim_rho, ProfileAim{}.min_growth, ProfileAim{}.max_growth};
  // Re-fits the others with `id` held at offset `offset` from the centre, started from `inner` (the re-fitted
  // point inside it) or its shift along the ridge, whichever has the lower S.
  auto evaluate = [&](double offset, const ParameterSet& inner) {
    Point point;
    point.profile.value = c + direction * offset * step;
    if (direction * (point.profile.value - bound) >= 0.0) {
      point.profile.value = bound;
      point.profile.at_bound = true;
    }
    point.step.offset = direction * (point.profile.value - c) / step;
    ParameterSet start = HeldAt(objective, inner, id, point.profile.value);
    const Objective held = objective.WithParameters(start);
    ParameterSet moved = start;
    bool shifted = false;
    for (ParameterId other : held.free_ids()) {
      const double slope = ridge_slope[static_cast<std::size_t>(other)];
      if (slope == 0.0) continue;
      const Parameter& q = held.parameters()[other];
      moved[other].value = std::clamp(inner.value(other) + slope * (point.profile.value - inner.value(id)), q.lower, q.upper);
      shifted = true;
    }
    if (shifted) {
      const SumOfSquaresValue at_moved = SumOfSquares(held, moved);
      ++*evaluations;
      if (at_moved.feasible) {
        best_epsilon->Offer(at_moved.epsilon_rad_s, moved);
        if (at_moved.sum_sq < SumOfSquares(held, start).sum_sq) start = moved;
        ++*evaluations;
      }
    }
    SumOfSquaresValue v;
    point.refit = RefitSumOfSquares(held, start, refit_step, scale.CheckedPast95(rule), &v, best_epsilon, evaluations,
                                    stats);
    point.profile.sum_sq = v.sum_sq;
    point.profile.feasible = v.feasible;
    point.step.rho = scale.Rho(v);
    return point;
  };

  if (c == bound) return {};  // the centre sits on the bound
  ProfileStepPoint before;            // the point inside the last one evaluated: the centre (offset 0, ρ 0) first
  std::optional<std::size_t> inner;   // its index in `points` (none: the centre)
  double offset = std::max(options.profile_aim_rho, min_offset);
  for (int i = 0; i < options.profile_points; ++i) {
    points.push_back(evaluate(offset, inner ? points[*inner].refit : centre));
    const ProfileStepPoint last = points.back().step;
    const bool at_bound = points.back().profile.at_bound;
    if (last.rho > kZ95) {
      // Bracketed. One point inside a loose bracket (or one that ends where the model fails).
      const double inside = RefineProfileOffset(before, last, options.profile_aim_rho);
      if (last.rho > options.profile_refine_above_rho && i + 1 < options.profile_points && last.offset > before.offset &&
          inside >= min_offset) {
        const ParameterSet from = inner ? points[*inner].refit : centre;
        points.push_back(evaluate(inside, from));
      }
      break;
    }
    if (at_bound) break;  // an open end
    offset = NextProfileOffset(before, last, aim);
    before = last;
    inner = points.size() - 1;
  }
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.step.offset < b.step.offset; });
  std::vector<ProfilePoint> out;
  out.reserve(points.size());
  for (const Point& point : points) out.push_back(point.profile);
  return out;
}

// Where the profile (centre first, then the side's points outwards) first rises above z (signed-root scale
// ρ = √(ΔS/s²_eff)), by linear interpolation in ρ; NaN when it never does (open end).
double ProfileCrossing(double centre_value, double centre_rho, const std::vector<ProfilePoint>& side, double sum_sq_min,
                       double s2_eff, double z) {
  double previous_value = centre_value, previous_rho = centre_rho;
  for (const ProfilePoint& point : side) {
    const double rho = point.feasible ? std::sqrt(std::max(0.0, point.sum_sq - sum_sq_min) / s2_eff)
                                      : std::numeric_limits<double>::infinity();
    if (rho > z) {
      if (!std::isfinite(rho)) return point.value;  // the model fails beyond: end there (conservatively)
      const double t = previous_rho >= z ? 0.0 : (z - previous_rho) / (rho - previous_rho);
      return previous_value + std::clamp(t, 0.0, 1.0) * (point.value - previous_value);
    }
    previous_value = point.value;
    previous_rho = rho;
  }
  return kNaN;
}

// `inner` cut to `outer` where `outer` is closed: an end of `inner` beyond it (or open) becomes `outer`'s.
Interval NestedIn(Interval inner, const Interval& outer) {
  if (!std::isnan(outer[0])) inner[0] = std::isnan(inner[0]) ? outer[0] : std::max(inner[0], outer[0]);
  if (!std::isnan(outer[1])) inner[1] = std::isnan(inner[1]) ? outer[1] : std::min(inner[1], outer[1]);
  return inner;
}

// centre ± half_width, an end beyond a bound of `p` open (NaN): the linearised interval.
Interval LinearisedInterval(double centre, double half_width, const Parameter& p) {
  auto clip = [&](double x) { return x < p.lower || x > p.upper ? kNaN : x; };
  return {clip(centre - half_width), clip(centre + half_width)};
}

// The part of the description that says how the 68 % intervals were made.
std::string Describe68(double bulk_inflation, const char* how) {
  if (std::isnan(bulk_inflation)) return fmt::format("; 68 % intervals {} at the same level", how);
  return fmt::format("; 68 % intervals {} at the bulk level of the standard errors (variance inflated by {:.2f} for "
                     "the lag-1 correlation)",
                     how, bulk_inflation);
}

}  // namespace

const char* ToString(Determination d) {
  switch (d) {
    case Determination::kYes: return "yes";
    case Determination::kSignOnly: return "sign only";
    case Determination::kNo: return "no";
  }
  return "?";
}

bool FromString(std::string_view text, Determination* value) {
  static constexpr Determination kAll[] = {Determination::kYes, Determination::kSignOnly, Determination::kNo};
  return core::FromStringAmong(text, kAll, value);
}

double ResidualDegreesOfFreedom(std::size_t nodes, std::size_t unobserved_components, std::size_t free_parameters) {
  return 3.0 * static_cast<double>(nodes) - static_cast<double>(unobserved_components) -
         static_cast<double>(free_parameters);
}

bool WeightedResiduals(const Objective& objective, const ParameterSet& at, std::vector<Eigen::Vector3d>* residuals,
                       double* epsilon_rad_s, std::vector<Eigen::Vector3d>* on_node_grid,
                       std::size_t* unobserved_components) {
  ErrorNodes nodes;
  ModelOutput output;
  const Evaluation e = objective.EvaluateDetailed(at, &nodes, &output);
  if (epsilon_rad_s != nullptr) *epsilon_rad_s = e.epsilon_rad_s;
  if (!e.feasible || output.w_B.size() != nodes.size()) return false;
  // Nodes without weight (clipped samples, gyro_clipping.hpp) are no residuals: counted, they would lower the
  // noise level per residual and the degrees of freedom would overstate the data.
  residuals->clear();
  residuals->reserve(nodes.size());
  if (on_node_grid != nullptr) on_node_grid->assign(nodes.size(), Eigen::Vector3d::Zero());
  if (unobserved_components != nullptr) *unobserved_components = NumSatisfiedCensoredComponents(nodes, output.w_B);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (nodes.weight_s[k] == 0.0) continue;
    residuals->push_back(std::sqrt(nodes.weight_s[k]) * NodeMisfit(nodes, k, output.w_B[k]));
    if (on_node_grid != nullptr) (*on_node_grid)[k] = residuals->back();
  }
  return true;
}

double Lag1InflationFactor(const double* values, std::size_t samples, std::size_t stride) {
  double lag0 = 0.0, lag1 = 0.0;
  for (std::size_t c = 0; c < stride; ++c) {
    for (std::size_t k = 0; k < samples; ++k) {
      const double v = values[stride * k + c];
      lag0 += v * v;
      if (k > 0) lag1 += v * values[stride * (k - 1) + c];
    }
  }
  if (!(lag0 > 0.0)) return 1.0;
  // Negative correlation never shrinks the noise level; 0.99 keeps the factor finite (199).
  const double rho = std::clamp(lag1 / lag0, 0.0, 0.99);
  return (1.0 + rho) / (1.0 - rho);
}

double LongRunVarianceFactor(const std::vector<Eigen::Vector3d>& r, int max_lag) {
  const std::size_t n = r.size();
  double lag0 = 0.0;
  for (const Eigen::Vector3d& x : r) lag0 += x.squaredNorm();
  if (n < 2 || !(lag0 > 0.0)) return 1.0;
  const int lags = std::min<int>(max_lag, static_cast<int>(n) - 1);
  double sum = 0.0;
  for (int l = 1; l <= lags; ++l) {
    double c = 0.0;
    for (std::size_t k = static_cast<std::size_t>(l); k < n; ++k) c += r[k].dot(r[k - static_cast<std::size_t>(l)]);
    const double bartlett = 1.0 - static_cast<double>(l) / static_cast<double>(lags + 1);
    sum += bartlett * c / lag0;
  }
  return std::max(1.0, 1.0 + 2.0 * sum);  // (the long-run variance never taken below the white-noise one)
}

Eigen::VectorXd SandwichInflation(const Linearisation& lin, int max_lag) {
  const Eigen::Index n = static_cast<Eigen::Index>(lin.ids.size());
  Eigen::VectorXd kappa = Eigen::VectorXd::Ones(n);
  if (!lin.available()) return kappa;
  const Eigen::Index slots = lin.residuals.size() / 3;
  // Score contributions per sample: g_k = Σ_c J_(k,c)ᵀ r_(k,c).
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(n, slots);
  double sum_sq = 0.0;
  for (Eigen::Index k = 0; k < slots; ++k) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      const double r = lin.residuals[3 * k + c];
      g.col(k) += lin.jacobian.row(3 * k + c).transpose() * r;
      sum_sq += r * r;
    }
  }
  Eigen::MatrixXd b = g * g.transpose();
  const Eigen::Index lags = std::min<Eigen::Index>(max_lag, slots - 1);
  for (Eigen::Index l = 1; l <= lags; ++l) {
    const double bartlett = 1.0 - static_cast<double>(l) / static_cast<double>(lags + 1);
    const Eigen::MatrixXd gamma = g.rightCols(slots - l) * g.leftCols(slots - l).transpose();
    b += bartlett * (gamma + gamma.transpose());
  }
  // Residuals at rows that are no node (before t0) are 0 and carry no information: count the others.
  Eigen::Index used = 0;
  for (Eigen::Index i = 0; i < lin.residuals.size(); ++i) used += lin.residuals[i] != 0.0 ? 1 : 0;
  const double dof = static_cast<double>(used - n);
  if (!(dof > 0.0) || !(sum_sq > 0.0)) return kappa;
  const double s2 = sum_sq / dof;
  const double small_sample = static_cast<double>(used) / dof;
  const Eigen::MatrixXd& m = lin.inverse_normal_matrix;
  const Eigen::MatrixXd sandwich = small_sample * m * b * m;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double white = s2 * m(j, j);
    if (white > 0.0 && std::isfinite(sandwich(j, j))) kappa[j] = std::max(1.0, sandwich(j, j) / white);
  }
  return kappa;
}

Determination Determine(const Interval& i95, double lower_bound, double upper_bound, double undetermined_range_fraction) {
  const bool open = std::isnan(i95[0]) || std::isnan(i95[1]);
  if (std::isnan(i95[0]) && std::isnan(i95[1])) return Determination::kNo;
  const double range = upper_bound - lower_bound;
  const bool wide = !open && std::isfinite(range) && i95[1] - i95[0] > undetermined_range_fraction * range;
  if (!open && !wide) return Determination::kYes;
  const bool zero_possible = lower_bound < 0.0 && upper_bound > 0.0;
  const bool excludes_zero = (!std::isnan(i95[0]) && i95[0] > 0.0) || (!std::isnan(i95[1]) && i95[1] < 0.0);
  return zero_possible && excludes_zero ? Determination::kSignOnly : Determination::kNo;
}

std::string IntervalJson(const Interval& interval, bool fixed) {
  if (fixed) return "null";
  nlohmann::json j = nlohmann::json::array();
  for (double v : interval) j.push_back(std::isnan(v) ? nlohmann::json() : nlohmann::json(v));
  return j.dump();
}

std::string CorrelationJson(const UncertaintySummary& u, const ParameterSet& parameters) {
  nlohmann::json names = nlohmann::json::array(), matrix = nlohmann::json::array();
  const std::vector<ParameterId> free = parameters.FreeIds();
  for (ParameterId a : free) {
    names.push_back(Name(a));
    nlohmann::json row = nlohmann::json::array();
    for (ParameterId b : free) {
      const double c = u.correlation.rows() == static_cast<Eigen::Index>(kNumParameters)
                           ? u.correlation(static_cast<int>(a), static_cast<int>(b))
                           : kNaN;
      row.push_back(std::isfinite(c) ? nlohmann::json(c) : nlohmann::json());
    }
    matrix.push_back(row);
  }
  return nlohmann::json{{"parameters", names}, {"matrix", matrix}}.dump();
}

std::string NoiseInflationJson(const UncertaintySummary& u, const ParameterSet& parameters) {
  nlohmann::json j = nlohmann::json::object();
  for (ParameterId id : parameters.FreeIds()) {
    const double k = u.noise_inflation[static_cast<std::size_t>(id)];
    j[Name(id)] = std::isfinite(k) ? nlohmann::json(k) : nlohmann::json();
  }
  return j.dump();
}

std::vector<std::string> DescribeUncertainty(const UncertaintySummary& u, const ParameterSet& parameters) {
  std::vector<std::string> out;
  const std::vector<ParameterId> free = parameters.FreeIds();
  if (u.correlation.rows() == static_cast<Eigen::Index>(kNumParameters)) {
    for (std::size_t a = 0; a < free.size(); ++a) {
      for (std::size_t b = a + 1; b < free.size(); ++b) {
        const double c = u.correlation(static_cast<int>(free[a]), static_cast<int>(free[b]));
        if (!(std::abs(c) >= kStrongCorrelation)) continue;
        const bool fall = free[a] == ParameterId::kT0 && free[b] == ParameterId::kAlpha;
        out.push_back(fmt::format("{} and {}: only {} is fixed (correlation {:.3f})", Name(free[a]), Name(free[b]),
                                  fall ? "t0 + T(α), the time of the first impact," : "a combination of the two", c));
      }
    }
  }
  auto end = [](double v) { return std::isnan(v) ? std::string("open") : fmt::format("{:.4g}", v); };
  for (ParameterId id : free) {
    const auto& d = u.determined[static_cast<std::size_t>(id)];
    if (!d || *d == Determination::kYes) continue;
    const Interval& i = u.interval_95[static_cast<std::size_t>(id)];
    if (*d == Determination::kSignOnly) {
      out.push_back(fmt::format("{}: only the sign is fixed ({} {} 0; 95 % interval [{}, {}])", Name(id), Name(id),
                                parameters.value(id) > 0.0 ? ">" : "<", end(i[0]), end(i[1])));
    } else {
      out.push_back(fmt::format("{}: not fixed by the data (95 % interval [{}, {}])", Name(id), end(i[0]), end(i[1])));
    }
  }
  return out;
}

UncertaintySummary ComputeUncertainty(const Objective& objective, const ParameterSet& fitted, double fitted_epsilon_rad_s,
                                      const std::array<bool, kNumParameters>& identifiable, const Linearisation& lin,
                                      const std::vector<ParameterSet>& alternatives, const IntervalOptions& options,
                                      int num_threads) {
  const Eigen::MatrixXd& inverse_normal_matrix = lin.inverse_normal_matrix;
  const std::vector<ParameterId>& covariance_ids = lin.ids;
  options.Validate();
  const auto clock_start = std::chrono::steady_clock::now();
  const std::int64_t runs_before = objective.counters().runs();
  UncertaintySummary u;
  u.method = options.method;
  for (auto& i : u.interval_68) i = {kNaN, kNaN};
  for (auto& i : u.interval_95) i = {kNaN, kNaN};
  u.linearised_sigma_95.fill(kNaN);
  const auto P = static_cast<Eigen::Index>(kNumParameters);
  u.correlation = Eigen::MatrixXd::Constant(P, P, kNaN);
  const auto n_cov = static_cast<Eigen::Index>(covariance_ids.size());
  const bool have_cov = inverse_normal_matrix.rows() == n_cov && n_cov > 0;
  if (have_cov) {
    for (Eigen::Index a = 0; a < n_cov; ++a) {
      for (Eigen::Index b = 0; b < n_cov; ++b) {
        const double d = inverse_normal_matrix(a, a) * inverse_normal_matrix(b, b);
        u.correlation(static_cast<int>(covariance_ids[static_cast<std::size_t>(a)]),
                      static_cast<int>(covariance_ids[static_cast<std::size_t>(b)])) =
            d > 0.0 ? inverse_normal_matrix(a, b) / std::sqrt(d) : kNaN;
      }
    }
  }
  if (options.method == IntervalMethod::kNone) {
    u.description = "none (standard errors only)";
    return u;
  }

  // The least-squares form of the problem: non-identifiable parameters held (they do not act on (28)).
  ParameterSet base = objective.parameters();
  for (ParameterId id : kAllParameters) base[id].value = fitted.value(id);
  std::vector<ParameterId> profiled;
  for (ParameterId id : objective.free_ids()) {
    if (identifiable[static_cast<std::size_t>(id)]) {
      profiled.push_back(id);
    } else {
      base[id].fixed = true;  // both ends stay open: the data say nothing about it
      u.determined[static_cast<std::size_t>(id)] = Determination::kNo;
    }
  }
  const Objective ls = objective.WithParameters(base);
  BestEpsilon best_epsilon;
  std::int64_t evaluations = 0;

  // The effective noise level from the residuals at the fit.
  // r: the residuals (what the sums and the degrees of freedom count); r_grid: the same on the node grid, 0 at a
  // node without weight (a clipped sample), for the correlation in time — no pair across a left-out sample is
  // taken for neighbours, and the zeros add nothing to the lag sums.
  std::vector<Eigen::Vector3d> r, r_grid;
  std::size_t unobserved = 0;  // censored components the model satisfies: no residual, no degree of freedom
  if (profiled.empty() || !WeightedResiduals(ls, base, &r, nullptr, &r_grid, &unobserved)) {
    u.description = "not available: the model fails at the fit";
    return u;
  }
  double sum_sq_fit = 0.0, weight_sum = 0.0;
  for (const Eigen::Vector3d& x : r) sum_sq_fit += x.squaredNorm();
  {
    ErrorNodes nodes;
    BuildErrorNodes(objective.signal(), fitted.value(ParameterId::kT0), objective.t_end_s(), &nodes);
    for (double w : nodes.weight_s) weight_sum += w;
  }
  const double dt_s = weight_sum / static_cast<double>(std::max<std::size_t>(r.size() - 1, 1));
  const int max_lag = std::max(1, static_cast<int>(std::lround(options.noise_correlation_window_s / dt_s)));
  // κ_j per parameter: the sandwich where the Jacobian is there, else the long-run factor of the residuals.
  PerParameter kappa;
  kappa.fill(LongRunVarianceFactor(r_grid, max_lag));
  u.noise_inflation.fill(kNaN);
  if (lin.available()) {
    const Eigen::VectorXd k = SandwichInflation(lin, max_lag);
    for (std::size_t a = 0; a < lin.ids.size(); ++a) kappa[static_cast<std::size_t>(lin.ids[a])] = k[static_cast<Eigen::Index>(a)];
  }
  for (double& k : kappa) k *= options.model_error_allowance;
  // The bulk level of the 68 % intervals (never above the 95 % level's, so that the intervals nest).
  const double bulk = Lag1InflationFactor(r_grid.front().data(), r_grid.size(), 3);
  PerParameter kappa_68 = kappa;
  if (options.bulk_noise_for_68) {
    for (double& k : kappa_68) k = std::min(k, bulk);
  }
  u.bulk_inflation = options.bulk_noise_for_68 ? bulk : kNaN;
  u.correlation_factor = 1.0;
  for (ParameterId id : profiled) {
    u.noise_inflation[static_cast<std::size_t>(id)] = kappa[static_cast<std::size_t>(id)];
    u.correlation_factor = std::max(u.correlation_factor, kappa[static_cast<std::size_t>(id)]);
  }
  const double dof = ResidualDegreesOfFreedom(r.size(), unobserved, profiled.size());
  double sum_sq_min = sum_sq_fit;  // the lowest S known (the profiles may find lower)
  if (!(dof > 0.0)) {
    u.description = "not available: fewer residuals than free parameters";
    return u;
  }
  // The noise level s² = S / noise_dof: with censored components (a clipped gyro) the maximum-likelihood σ² of
  // the censored normal model at the fit over S/dof scales it (censored_noise_level.hpp); without them
  // noise_dof is dof itself, so every expression below is the one before, to the last digit.
  const double censored_factor = CensoredNoiseFactorAt(ls, base, profiled.size());
  const double noise_dof = dof / censored_factor;
  u.censored_noise_factor = censored_factor;

  // Linearised σ with the effective noise level (the fast intervals; the profile's step sizes).
  PerParameter sigma;
  sigma.fill(kNaN);
  auto linearised_sigma = [&](double s2) {
    if (!have_cov) return;
    for (Eigen::Index a = 0; a < n_cov; ++a) {
      const double v = inverse_normal_matrix(a, a) * s2 * kappa[static_cast<std::size_t>(covariance_ids[static_cast<std::size_t>(a)])];
      sigma[static_cast<std::size_t>(covariance_ids[static_cast<std::size_t>(a)])] = v >= 0.0 ? std::sqrt(v) : kNaN;
    }
  };

  if (options.method == IntervalMethod::kFast) {
    u.noise_rms_rad_s = std::sqrt(sum_sq_fit / noise_dof / dt_s);
    linearised_sigma(sum_sq_fit / noise_dof);
    u.linearised_sigma_95 = sigma;
    for (ParameterId id : profiled) {
      const std::size_t k = static_cast<std::size_t>(id);
      const Parameter& p = objective.parameters()[id];
      const double c = fitted.value(id);
      if (std::isfinite(sigma[k])) {
        const double sigma_68 = sigma[k] * std::sqrt(kappa_68[k] / kappa[k]);
        u.interval_68[k] = LinearisedInterval(c, kZ68 * sigma_68, p);
        u.interval_95[k] = LinearisedInterval(c, kZ95 * sigma[k], p);
      }
      u.determined[k] = Determine(u.interval_95[k], p.lower, p.upper, options.undetermined_range_fraction);
    }
    u.description = fmt::format("fast: linearised, value ± z·σ with the residual noise level {:.3g} rad/s, variances "
                                "inflated by up to κ = {:.2f} for its correlation in time and model error{}",
                                u.noise_rms_rad_s, u.correlation_factor, Describe68(u.bulk_inflation, "linearised"));
  } else {
    // The least-squares optimum the profiles start from (close to the optimum of (28)).
    PerParameter refit_step = kFallbackStep;
    linearised_sigma(sum_sq_fit / noise_dof);
    for (ParameterId id : kAllParameters) {
      const std::size_t k = static_cast<std::size_t>(id);
      if (std::isfinite(sigma[k])) refit_step[k] = std::clamp(sigma[k], options.min_step[k], kFallbackStep[k]);
    }
    SumOfSquaresValue centre_value;
    const bool exact = options.profile_refit == ProfileRefit::kExact;
    RefitStats refit_stats;
    const RefitRule centre_rule{exact, options.centre_iterations, options.centre_evaluations, options.refit_checked};
    const ParameterSet centre = RefitSumOfSquares(ls, base, refit_step, centre_rule, &centre_value, &best_epsilon,
                                                  &evaluations, &refit_stats);
    // Where the model gives no exact Jacobian at the optimum (clipped samples in the window, a gyro scale estimate,
    // a parameter without derivatives) it gives none at the profile points either: Nelder–Mead throughout.
    const RefitRule profile_rule{exact && refit_stats.without_jacobian == 0, options.refit_iterations,
                                 options.profile_evaluations, options.refit_checked};
    const double sum_sq_centre = centre_value.sum_sq;
    const double s2_centre = sum_sq_centre / noise_dof;
    linearised_sigma(s2_centre);

    // The linearised ridge of each profile (how the others move when they are re-fitted), 0 without M.
    std::vector<PerParameter> ridge_slope(profiled.size());
    for (std::size_t j = 0; j < profiled.size(); ++j) {
      ridge_slope[j].fill(0.0);
      const auto a = std::find(covariance_ids.begin(), covariance_ids.end(), profiled[j]);
      if (!have_cov || a == covariance_ids.end()) continue;
      const Eigen::VectorXd slope = RidgeSlope(inverse_normal_matrix, a - covariance_ids.begin());
      for (Eigen::Index b = 0; b < n_cov; ++b) ridge_slope[j][static_cast<std::size_t>(covariance_ids[static_cast<std::size_t>(b)])] = slope[b];
    }
    // Both sides of every profiled parameter, in parallel (independent: deterministic in any thread count).
    const std::size_t sides = 2 * profiled.size();
    std::vector<std::vector<ProfilePoint>> points(sides);
    std::vector<BestEpsilon> side_best(sides);
    std::vector<std::int64_t> side_evaluations(sides, 0);
    std::vector<RefitStats> side_stats(sides);
    ParallelFor(sides, num_threads, [&](std::size_t s) {
      const ParameterId id = profiled[s / 2];
      const std::size_t k = static_cast<std::size_t>(id);
      const double step = std::isfinite(sigma[k]) ? std::max(sigma[k], options.min_step[k]) : kFallbackStep[k];
      // The aimed points' unit: σ_j itself, the model's resolution kept as a smallest offset.
      const double unit = std::isfinite(sigma[k]) && sigma[k] > 0.0 ? sigma[k] : step;
      const ProfileScale scale{sum_sq_centre, kappa[k] * s2_centre};
      const double direction = s % 2 == 0 ? -1.0 : +1.0;
      if (options.profile_aimed) {
        points[s] = ProfileSideAimed(ls, centre, id, direction, unit, options.min_step[k] / unit, scale, ridge_slope[s / 2], refit_step, profile_rule,
                                     options, &side_best[s], &side_evaluations[s], &side_stats[s]);
      } else {
        points[s] = ProfileSideOnGrid(ls, centre, id, direction, step, scale, refit_step, profile_rule, options,
                                      &side_best[s], &side_evaluations[s], &side_stats[s]);
      }
    });
    sum_sq_min = sum_sq_centre;
    for (std::size_t s = 0; s < sides; ++s) {
      evaluations += side_evaluations[s];
      refit_stats.Merge(side_stats[s]);
      best_epsilon.Merge(side_best[s]);
      for (const ProfilePoint& pt : points[s]) {
        if (pt.feasible) sum_sq_min = std::min(sum_sq_min, pt.sum_sq);
      }
    }
    u.sensitivity_runs = refit_stats.sensitivity_runs;
    u.exact_refits = refit_stats.exact;
    u.nelder_mead_refits = exact ? refit_stats.fallback : 0;
    u.noise_rms_rad_s = std::sqrt(sum_sq_min / noise_dof / dt_s);
    linearised_sigma(sum_sq_min / noise_dof);
    const PerParameter linear_sigma = sigma;
    u.linearised_sigma_95 = sigma;
    for (std::size_t j = 0; j < profiled.size(); ++j) {
      const ParameterId id = profiled[j];
      const std::size_t k = static_cast<std::size_t>(id);
      const Parameter& p = objective.parameters()[id];
      const double c = centre.value(id), v = fitted.value(id);
      auto ends = [&](double z, double inflation) {
        const double s2_eff = inflation * sum_sq_min / noise_dof;
        const double centre_rho = std::sqrt(std::max(0.0, sum_sq_centre - sum_sq_min) / s2_eff);
        Interval i = {ProfileCrossing(c, centre_rho, points[2 * j], sum_sq_min, s2_eff, z),
                      ProfileCrossing(c, centre_rho, points[2 * j + 1], sum_sq_min, s2_eff, z)};
        // The reported value (the optimum of (28)) always lies inside its intervals.
        if (!std::isnan(i[0])) i[0] = std::min(i[0], v);
        if (!std::isnan(i[1])) i[1] = std::max(i[1], v);
        return i;
      };
      u.interval_95[k] = ends(kZ95, kappa[k]);
      // The 95 % interval is the hull of the profile's and the linearised one (value ± 1.96·σ_j, clipped to
      // the bounds): where the two disagree, neither is trusted alone. Measured on the coverage study
      // (fitting/README.md, "Intervals"), it holds the truth more often at 95 % in the heavy tail of the
      // errors (wrong sub-basins with weak lateral motion) at little cost in width elsewhere.
      if (options.hull_with_linearised && std::isfinite(linear_sigma[k])) {
        Interval& i = u.interval_95[k];
        if (!std::isnan(i[0])) i[0] = std::max(p.lower, std::min(i[0], v - kZ95 * linear_sigma[k]));
        if (!std::isnan(i[1])) i[1] = std::min(p.upper, std::max(i[1], v + kZ95 * linear_sigma[k]));
      }
      // The 68 % interval: linearised at the bulk level (IntervalOptions::profile_68 false, measured on the
      // coverage study), or the profile's crossing; inside the 95 % one.
      if (options.profile_68 || !std::isfinite(linear_sigma[k])) {
        u.interval_68[k] = ends(kZ68, kappa_68[k]);
      } else {
        // An end beyond a bound is open, as in fast; NestedIn below closes it where the 95 % interval is closed.
        const double sigma_68 = linear_sigma[k] * std::sqrt(kappa_68[k] / kappa[k]);
        u.interval_68[k] = LinearisedInterval(v, kZ68 * sigma_68, p);
      }
      u.interval_68[k] = NestedIn(u.interval_68[k], u.interval_95[k]);
      u.determined[k] = Determine(u.interval_95[k], p.lower, p.upper, options.undetermined_range_fraction);
    }
    u.description = fmt::format("thorough: 95 % intervals from the profile of the sum of squares of (28)'s residuals, the "
                                "others re-fitted, at the residual noise level {:.3g} rad/s inflated by up to κ = {:.2f} for its "
                                "correlation in time and model error{}{}",
                                u.noise_rms_rad_s, u.correlation_factor,
                                options.hull_with_linearised ? ", at least as wide as the linearised ones" : "",
                                Describe68(u.bulk_inflation, options.profile_68 ? "from the profile" : "linearised"));
    if (exact) {
      u.description += fmt::format("; the re-fits by Ceres with exact derivatives ({} of {}, the others by Nelder–Mead)",
                                   u.exact_refits, u.exact_refits + u.nelder_mead_refits);
    }
    if (best_epsilon.at && best_epsilon.epsilon_rad_s < (1.0 - kBetterPointFraction) * fitted_epsilon_rad_s) {
      u.better_point = best_epsilon.at;
      u.better_epsilon_rad_s = best_epsilon.epsilon_rad_s;
    }
  }
  // Other basins within the thresholds widen the intervals (see the header); SS relative to the lowest known.
  {
    double sum_sq_ref = sum_sq_min;
    std::vector<std::pair<SumOfSquaresValue, ParameterSet>> alt;
    for (const ParameterSet& a : alternatives) {
      ParameterSet set = base;
      for (ParameterId id : profiled) set[id].value = a.value(id);
      const SumOfSquaresValue v = SumOfSquares(ls, set);
      if (!v.feasible) continue;
      sum_sq_ref = std::min(sum_sq_ref, v.sum_sq);
      alt.emplace_back(v, set);
    }
    const std::array<Interval, kNumParameters> profile_95 = u.interval_95;
    for (const auto& [v, set] : alt) {
      bool apart = set.value(ParameterId::kLambdaLat) * fitted.value(ParameterId::kLambdaLat) < 0.0;
      bool within_all = true;
      for (ParameterId id : profiled) {
        const std::size_t k = static_cast<std::size_t>(id);
        auto rise = [&](double inflation) { return std::sqrt(std::max(0.0, v.sum_sq - sum_sq_ref) / (inflation * sum_sq_ref / noise_dof)); };
        const double rho = rise(kappa[k]);
        const double x = set.value(id);
        for (auto [z, level_rho, interval] :
             {std::tuple{kZ68, rise(kappa_68[k]), &u.interval_68[k]}, std::tuple{kZ95, rho, &u.interval_95[k]}}) {
          if (level_rho > z) continue;
          if (!std::isnan((*interval)[0])) (*interval)[0] = std::min((*interval)[0], x);
          if (!std::isnan((*interval)[1])) (*interval)[1] = std::max((*interval)[1], x);
        }
        if (rho > kZ95) within_all = false;
        const Interval& p = profile_95[k];
        const double w = p[1] - p[0];
        if (std::isfinite(w) && (x < p[0] - w || x > p[1] + w)) apart = true;
      }
      if (within_all && apart && (!u.second_solution || v.epsilon_rad_s < u.second_solution_epsilon_rad_s)) {
        u.second_solution = set;
        u.second_solution_epsilon_rad_s = v.epsilon_rad_s;
      }
    }
    for (ParameterId id : profiled) {
      const std::size_t k = static_cast<std::size_t>(id);
      const Parameter& p = objective.parameters()[id];
      u.determined[k] = Determine(u.interval_95[k], p.lower, p.upper, options.undetermined_range_fraction);
    }
  }
  u.statements = DescribeUncertainty(u, fitted);
  u.evaluations = objective.counters().runs() - runs_before;
  u.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return u;
}

}  // namespace rockfit::fitting
