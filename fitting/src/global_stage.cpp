#include "rockfit/fitting/global_stage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <chrono>
#include <numeric>
#include <optional>

#include "parallel_for.hpp"
#include "rockfit/fitting/identifiability.hpp"
#include "rockfit/fitting/latin_hypercube.hpp"
#include "rockfit/fitting/prefix_screen.hpp"

namespace rockfit::fitting {
namespace {

// Two starts closer than this in box-normalised coordinates (each axis scaled to [0, 1]) are the same start.
constexpr double kDistinctStartDistance = 0.05;

// True when moving `id` by ±probe_step from `at` (within its bounds) changes ε on `window` by more than
// `tolerance_rad_s` — CheckIdentifiability's verdict (identifiability.hpp) for one parameter, with the −step probe
// run only when the +step probe shows no change: the same verdict for half the runs where the parameter acts.
bool ActsAt(const Objective& window, const ParameterSet& at, const Evaluation& centre, ParameterId id,
            double tolerance_rad_s, const IdentifiabilityOptions& options) {
  const Parameter& p = window.parameters()[id];
  const double step = options.probe_step[static_cast<std::size_t>(id)];
  for (double direction : {+1.0, -1.0}) {
    ParameterSet probe = at;
    probe[id].value = std::clamp(at.value(id) + direction * step, p.lower, p.upper);
    if (probe[id].value == at.value(id)) continue;
    const Evaluation e = window.Evaluate(probe);
    // A probe where the model fails shows that the parameter matters.
    const double change = e.feasible == centre.feasible ? std::abs(e.epsilon_rad_s - centre.epsilon_rad_s)
                                                        : std::abs(window.options().failure_penalty_rad_s);
    if (change > tolerance_rad_s) return true;
  }
  return false;
}

// `window` with every parameter that does not change ε at `at` held fixed at its value there (all values
// taken from `at`; the verdicts of CheckIdentifiability). nullopt when nothing acts; `window` at `at`'s values,
// nothing held, when the model fails at `at`.
std::optional<Objective> ActingParameters(const Objective& window, const ParameterSet& at,
                                          const IdentifiabilityOptions& options) {
  ParameterSet params = window.parameters();
  for (ParameterId id : kAllParameters) params[id].value = at.value(id);
  const Evaluation centre = window.Evaluate(params);
  if (!centre.feasible) return window.WithParameters(params);
  const double tolerance_rad_s = options.relative_tolerance * std::abs(centre.epsilon_rad_s);
  for (ParameterId id : window.free_ids()) {
    if (!ActsAt(window, params, centre, id, tolerance_rad_s, options)) params[id].fixed = true;
  }
  if (params.FreeIds().empty()) return std::nullopt;
  return window.WithParameters(params);
}

// Nelder–Mead on `window` from the full parameter set `from`; returns the full parameter set it reached.
ParameterSet MinimizeIn(const Objective& window, const ParameterSet& from, const NelderMeadOptions& options,
                        bool* converged, double* epsilon_rad_s = nullptr) {
  const LocalResult r = MakeNelderMead(options)->Minimize(window, window.FreeValues(from));
  *converged = r.converged;
  if (epsilon_rad_s) *epsilon_rad_s = r.feasible ? r.epsilon_rad_s : std::numeric_limits<double>::quiet_NaN();
  return window.WithFree(r.x);
}

// One start on its way from the first window to the full window.
struct Track {
  ParameterSet at;
  std::vector<ParameterId> acting;  // the parameters that have acted in a window so far
  bool converged = true;            // the last local search converged
  bool active = true;               // false: dropped by the stop rule (PruneTracks)
  double window_epsilon_rad_s = std::numeric_limits<double>::quiet_NaN();  // (28) on the last window searched
};

// One window of the continuation for one track: a parameter not yet in `acting` that starts acting in the
// window is first scanned over its bounds at `scan_points` values (0: no scans), then a short Nelder–Mead run.
void StepTrack(const Objective& objective, double window_end, int scan_points, const FitOptions& options,
               const NelderMeadOptions& step_options, Track* track) {
  track->window_epsilon_rad_s = std::numeric_limits<double>::quiet_NaN();
  const std::optional<Objective> window =
      ActingParameters(objective.WithWindowEnd(window_end), track->at, options.identifiability);
  if (!window) return;
  // A parameter that starts acting in this window (λ at the first edge impact) has had no say so far:
  // scan it over its bounds before the local search.
  for (ParameterId id : window->free_ids()) {
    if (std::find(track->acting.begin(), track->acting.end(), id) != track->acting.end()) continue;
    track->acting.push_back(id);
    if (scan_points > 0) track->at = ScanParameter(*window, track->at, id, scan_points, options.global.scan_prefix_fraction);
  }
  bool step_converged = false;
  track->at = MinimizeIn(*window, track->at, step_options, &step_converged, &track->window_epsilon_rad_s);
  track->converged = step_converged;
}

// The stop rule of the continuation: a track is dropped (prune_ratio 0: none is) when both its (28) on the window
// just searched and its error summed over that window, (28)·(window end − t0) [rad], exceed prune_ratio times the
// best track's. (28) is a mean from the track's own t0: a track hovering near θc with t0 far too early adds the
// recorded rest, fitted to the noise, and lowers its mean; the sum does not gain from it (fitting/README.md, "The
// stop rule of the continuation"). Tracks are compared on the same window, after all of them were searched in it,
// so the rule does not depend on the number of threads.
void PruneTracks(double prune_ratio, double window_end_s, std::vector<Track>* tracks) {
  if (!(prune_ratio > 0.0)) return;
  const auto summed_rad = [&](const Track& t) {
    return t.window_epsilon_rad_s * (window_end_s - t.at.value(ParameterId::kT0));
  };
  double best_rad_s = std::numeric_limits<double>::infinity(), best_summed_rad = best_rad_s;
  for (const Track& t : *tracks) {
    if (t.active && std::isfinite(t.window_epsilon_rad_s)) {
      best_rad_s = std::min(best_rad_s, t.window_epsilon_rad_s);
      best_summed_rad = std::min(best_summed_rad, summed_rad(t));
    }
  }
  if (!std::isfinite(best_rad_s)) return;
  for (Track& t : *tracks) {
    if (t.active && std::isfinite(t.window_epsilon_rad_s) && t.window_epsilon_rad_s > prune_ratio * best_rad_s &&
        summed_rad(t) > prune_ratio * best_summed_rad) {
      t.active = false;
    }
  }
}

// Carries the active tracks through windows growing by `continuation_growth` after `t_release_ref` from
// `window_end` to the full window, all tracks window by window (in parallel within a window), with the stop rule
// after each window.
void ContinueTracks(const Objective& objective, double window_end, double t_release_ref, int scan_points,
                    const FitOptions& options, const NelderMeadOptions& step_options, double prune_ratio,
                    std::vector<Track>* tracks) {
  const GlobalStageOptions& g = options.global;
  while (window_end < objective.t_end_s()) {
    window_end = std::min(objective.t_end_s(), t_release_ref + (window_end - t_release_ref) * g.continuation_growth);
    ParallelFor(tracks->size(), options.num_threads, [&](std::size_t i) {
      Track& track = (*tracks)[i];
      if (track.active) StepTrack(objective, window_end, scan_points, options, step_options, &track);
    });
    PruneTracks(prune_ratio, window_end, tracks);
  }
}

// One start carried to the full window alone (no stop rule).
ParameterSet ContinueToFullWindow(const Objective& objective, const ParameterSet& from, double window_end,
                                  double t_release_ref, std::vector<ParameterId> acting, int scan_points,
                                  const FitOptions& options, const NelderMeadOptions& step_options, bool* converged) {
  std::vector<Track> tracks(1);
  tracks[0].at = from;
  tracks[0].acting = std::move(acting);
  ContinueTracks(objective, window_end, t_release_ref, scan_points, options, step_options, 0.0, &tracks);
  *converged = tracks[0].converged;
  return tracks[0].at;
}

// The joint scan of λ and λ_lat on the full window around `at`: λ at `scan_points` values over its bounds times
// λ_lat at `joint_scan_lat_points` values within ±joint_scan_lat_fraction of its value at `at`, evaluated in
// parallel. Returns the best grid point; nullopt when λ or λ_lat is not free, λ_lat is 0 or no point is feasible.
std::optional<ParameterSet> JointLambdaScan(const Objective& objective, const ParameterSet& at,
                                            const GlobalStageOptions& g, int num_threads) {
  const bool both_free = objective.IsFree(ParameterId::kLambda) && objective.IsFree(ParameterId::kLambdaLat);
  const double lat0 = at.value(ParameterId::kLambdaLat);
  if (!both_free || g.joint_scan_lat_points < 1 || lat0 == 0.0) return std::nullopt;
  const Parameter& lambda = objective.parameters()[ParameterId::kLambda];
  const Parameter& lat = objective.parameters()[ParameterId::kLambdaLat];
  const int n_lat = g.joint_scan_lat_points;
  std::vector<ParameterSet> grid;
  for (int j = 0; j < g.scan_points; ++j) {
    for (int k = 0; k < n_lat; ++k) {
      ParameterSet q = at;
      q[ParameterId::kLambda].value = lambda.lower + (lambda.upper - lambda.lower) * (j + 0.5) / g.scan_points;
      const double f = n_lat > 1 ? g.joint_scan_lat_fraction * (2.0 * k / (n_lat - 1) - 1.0) : 0.0;
      q[ParameterId::kLambdaLat].value = std::clamp(lat0 * (1.0 + f), lat.lower, lat.upper);
      grid.push_back(std::move(q));
    }
  }
  const std::optional<std::size_t> best = ScreenedArgmin(objective, grid, g.scan_prefix_fraction, num_threads);
  if (!best) return std::nullopt;
  return grid[*best];
}

// The scan along the ridge of (28) in (t0, α, λ_lon). The data fix the first impact t1 = t0 + T(α) much better
// than t0 and α apart (T the model's fall time), and the rate after it, which λ_lon scales, better than the rate
// before it, which α sets; near θ_c the local searches barely move along this ridge. t0 is moved by
// `ridge_points` equally spaced steps within ±ridge_t0_halfwidth_s and α with it so that t1 stays (to first
// order: dα = −dt0 / T'(α), T' by a central difference of two model runs); at each point λ_lon (when free) is
// re-fitted by a parabola through three values ridge_lambda_lon_step apart around its value at the previous
// point, walking outwards from `at`. Returns the best point (nullopt when t0 or α is not free or the model has
// no impact).
std::optional<ParameterSet> RidgeScan(const Objective& objective, const ParameterSet& at, const GlobalStageOptions& g) {
  if (!objective.IsFree(ParameterId::kT0) || !objective.IsFree(ParameterId::kAlpha) || g.ridge_points < 1) {
    return std::nullopt;
  }
  const Parameter& t0 = objective.parameters()[ParameterId::kT0];
  const Parameter& alpha = objective.parameters()[ParameterId::kAlpha];
  const Parameter& lon = objective.parameters()[ParameterId::kLambdaLon];
  const double alpha0 = at.value(ParameterId::kAlpha);
  const std::optional<double> fall_slope = FallTimeSlope(objective, at, g.ridge_alpha_difference_rad);
  if (!fall_slope) return std::nullopt;
  const double dfall_dalpha = *fall_slope;  // T'(α) > 0 [s/rad]

  std::optional<ParameterSet> best;
  double best_epsilon = 0.0;
  auto evaluate = [&](const ParameterSet& q) {
    const Evaluation e = objective.Evaluate(q);
    if (e.feasible && (!best || e.epsilon_rad_s < best_epsilon)) {
      best = q;
      best_epsilon = e.epsilon_rad_s;
    }
    return e.feasible ? e.epsilon_rad_s : std::numeric_limits<double>::infinity();
  };
  // One ridge point at t0 + dt0 with λ_lon re-fitted around `lon_center`; returns the λ_lon it chose.
  auto ridge_point = [&](double dt0, double lon_center) {
    ParameterSet q = at;
    q[ParameterId::kT0].value = std::clamp(at.value(ParameterId::kT0) + dt0, t0.lower, t0.upper);
    q[ParameterId::kAlpha].value = std::clamp(alpha0 - dt0 / dfall_dalpha, alpha.lower, alpha.upper);
    if (!objective.IsFree(ParameterId::kLambdaLon)) {
      evaluate(q);
      return lon_center;
    }
    const double d = g.ridge_lambda_lon_step;
    std::array<double, 3> x{}, f{};
    for (int j = 0; j < 3; ++j) {
      x[j] = std::clamp(lon_center + (j - 1) * d, lon.lower, lon.upper);
      q[ParameterId::kLambdaLon].value = x[j];
      f[j] = evaluate(q);
    }
    const int j_best = static_cast<int>(std::min_element(f.begin(), f.end()) - f.begin());
    double chosen = x[j_best];
    const double curvature = f[0] - 2.0 * f[1] + f[2];
    if (std::isfinite(curvature) && curvature > 0.0) {
      const double vertex = std::clamp(lon_center + 0.5 * d * (f[0] - f[2]) / curvature, lon_center - 2.0 * d,
                                       lon_center + 2.0 * d);
      q[ParameterId::kLambdaLon].value = std::clamp(vertex, lon.lower, lon.upper);
      if (evaluate(q) < f[j_best]) chosen = q.value(ParameterId::kLambdaLon);
    }
    return chosen;
  };
  const int half = g.ridge_points / 2;
  const double step_s = half > 0 ? g.ridge_t0_halfwidth_s / half : 0.0;
  const double lon0 = at.value(ParameterId::kLambdaLon);
  const double lon_at_center = ridge_point(0.0, lon0);
  for (int direction : {+1, -1}) {
    double lon_center = lon_at_center;
    for (int k = 1; k <= half; ++k) lon_center = ridge_point(direction * k * step_s, lon_center);
  }
  return best;
}
}  // namespace

void GlobalSamplingBox(const Objective& objective, const Eigen::VectorXd& estimate, const GlobalStageOptions& options,
                       Eigen::VectorXd* lower, Eigen::VectorXd* upper) {
  *lower = objective.FreeLower();
  *upper = objective.FreeUpper();
  for (std::size_t i = 0; i < objective.num_free(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    double half_width = 0.0;
    if (objective.free_ids()[i] == ParameterId::kT0) half_width = options.t0_halfwidth_s;
    if (objective.free_ids()[i] == ParameterId::kAlpha) half_width = options.alpha_halfwidth_rad;
    if (half_width > 0.0) {
      (*lower)[k] = std::max((*lower)[k], estimate[k] - half_width);
      (*upper)[k] = std::min((*upper)[k], estimate[k] + half_width);
    }
  }
}

namespace {

// The first window's starts: the estimate and a Latin hypercube over the sampling box, evaluated in parallel; when
// none is feasible (e.g. the estimate's tilt is beyond the critical angle) a second hypercube over the bounds.
struct FirstWindowSamples {
  std::vector<Eigen::VectorXd> points;
  std::vector<Evaluation> values;
  Eigen::VectorXd lower, upper;  // the box the points were drawn from
  int num_feasible() const {
    return static_cast<int>(std::count_if(values.begin(), values.end(), [](const Evaluation& e) { return e.feasible; }));
  }
};

FirstWindowSamples SampleFirstWindow(const Objective& first, const Eigen::VectorXd& first_estimate,
                                     const FitOptions& options) {
  const GlobalStageOptions& g = options.global;
  FirstWindowSamples s;
  GlobalSamplingBox(first, first_estimate, g, &s.lower, &s.upper);
  s.points = {first_estimate};
  for (Eigen::VectorXd& p : LatinHypercube(s.lower, s.upper, g.num_samples, g.seed)) s.points.push_back(std::move(p));
  s.values.resize(s.points.size());
  ParallelFor(s.points.size(), options.num_threads, [&](std::size_t i) { s.values[i] = first.EvaluateFree(s.points[i]); });
  if (s.num_feasible() > 0) return s;
  s.lower = first.FreeLower();
  s.upper = first.FreeUpper();
  std::vector<Eigen::VectorXd> wide = LatinHypercube(s.lower, s.upper, g.num_samples, g.seed + 1);
  const std::size_t offset = s.points.size();
  s.points.insert(s.points.end(), wide.begin(), wide.end());
  s.values.resize(s.points.size());
  ParallelFor(wide.size(), options.num_threads,
              [&](std::size_t i) { s.values[offset + i] = first.EvaluateFree(s.points[offset + i]); });
  return s;
}

// The first index in `order` that is feasible with λ_lat of sign `sign`: the sign selects the vertex the block
// rocks on after the facet impact, so each sign keeps its best start (docs/design.md §3).
template <class LambdaLatOf, class FeasibleAt>
std::optional<std::size_t> BestOfSign(const std::vector<std::size_t>& order, int sign, const LambdaLatOf& lambda_lat_of,
                                      const FeasibleAt& feasible_at) {
  for (std::size_t i : order) {
    if (feasible_at(i) && sign * lambda_lat_of(i) > 0.0) return i;
  }
  return std::nullopt;
}

// Indices in ascending order of `epsilon_of` (stable).
template <class EpsilonOf>
std::vector<std::size_t> OrderByEpsilon(std::size_t n, const EpsilonOf& epsilon_of) {
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return epsilon_of(a) < epsilon_of(b); });
  return order;
}

// The starts to polish: the best of each sign of λ_lat, then the best others, all distinct in the box.
std::vector<std::size_t> ChooseStartsToPolish(const Objective& first, const FirstWindowSamples& s,
                                              const GlobalStageOptions& g) {
  const std::vector<std::size_t> order =
      OrderByEpsilon(s.points.size(), [&](std::size_t i) { return s.values[i].epsilon_rad_s; });
  const Eigen::VectorXd box = (s.upper - s.lower).cwiseMax(1e-300);
  std::vector<std::size_t> chosen;
  auto distinct = [&](std::size_t candidate) {
    for (std::size_t c : chosen) {
      if ((s.points[c] - s.points[candidate]).cwiseQuotient(box).norm() < kDistinctStartDistance) return false;
    }
    return true;
  };
  const auto& ids = first.free_ids();
  const auto lat = std::find(ids.begin(), ids.end(), ParameterId::kLambdaLat);
  if (lat != ids.end()) {
    const auto k = static_cast<Eigen::Index>(lat - ids.begin());
    for (int sign : {+1, -1}) {
      const std::optional<std::size_t> best = BestOfSign(
          order, sign, [&](std::size_t i) { return s.points[i][k]; }, [&](std::size_t i) { return s.values[i].feasible; });
      if (best && distinct(*best)) chosen.push_back(*best);
    }
  }
  for (std::size_t i : order) {
    if (static_cast<int>(chosen.size()) >= g.num_polished) break;
    if (distinct(i)) chosen.push_back(i);
  }
  return chosen;
}

// Nelder–Mead from each chosen start in parallel; the starts carried on: the best of each λ_lat sign (the better
// of the two first), then the best others, num_continued in all.
std::vector<ParameterSet> PolishAndCarry(const Objective& first, const FirstWindowSamples& s,
                                         const std::vector<std::size_t>& chosen, const FitOptions& options) {
  const GlobalStageOptions& g = options.global;
  NelderMeadOptions polish = options.nelder_mead;
  polish.max_evaluations = g.polish_evaluations;
  std::vector<LocalResult> runs(chosen.size());
  ParallelFor(chosen.size(), options.num_threads, [&](std::size_t i) {
    runs[i] = MakeNelderMead(polish)->Minimize(first, s.points[chosen[i]]);
  });
  const auto epsilon_of = [&](std::size_t i) { return runs[i].epsilon_rad_s; };
  const std::vector<std::size_t> by_epsilon = OrderByEpsilon(runs.size(), epsilon_of);
  std::vector<std::size_t> carry;
  for (int sign : {+1, -1}) {
    const std::optional<std::size_t> best = BestOfSign(
        by_epsilon, sign, [&](std::size_t i) { return first.WithFree(runs[i].x).value(ParameterId::kLambdaLat); },
        [&](std::size_t i) { return runs[i].feasible; });
    if (best) carry.push_back(*best);
  }
  for (std::size_t i : by_epsilon) {
    if (std::find(carry.begin(), carry.end(), i) == carry.end()) carry.push_back(i);
  }
  std::stable_sort(carry.begin(), carry.begin() + std::min<std::ptrdiff_t>(2, static_cast<std::ptrdiff_t>(carry.size())),
                   [&](std::size_t a, std::size_t b) { return epsilon_of(a) < epsilon_of(b); });
  carry.resize(std::min(carry.size(), static_cast<std::size_t>(g.num_continued)));
  std::vector<ParameterSet> carried;
  for (std::size_t i : carry) carried.push_back(first.WithFree(runs[i].x));
  return carried;
}

// What every carried start shares on its way to the full window.
struct Continuation {
  double first_window_end_s = 0.0;
  double t_release_ref_s = 0.0;  // windows grow by continuation_growth after this time
  std::vector<ParameterId> first_acting;
  NelderMeadOptions step_options;
};

// The local searches of the continuation: short, from a smaller simplex, so that the search stays in the basin it
// tracks from one window to the next.
NelderMeadOptions ContinuationStepOptions(const FitOptions& options) {
  NelderMeadOptions step_options = options.nelder_mead;
  step_options.max_evaluations = options.global.continuation_evaluations;
  for (double& step : step_options.initial_step) step *= options.global.continuation_step_fraction;
  return step_options;
}

// A start carried to the full window: there, every parameter sampled over its whole bounds (not t0 and α, which
// phase 1 pins down) is scanned once more: later impacts can make its landscape multimodal where the first windows
// were not (e.g. λ with a long cascade of small lateral edge impacts). Then a last local search.
ParameterSet RescanOnFullWindow(const Objective& objective, ParameterSet at, const Continuation& plan,
                                const FitOptions& options, bool* converged) {
  const GlobalStageOptions& g = options.global;
  if (!g.final_scan) return at;
  ParameterSet scanned = at;
  const Evaluation before = objective.Evaluate(at);
  for (ParameterId id : objective.free_ids()) {
    if (id == ParameterId::kT0 || id == ParameterId::kAlpha) continue;
    scanned = ScanParameter(objective, scanned, id, g.scan_points, g.scan_prefix_fraction);
  }
  if (objective.Evaluate(scanned).epsilon_rad_s < before.epsilon_rad_s) {
    bool step_converged = false;
    at = MinimizeIn(objective, scanned, plan.step_options, &step_converged);
    *converged = step_converged;
  }
  return at;
}

// Step 4: the best of a joint (λ, λ_lat) scan joins the best point as a second candidate; each is carried once
// more from the first window to the full window (every parameter acts already: no scans; the first windows see t0,
// α and λ_lon best, and λ_lat and λ, weakly seen there, are settled by the last search), scanned along the
// t0–α–λ_lon ridge and searched locally. Candidates are independent: deterministic in any thread count.
void Refine(const Objective& objective, const Continuation& plan, const FitOptions& options, GlobalStageResult* result) {
  const ParameterSet best_set = objective.WithFree(result->best_x);
  std::vector<ParameterSet> candidates = {best_set};
  if (std::optional<ParameterSet> joint = JointLambdaScan(objective, best_set, options.global, options.num_threads)) {
    candidates.push_back(*joint);
  }
  std::vector<ParameterSet> refined(candidates.size());
  std::vector<Evaluation> refined_e(candidates.size());
  std::vector<char> refine_converged(candidates.size(), 0);
  ParallelFor(candidates.size(), options.num_threads, [&](std::size_t i) {
    bool ok = true;
    ParameterSet at = ContinueToFullWindow(objective, candidates[i], plan.first_window_end_s, plan.t_release_ref_s,
                                           objective.free_ids(), 0, options, plan.step_options, &ok);
    const Evaluation continued_e = objective.Evaluate(at);
    const std::optional<ParameterSet> ridge = RidgeScan(objective, at, options.global);
    if (ridge && objective.Evaluate(*ridge).epsilon_rad_s < continued_e.epsilon_rad_s) at = *ridge;
    at = MinimizeIn(objective, at, plan.step_options, &ok);
    refined[i] = at;
    refined_e[i] = objective.Evaluate(at);
    refine_converged[i] = ok ? 1 : 0;
  });
  for (std::size_t i = 0; i < refined.size(); ++i) {
    if (refined_e[i].feasible) result->candidates.emplace_back(objective.FreeValues(refined[i]), refined_e[i].epsilon_rad_s);
    if (refined_e[i].feasible && refined_e[i].epsilon_rad_s < result->best_epsilon_rad_s) {
      result->best_x = objective.FreeValues(refined[i]);
      result->best_epsilon_rad_s = refined_e[i].epsilon_rad_s;
      result->converged = refine_converged[i] != 0;
    }
  }
}

}  // namespace

ParameterSet ScanParameter(const Objective& window, const ParameterSet& at, ParameterId id, int points,
                           double prefix_fraction) {
  const Parameter& p = window.parameters()[id];
  const PrefixScreen screen(window, prefix_fraction);
  std::vector<ParameterSet> trials(static_cast<std::size_t>(std::max(points, 0)), at);
  std::vector<PrefixBound> bounds(trials.size());
  for (std::size_t j = 0; j < trials.size(); ++j) {
    trials[j][id].value = p.lower + (p.upper - p.lower) * (static_cast<double>(j) + 0.5) / points;
    bounds[j] = screen.Bound(trials[j]);
  }
  // The values run over the whole window in the order of their bounds, until the next bound rules out the rest:
  // every value whose (28) is at most the best's is run (its bound is at most its (28)), so the result is that of
  // running them all — the first of the values with the lowest (28), when that lies below (28) at `at`.
  std::vector<std::size_t> order;
  for (std::size_t j = 0; j < trials.size(); ++j) {
    if (bounds[j].feasible) order.push_back(j);  // a prefix on which the model fails: the whole window fails too
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return bounds[a].epsilon_lower_rad_s < bounds[b].epsilon_lower_rad_s;
  });
  Evaluation best_e = window.Evaluate(at);
  std::optional<std::size_t> best;  // nullopt: `at` itself
  for (std::size_t j : order) {
    const double to_beat = best_e.feasible ? best_e.epsilon_rad_s : std::numeric_limits<double>::infinity();
    if (PrefixScreen::CannotBeatWithBound(bounds[j], to_beat)) break;
    const Evaluation e = window.Evaluate(trials[j]);
    if (!e.feasible) continue;
    const bool lower = !best_e.feasible || e.epsilon_rad_s < best_e.epsilon_rad_s;
    const bool equal_and_earlier = best && e.epsilon_rad_s == best_e.epsilon_rad_s && j < *best;
    if (lower || equal_and_earlier) {
      best = j;
      best_e = e;
    }
  }
  return best ? trials[*best] : at;
}

std::optional<double> FirstImpactTime(const Objective& objective, const ParameterSet& at) {
  ErrorNodes nodes;
  ModelOutput output;
  if (!objective.EvaluateDetailed(at, &nodes, &output).feasible || output.events.empty()) return std::nullopt;
  return at.value(ParameterId::kT0) + output.events.front().t_s;
}

std::optional<double> FallTimeSlope(const Objective& objective, const ParameterSet& at, double h_rad,
                                    std::int64_t* model_runs) {
  const Parameter& alpha = objective.parameters()[ParameterId::kAlpha];
  const double alpha0 = at.value(ParameterId::kAlpha);
  if (alpha0 - h_rad < alpha.lower || alpha0 + h_rad > alpha.upper) return std::nullopt;
  auto fall_time = [&](double alpha_rad) -> std::optional<double> {
    ParameterSet q = at;
    q[ParameterId::kAlpha].value = alpha_rad;
    if (model_runs != nullptr) ++*model_runs;
    const std::optional<double> t1 = FirstImpactTime(objective, q);
    if (!t1) return std::nullopt;
    return *t1 - q.value(ParameterId::kT0);
  };
  const std::optional<double> fall_minus = fall_time(alpha0 - h_rad);
  const std::optional<double> fall_plus = fall_time(alpha0 + h_rad);
  if (!fall_minus || !fall_plus || !(*fall_plus > *fall_minus)) return std::nullopt;
  return (*fall_plus - *fall_minus) / (2.0 * h_rad);
}

GlobalStageResult RunGlobalStage(const Objective& objective, const Eigen::VectorXd& estimate_in,
                                 const FitOptions& options) {
  options.Validate();
  const GlobalStageOptions& g = options.global;
  const auto clock_start = std::chrono::steady_clock::now();
  const std::int64_t runs_before = objective.counters().runs();
  GlobalStageResult result;
  const Eigen::VectorXd estimate = estimate_in.cwiseMax(objective.FreeLower()).cwiseMin(objective.FreeUpper());
  const ParameterSet estimate_set = objective.WithFree(estimate);

  // 1. The first window, the parameters acting in it, and the polished starts to carry from it.
  const std::optional<double> t1 = FirstImpactTime(objective, estimate_set);
  double t_first_end = objective.t_end_s();
  if (t1 && *t1 + g.first_window_s < objective.t_end_s()) t_first_end = *t1 + g.first_window_s;
  result.first_window_end_s = t_first_end;
  const std::optional<Objective> first =
      ActingParameters(objective.WithWindowEnd(t_first_end), estimate_set, options.identifiability);
  std::vector<ParameterSet> carried;
  if (first) {
    const FirstWindowSamples samples = SampleFirstWindow(*first, first->FreeValues(estimate_set), options);
    result.num_samples = static_cast<int>(samples.points.size());
    result.num_feasible_samples = samples.num_feasible();
    carried = PolishAndCarry(*first, samples, ChooseStartsToPolish(*first, samples, g), options);
  }
  if (carried.empty()) carried.push_back(estimate_set);

  // 2. Continuation to the full window, each carried start in its own thread.
  Continuation plan;
  plan.first_window_end_s = t_first_end;
  plan.t_release_ref_s = t1 ? *t1 : objective.t_end_s();
  plan.first_acting = first ? first->free_ids() : std::vector<ParameterId>{};
  plan.step_options = ContinuationStepOptions(options);
  // The tracks go window by window; one that falls far behind the best is dropped (the stop rule).
  std::vector<Track> tracks(carried.size());
  for (std::size_t i = 0; i < carried.size(); ++i) {
    tracks[i].at = carried[i];
    tracks[i].acting = plan.first_acting;
  }
  ContinueTracks(objective, plan.first_window_end_s, plan.t_release_ref_s, g.scan_points, options, plan.step_options,
                 g.continuation_prune_ratio, &tracks);
  std::vector<Track> arrived;
  for (Track& t : tracks) {
    if (t.active) arrived.push_back(std::move(t));
  }
  std::vector<ParameterSet> continued(arrived.size());
  std::vector<char> converged(arrived.size(), 0);
  ParallelFor(arrived.size(), options.num_threads, [&](std::size_t i) {
    bool ok = arrived[i].converged;
    continued[i] = RescanOnFullWindow(objective, arrived[i].at, plan, options, &ok);
    converged[i] = ok ? 1 : 0;
  });
  result.num_continued = static_cast<int>(continued.size());

  // 3. The best on the full window.
  for (std::size_t i = 0; i < continued.size(); ++i) {
    const Evaluation e = objective.Evaluate(continued[i]);
    if (e.feasible) result.candidates.emplace_back(objective.FreeValues(continued[i]), e.epsilon_rad_s);
    if (i == 0 || (e.feasible && !result.feasible) ||
        (e.feasible == result.feasible && e.epsilon_rad_s < result.best_epsilon_rad_s)) {
      result.best_x = objective.FreeValues(continued[i]);
      result.best_epsilon_rad_s = e.epsilon_rad_s;
      result.feasible = e.feasible;
      result.converged = converged[i] != 0;
    }
  }

  // 4. Refinement of the best point (see the header).
  if (g.refine && result.feasible) Refine(objective, plan, options, &result);
  result.evaluations = objective.counters().runs() - runs_before;
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace rockfit::fitting
