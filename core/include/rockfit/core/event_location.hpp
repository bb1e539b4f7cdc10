// Event location on one integrator step (docs/design.md §4): a guard function g(t) (a vertex height, the margin of
// the COM over its support, a tilt) must not go below zero unnoticed, not even when it dips below and comes
// back within the step. Steps are short against the rocking time scale, so g has at most one extremum per
// step; the sign of ġ at the two step ends tells whether an interior minimum exists, and that minimum is
// located on the dense output. Roots are polished with GSL's Brent solver.
#pragma once

#include <algorithm>
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

// The first time in [t0, t1] at which g becomes negative, or empty. `eval(t)` returns g and ġ at any t
// of the step (from the dense output); g0, g1 are the values at the step ends. A guard that starts at
// g(t0) ≤ 0 (a vertex that has just left the ground) counts as crossing only after it has been positive,
// unless it starts moving down, which is a crossing at t0. Roots are located to `time_tol`.
template <class Eval>
std::optional<double> FindFirstDescent(const Eval& eval, double t0, const GuardValue& g0, double t1,
                                       const GuardValue& g1, RootPolisher& polisher, double time_tol) {
  const auto value = [&eval](double t) { return eval(t).value; };
  const auto rate = [&eval](double t) { return eval(t).rate; };
  // The extremum needs only a coarse time: g is flat there.
  const double extremum_tol = std::max(time_tol, 1e-6 * (t1 - t0));
  if (g0.value <= 0.0) {
    if (g0.rate < 0.0 || (g0.rate == 0.0 && g1.value < 0.0)) return t0;  // moving into the ground at once
    if (g1.value >= 0.0) return std::nullopt;
    // It rose and fell back below within the step: the crossing follows the maximum.
    if (!(g1.rate < 0.0)) return t0;
    const std::optional<double> t_max = polisher.Solve(rate, t0, t1, extremum_tol);
    if (!t_max) return t0;
    if (!(value(*t_max) > 0.0)) return t0;
    const std::optional<double> root = polisher.Solve(value, *t_max, t1, time_tol);
    return root ? root : std::optional<double>(t1);
  }
  if (g1.value < 0.0) {
    const std::optional<double> root = polisher.Solve(value, t0, t1, time_tol);
    return root ? root : std::optional<double>(t1);
  }
  if (g0.rate < 0.0 && g1.rate > 0.0) {
    // An interior minimum: a dip below zero and back within the step.
    const std::optional<double> t_min = polisher.Solve(rate, t0, t1, extremum_tol);
    if (!t_min || !(value(*t_min) < 0.0)) return std::nullopt;
    const std::optional<double> root = polisher.Solve(value, t0, *t_min, time_tol);
    return root ? root : std::optional<double>(*t_min);
  }
  return std::nullopt;
}

}  // namespace rockfit::core
