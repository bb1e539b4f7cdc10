// Event location on one integrator step (docs/design.md §4): a guard function g(t) (a vertex height, the margin of
// the COM over its support, a tilt) must not go below zero unnoticed, not even when it dips below and comes
// back within the step. Steps are short against the rocking time scale, so g usually has at most one extremum
// per step; the sign of ġ at the two step ends tells whether an interior minimum exists, and that minimum is
// bounded from below (TimeBelowZeroNearMinimum) or searched on the dense output. A guard that turns twice within
// a step (under a moving table) is caught by the step's Hermite cubic (HermiteDipTime). A crossing is polished by
// Newton's method on g and ġ inside its bracket (PolishCrossing), which Newton's error bound ends without a
// confirming evaluation; a vertex that lifts and lands within one step is searched from the landing of the step's
// Hermite cubic (LandingAfterHop); the maximum of a guard that rose and fell back within a step, which needs only
// ġ, by GSL's Brent solver (where the Hermite landing does not apply).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace rockfit::core {

struct GuardValue {
  double value = 0.0;  // g
  double rate = 0.0;   // ġ
};

// Brent's method (gsl_root_fsolver_brent) with one solver allocated per instance.
class RootPolisher {
 public:
  RootPolisher();
  ~RootPolisher();
  RootPolisher(const RootPolisher&) = delete;
  RootPolisher& operator=(const RootPolisher&) = delete;

  // A root of f in [lo, hi] where f(lo) and f(hi) do not have the same strict sign, to an interval
  // shorter than `tolerance`. Empty if the solver fails (e.g. a non-finite f).
  template <class F>
  std::optional<double> Solve(const F& f, double lo, double hi, double tolerance) {
    return SolveErased(&Trampoline<F>, const_cast<F*>(&f), lo, hi, tolerance);
  }

 private:
  template <class F>
  static double Trampoline(double x, void* raw) {
    return (*static_cast<const F*>(raw))(x);
  }
  std::optional<double> SolveErased(double (*f)(double, void*), void* params, double lo, double hi,
                                    double tolerance);
  void* solver_;  // gsl_root_fsolver*
};

// A bound of |g̈| over a step [t0, t1] for Newton's error bound (NewtonInBracket): the larger |p''| of the cubic p
// through g and ġ at both ends of the step (Hermite) at the two ends (p'' is linear: its largest value on the step),
// times a safety factor for the difference between the cubic and the guard.
inline double HermiteCurvatureBound(double t0, const GuardValue& g0, double t1, const GuardValue& g1) {
  // The cubic's curvature is the guard's to within the step's interpolation error; over a step that turns the body
  // by at most half a radian (a vertex height A cos(ω t) + C) that is far below a factor of four.
  constexpr double kCurvatureSafety = 4.0;
  const double h = t1 - t0;
  // p(s) = a s³ + b s² + c s + d on s ∈ [0, 1], t = t0 + s h: p''(0) = 2b, p''(1) = 6a + 2b.
  const double b = 3.0 * (g1.value - g0.value) - 2.0 * h * g0.rate - h * g1.rate;
  const double a = 2.0 * (g0.value - g1.value) + h * g0.rate + h * g1.rate;
  return kCurvatureSafety * std::max(std::abs(2.0 * b), std::abs(6.0 * a + 2.0 * b)) / (h * h);
}

// Newton steps on g from x inside the bracket [a, b] of a crossing, where g is positive at a (`positive_at_a`) or at
// b: the steps are kept inside the bracket, which shrinks with every evaluation; a step that leaves the bracket, or
// that does not at least halve the one before it, becomes a bisection. It ends when a step or the bracket is
// within round-off of t. With a bound of |g̈| on the bracket (`curvature_bound` > 0) it also ends after a Newton
// step whose successor would be below round-off: Newton's error after a step δ from x is at most
// |g̈| δ² / (2 |ġ(x)|) (quadratic convergence), and where that is below round-off of t the evaluation at the new
// point would only confirm it. The bound is raised to the difference quotient of ġ between the last two points
// where that is larger (times the same safety factor of four). Empty if g is not finite. The loop of
// PolishCrossing and LandingAfterHop.
template <class Eval>
std::optional<double> NewtonInBracket(const Eval& eval, double a, double b, bool positive_at_a, double x,
                                      double curvature_bound = 0.0) {
  constexpr int kMaxIterations = 200;  // bisection alone closes any bracket of a step in fewer
  constexpr double kCurvatureSafety = 4.0;  // as HermiteCurvatureBound's
  // Newton's error bound is used once the relative change of ġ over a step is below this (the bound's
  // (δ + error)² ≈ δ² then holds to a few per cent, which the factor of two below covers).
  constexpr double kQuadraticRegime = 0.1;
  double step_before = b - a;
  double x_before = std::numeric_limits<double>::quiet_NaN();
  double rate_before = 0.0;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const GuardValue gx = eval(x);
    if (!std::isfinite(gx.value) || !std::isfinite(gx.rate)) return std::nullopt;
    if (gx.value == 0.0) return x;
    // Round-off of t: a few units in the last place.
    const double floor_s = 4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(x));
    double next = x - gx.value / gx.rate;  // (a zero rate gives ±inf or NaN: not inside the bracket)
    double step = std::abs(next - x);
    if (step <= floor_s) return x;  // (x is then also an end of the bracket: test before the bracket's test)
    ((gx.value > 0.0) == positive_at_a ? a : b) = x;
    if (!(next > a && next < b) || step > 0.5 * step_before) {
      next = 0.5 * (a + b);
      step = 0.5 * (b - a);
    } else if (curvature_bound > 0.0) {
      double curvature = curvature_bound;
      if (std::isfinite(x_before) && x_before != x) {
        curvature = std::max(curvature, kCurvatureSafety * std::abs((gx.rate - rate_before) / (x - x_before)));
      }
      const double k = curvature / (2.0 * std::abs(gx.rate));  // error of next ≤ k · step²
      if (k * step <= kQuadraticRegime && 2.0 * k * step * step <= floor_s) return next;
    }
    if (step <= floor_s || b - a <= floor_s) return next;
    step_before = step;
    x_before = x;
    rate_before = gx.rate;
    x = next;
  }
  return 0.5 * (a + b);
}

// A root of g in [a, b], where g(a) and g(b) do not have the same strict sign, with g and ġ at both ends.
// Newton steps from the secant root of the bracket (a Newton step from either end can overshoot the other), kept
// inside the bracket (NewtonInBracket). On the chattering benchmark record of the response it needs 8–9
// evaluations a crossing (many brackets start at a guard's maximum, where Newton starts slowly), where Brent's
// method on g alone needed 12 to close the bracket to 1e-12 s. Polishing to round-off rather than to a
// tolerance matters for runs that should agree: rocking that wobbles along a base edge amplifies a difference
// in an event time a hundredfold within tens of impacts, and a run whose events are off by up to the tolerance
// seeds that difference at the tolerance instead of at round-off. Empty if g is not finite.
template <class Eval>
std::optional<double> PolishCrossing(const Eval& eval, double a, GuardValue ga, double b, GuardValue gb,
                                     double curvature_bound = 0.0) {
  if (ga.value == 0.0) return a;
  if (gb.value == 0.0) return b;
  if ((ga.value > 0.0) == (gb.value > 0.0)) return std::nullopt;
  double x = a - ga.value * (b - a) / (gb.value - ga.value);
  if (!(x > a && x < b)) x = 0.5 * (a + b);
  return NewtonInBracket(eval, a, b, ga.value > 0.0, x, curvature_bound);
}

// For a guard that leaves the surface rising at t0 (g0 = 0, ġ0 > 0) and is below it at t1: the time at which the
// cubic through g and ġ at both ends of the step (Hermite) comes back to zero; empty where the ends do not fit
// that shape. With p(s) = a s³ + b s² + c s on s ∈ [0, 1] (t = t0 + s h, p(0) = 0), the landing is the root of
// a s² + b s + c, positive at s = 0 (c = h ġ0) and negative at s = 1 (its value there is g1): one root in (0, 1).
// Over a step that turns the body by at most half a radian the cubic is close to the guard (a hop of a vertex is
// a hump of A cos(ω t) + C), so the root is a first point from which Newton's method needs one or two steps.
inline std::optional<double> HermiteLandingTime(double t0, const GuardValue& g0, double t1, const GuardValue& g1) {
  if (!(g0.value == 0.0 && g0.rate > 0.0 && g1.value < 0.0)) return std::nullopt;
  const double h = t1 - t0;
  const double c = h * g0.rate;
  const double b = 3.0 * g1.value - 2.0 * h * g0.rate - h * g1.rate;
  const double a = -2.0 * g1.value + h * g0.rate + h * g1.rate;
  double s = -1.0;
  if (a == 0.0) {
    if (b != 0.0) s = -c / b;
  } else {
    const double discriminant = b * b - 4.0 * a * c;
    if (discriminant < 0.0) return std::nullopt;
    // The two roots without cancellation: q/a and c/q.
    const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
    if (q == 0.0) return std::nullopt;
    const double root_1 = q / a, root_2 = c / q;
    s = (root_1 > 0.0 && root_1 < 1.0) ? root_1 : root_2;
  }
  if (!(s > 0.0 && s < 1.0)) return std::nullopt;
  return t0 + s * h;
}

// The landing of a guard that leaves the surface rising at t0 and is below it and falling at t1 (a vertex that
// lifts and lands within one step), to round-off: Newton's method from the step's Hermite landing
// (HermiteLandingTime) inside [t0, t1], where g is positive just after t0. Empty where the cubic has no landing or
// the evaluations do not show one hump (a point below the surface that is not falling: a hop too short to see,
// which the caller's search by halving handles); the landing's rate is negative.
template <class Eval>
std::optional<double> LandingAfterHop(const Eval& eval, double t0, const GuardValue& g0, double t1,
                                      const GuardValue& g1) {
  const std::optional<double> guess = HermiteLandingTime(t0, g0, t1, g1);
  if (!guess) return std::nullopt;
  GuardValue last;
  bool one_hump = true;
  const auto watched = [&](double t) {
    last = eval(t);
    if (last.value <= 0.0 && !(last.rate < 0.0)) one_hump = false;
    return last;
  };
  const std::optional<double> root =
      NewtonInBracket(watched, t0, t1, true, *guess, HermiteCurvatureBound(t0, g0, t1, g1));
  if (!root || !one_hump || !(last.rate < 0.0) || !(*root > t0)) return std::nullopt;
  return root;
}

// Inside a step where g has its minimum (ġ(t0) < 0 < ġ(t1)): a time at which g < 0, or empty when g stays
// non-negative. g is convex around its minimum over a step (a height under a steady rotation is A cos θ + C, and
// a step turns the body by less than π/2), so the tangents at the ends of any bracket of the minimum bound g
// from below: their intersection's value is a lower bound, and once it is positive there is no dip. Each new
// point is the secant root of ġ (exact for a parabola), with bisection when the bracket does not shrink by a
// quarter. A dip that clears the ground by more than the tangents' gap ends without any evaluation.
template <class Eval>
std::optional<double> TimeBelowZeroNearMinimum(const Eval& eval, double t0, const GuardValue& g0, double t1,
                                               const GuardValue& g1, double extremum_tol) {
  constexpr int kMaxIterations = 100;
  double a = t0, b = t1;
  GuardValue ga = g0, gb = g1;
  double width_before = 2.0 * (b - a);
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    // The tangents at a and b meet at t_x; by convexity g ≥ their value there on [a, b].
    const double slope_gap = gb.rate - ga.rate;  // > 0
    const double t_x = (gb.value - ga.value + ga.rate * a - gb.rate * b) / -slope_gap;
    const double lower_bound = ga.value + ga.rate * (std::clamp(t_x, a, b) - a);
    if (lower_bound > 0.0) return std::nullopt;
    const double width = b - a;
    if (width < extremum_tol) {
      const double mid = 0.5 * (a + b);
      return eval(mid).value < 0.0 ? std::optional<double>(mid) : std::nullopt;
    }
    double x = a - ga.rate * width / slope_gap;  // the secant root of ġ
    if (!(x > a && x < b) || width > 0.75 * width_before) x = 0.5 * (a + b);
    width_before = width;
    const GuardValue gx = eval(x);
    if (!std::isfinite(gx.value) || !std::isfinite(gx.rate)) return std::nullopt;
    if (gx.value < 0.0) return x;
    if (gx.rate == 0.0) return std::nullopt;  // the minimum itself, and it is not below zero
    (gx.rate < 0.0 ? a : b) = x;
    (gx.rate < 0.0 ? ga : gb) = gx;
  }
  return std::nullopt;
}

// Where the cubic through g and ġ at both ends of a step (Hermite) has a minimum below zero inside the step, the
// time of that minimum; empty otherwise. A guard that turns twice within a step (a maximum, then a minimum: the
// table's acceleration turning a height of micrometres around) can dip below zero and end above it with no sign
// at the ends that the one-extremum tests read; the cubic shows it, and the dense output at its minimum confirms it.
inline std::optional<double> HermiteDipTime(double t0, const GuardValue& g0, double t1, const GuardValue& g1) {
  // Dips of the cubic shallower than this fraction of the guard's change over the step are not followed: the
  // cubic differs from the dense output by more than that near a start at rest on the surface (a block lifted
  // by the table: ψ grows as (t − t0)³ while the cubic's fit of the higher terms can dip by round-off), and a
  // guard whose true dip is that shallow merely touches.
  constexpr double kNegligibleDipFraction = 1e-6;
  const double h = t1 - t0;
  // p(s) = a s³ + b s² + c s + d on s ∈ [0, 1], t = t0 + s h.
  const double d = g0.value;
  const double c = h * g0.rate;
  const double b = 3.0 * (g1.value - g0.value) - 2.0 * h * g0.rate - h * g1.rate;
  const double a = 2.0 * (g0.value - g1.value) + h * g0.rate + h * g1.rate;
  std::optional<double> dip;
  const double change =
      std::max({std::abs(g0.value), std::abs(g1.value), h * std::abs(g0.rate), h * std::abs(g1.rate)});
  double lowest = -kNegligibleDipFraction * change;
  // A cheap bound first (most steps of most guards): with Δ = g1 − g0, e0 = h ġ0 − Δ and e1 = h ġ1 − Δ the cubic
  // is p(s) = (1 − s) g0 + s g1 + s (1 − s) ((1 − s) e0 − s e1), and s (1 − s) ≤ 1/4, so p ≥ min(g0, g1) −
  // max(|e0|, |e1|)/4 on [0, 1]. Where that is not negative there is no dip, as the search below would find.
  const double delta = g1.value - g0.value;
  if (std::min(g0.value, g1.value) - 0.25 * std::max(std::abs(h * g0.rate - delta), std::abs(h * g1.rate - delta)) >=
      0.0) {
    return std::nullopt;
  }
  const auto consider = [&](double s) {  // a root of p'(s) = 3a s² + 2b s + c
    if (!(s > 0.0 && s < 1.0) || !(3.0 * a * s + b > 0.0)) return;  // inside, and a minimum (p'' > 0)
    const double p = ((a * s + b) * s + c) * s + d;
    if (p < lowest) {
      lowest = p;
      dip = t0 + s * h;
    }
  };
  if (a == 0.0) {
    if (b != 0.0) consider(-c / (2.0 * b));
  } else {
    const double discriminant = b * b - 3.0 * a * c;
    if (discriminant >= 0.0) {
      const double root = std::sqrt(discriminant);
      consider((-b + root) / (3.0 * a));
      consider((-b - root) / (3.0 * a));
    }
  }
  return dip;
}

// Halvings of the search for a short hop below 1/16 of the interval: 2^-46 of a 10 ms step is ~1e-16 s.
inline constexpr int kHopSearchHalvings = 42;

// For a guard that starts on the surface at t0 and is below it at t_below: the crossing after the first of a few
// early points of [t0, t_below] where g is positive (it rose, then came down), or t0 when it is positive at none
// of them (it never rose measurably: into the ground at once). With a positive starting rate `rate0` the search
// goes on towards t0 by halving.
template <class Eval>
std::optional<double> CrossingAfterItRose(const Eval& eval, double t0, double t_below, const GuardValue& g_below,
                                          double rate0 = 0.0) {
  const auto crossing_from = [&](double t_positive, const GuardValue& g_positive) {
    const std::optional<double> root = PolishCrossing(eval, t_positive, g_positive, t_below, g_below);
    return root ? root : std::optional<double>(t_below);
  };
  for (const double fraction : {0.0625, 0.125, 0.25, 0.5}) {
    const double t_positive = t0 + fraction * (t_below - t0);
    const GuardValue g_positive = eval(t_positive);
    if (g_positive.value > 0.0) return crossing_from(t_positive, g_positive);
  }
  // A guard that left the surface rising (rate0 > 0) rose for certain: its hop may be too short for the
  // fractions above (a vertex lifted at 1e-6 m/s after a chatter's facet impact comes back within 1e-7 s of a
  // 5 ms step). Halving towards t0 finds it; a landing at t0, still rising, would have no solution.
  if (rate0 > 0.0) {
    double fraction = 0.0625;
    for (int k = 0; k < kHopSearchHalvings; ++k) {
      fraction *= 0.5;
      const double t_positive = t0 + fraction * (t_below - t0);
      if (!(t_positive > t0)) break;
      const GuardValue g_positive = eval(t_positive);
      if (g_positive.value > 0.0) return crossing_from(t_positive, g_positive);
    }
  }
  return t0;
}

// The first time in [t0, t1] at which g becomes negative, or empty. `eval(t)` returns g and ġ at any t
// of the step (from the dense output); g0, g1 are the values at the step ends. A guard that starts at
// g(t0) ≤ 0 (a vertex that has just left the ground) counts as crossing only after it has been positive,
// unless it starts moving down, which is a crossing at t0. Crossings are located to round-off (PolishCrossing);
// `time_tol` bounds the location of a maximum or minimum, which only brackets a crossing.
template <class Eval>
std::optional<double> FindFirstDescent(const Eval& eval, double t0, const GuardValue& g0, double t1,
                                       const GuardValue& g1, RootPolisher& polisher, double time_tol) {
  const auto rate = [&eval](double t) { return eval(t).rate; };
  // The extremum needs only a coarse time: g is flat there.
  const double extremum_tol = std::max(time_tol, 1e-6 * (t1 - t0));
  if (g0.value <= 0.0) {
    if (g0.rate < 0.0) return t0;  // moving into the ground at once
    if (g0.rate == 0.0 && g1.value < 0.0) {
      // On the surface and at rest relative to it, below it at the step's end: into the ground at once, unless
      // its acceleration first lifts it and it falls back within the step (a block that uplifts where the
      // table's acceleration barely passes the threshold). A positive value early in the step tells; the
      // crossing then follows the one maximum.
      return CrossingAfterItRose(eval, t0, t1, g1);
    }
    if (g1.value >= 0.0) {
      // It rose and ends above zero: below in between only if it turned twice, down and up again.
      const std::optional<double> t_dip = HermiteDipTime(t0, g0, t1, g1);
      if (!t_dip) return std::nullopt;
      const GuardValue g_dip = eval(*t_dip);
      if (!(g_dip.value < 0.0)) return std::nullopt;
      return CrossingAfterItRose(eval, t0, *t_dip, g_dip, g0.rate);
    }
    // It rose and fell back below within the step: the crossing follows the maximum. Any point where g > 0
    // brackets it with t1 (g rises to its one maximum and falls from there); the secant root of ġ is tried first,
    // the located maximum only if g is not positive there.
    // A hop too short for the secant and the located maximum to see (a tilt of 1e-11 rad for 1e-6 s after a
    // chatter's facet impact) is found by halving from t0, as in the dip case above.
    const auto short_hop = [&] { return CrossingAfterItRose(eval, t0, t1, g1, g0.rate); };
    if (!(g1.rate < 0.0)) return short_hop();
    // A hop within the step (99 of the 155 guard evaluations of the paper's Fig. 14 run went to 14 of them, 7
    // each, by the search below): Newton's method from the step's Hermite landing.
    if (const std::optional<double> landing = LandingAfterHop(eval, t0, g0, t1, g1)) return landing;
    double t_positive = t0 + (t1 - t0) * g0.rate / (g0.rate - g1.rate);
    GuardValue g_positive;
    if (t_positive > t0 && t_positive < t1) g_positive = eval(t_positive);
    if (!(g_positive.value > 0.0)) {
      const std::optional<double> t_max = polisher.Solve(rate, t0, t1, extremum_tol);
      if (!t_max) return short_hop();
      g_positive = eval(*t_max);
      if (!(g_positive.value > 0.0)) return short_hop();
      t_positive = *t_max;
    }
    const std::optional<double> root = PolishCrossing(eval, t_positive, g_positive, t1, g1);
    return root ? root : std::optional<double>(t1);
  }
  if (g1.value < 0.0) {
    const std::optional<double> root = PolishCrossing(eval, t0, g0, t1, g1, HermiteCurvatureBound(t0, g0, t1, g1));
    return root ? root : std::optional<double>(t1);
  }
  if (g0.rate < 0.0 && g1.rate > 0.0) {
    // An interior minimum: a dip below zero and back within the step. The crossing lies between t0 (g > 0) and
    // the first point found below zero (g falls to its minimum and stays negative up to that point).
    const std::optional<double> below = TimeBelowZeroNearMinimum(eval, t0, g0, t1, g1, extremum_tol);
    if (!below) return std::nullopt;
    const std::optional<double> root = PolishCrossing(eval, t0, g0, *below, eval(*below));
    return root ? root : std::optional<double>(*below);
  }
  // No sign of a dip at the ends: below zero in between only if g turned twice within the step.
  const std::optional<double> t_dip = HermiteDipTime(t0, g0, t1, g1);
  if (!t_dip) return std::nullopt;
  const GuardValue g_dip = eval(*t_dip);
  if (!(g_dip.value < 0.0)) return std::nullopt;
  const std::optional<double> root = PolishCrossing(eval, t0, g0, *t_dip, g_dip);
  return root ? root : std::optional<double>(*t_dip);
}

}  // namespace rockfit::core
