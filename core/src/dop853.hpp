// An embedded explicit Runge–Kutta integrator of order 8 with error estimators of orders 5 and 3 and a
// 7th-order continuous extension (Dormand–Prince "DOP853", Hairer, Nørsett & Wanner, Solving ODE I,
// 2nd ed., Sect. II.10). The state dimension is a template parameter, so one step allocates nothing.
//
// Use: Reset() at a state, then Step() repeatedly; after each accepted step [t_previous(), t()],
// PrepareDense() followed by Interpolate() gives the solution anywhere inside the step (7th order).
// Between steps, mutable_y() lets the caller project the state (e.g. renormalise a quaternion).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "detail/dop853_tableau.hpp"

namespace rockfit::core {

struct Dop853Options {
  double rel_tol = 1e-12;  // local error per step ≤ abs_tol + rel_tol·|y| (component-wise, RMS norm)
  double abs_tol = 1e-14;
  double max_step = std::numeric_limits<double>::infinity();  // largest step [time units]
  // Throws InvalidArgument naming the bad field.
  void Validate() const;
};

enum class StepStatus {
  kOk,
  kStepTooSmall,  // the step size fell below round-off of t (stiff, singular or non-finite right-hand side)
};

template <int N>
class Dop853 {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;

  explicit Dop853(const Dop853Options& options) : options_(options) {}

  // Starts a new trajectory at (t, y). `step_hint` > 0 is used as the first step size; otherwise the first
  // step is estimated from the derivatives (Hairer's starting-step algorithm). `rhs(t, y, dydt)` must be
  // callable as void(double, const Vector&, Vector&).
  template <class Rhs>
  void Reset(const Rhs& rhs, double t, const Vector& y, double step_hint = 0.0);

  // Takes one accepted step, never beyond `t_limit` (> t()). On kStepTooSmall the state is unchanged.
  template <class Rhs>
  StepStatus Step(const Rhs& rhs, double t_limit);

  // Computes the continuous extension of the last accepted step (three more evaluations of rhs, done once
  // per step however often it is called).
  template <class Rhs>
  void PrepareDense(const Rhs& rhs);

  // The continuous extension at t ∈ [t_previous(), t()]; requires PrepareDense() after the last Step().
  void Interpolate(double t, Vector* y) const;
  // Components [First, First + Count) of Interpolate(t) alone, bit for bit (an output sample that needs only some
  // of the state, such as ω without the attitude).
  template <int First, int Count>
  void InterpolateComponents(double t, Eigen::Matrix<double, Count, 1>* y) const;

  double t() const { return t_; }
  const Vector& y() const { return y_; }
  const Vector& dydt() const { return k_[0]; }  // f(t, y) at the end of the last step
  double t_previous() const { return t_previous_; }
  const Vector& y_previous() const { return y_previous_; }
  // Writable state for a projection between steps; dydt() is kept (the caller keeps the change tiny).
  Vector& mutable_y() { return y_; }
  double suggested_step() const { return h_next_; }
  long num_evaluations() const { return num_evaluations_; }
  long num_accepted() const { return num_accepted_; }
  long num_rejected() const { return num_rejected_; }

 private:
  template <class Rhs>
  void Evaluate(const Rhs& rhs, double t, const Vector& y, Vector& dydt) {
    rhs(t, y, dydt);
    ++num_evaluations_;
  }
  double ScaledRms(const Vector& v, const Vector& y_a, const Vector& y_b) const;
  // The mean squares of a/scale and b/scale, scale = abs_tol + rel_tol·max(|y_a|, |y_b|) per component.
  void ScaledMeanSquares(const Vector& a, const Vector& b, const Vector& y_a, const Vector& y_b, double* mean_a,
                         double* mean_b) const;
  // x^(1/8) for x ≥ 0, the step-size controller's exponent for an 8th-order method: three square roots
  // (correctly rounded each) instead of std::pow, the same value to a few units of round-off and cheaper.
  static double EighthRoot(double x) { return std::sqrt(std::sqrt(std::sqrt(x))); }
  // Component i of the continuous extension at θ = (t − t_previous)/h (Horner form, detail/dop853_tableau.hpp).
  double DenseComponent(int i, double theta, double theta1) const {
    const double inner = dense_[4][i] + theta * (dense_[5][i] + theta1 * (dense_[6][i] + theta * dense_[7][i]));
    return dense_[0][i] + theta * (dense_[1][i] + theta1 * (dense_[2][i] + theta * (dense_[3][i] + theta1 * inner)));
  }
  // *out = base + h·Σ_{j<count} weights[j]·k_j.
  template <std::size_t M>
  void Combine(const std::array<double, M>& weights, int count, double h, const Vector& base, Vector* out) const {
    if constexpr (N >= kStageOuterMinStates) {
      // Stage-outer loops: the same sums in the same order per component, but the components side by side,
      // which the compiler vectorises (the stage-inner form strides through k_ and does not).
      // A third of DOP853's coefficients are zero (stages 2–5 enter few later sums): they are skipped.
      std::array<double, N> sum{};
      for (int j = 0; j < count; ++j) {
        const double w = weights[j];
        if (w == 0.0) continue;
        for (int i = 0; i < N; ++i) sum[i] += w * k_[j][i];
      }
      for (int i = 0; i < N; ++i) (*out)[i] = base[i] + h * sum[i];
    } else {
      for (int i = 0; i < N; ++i) {
        double sum = 0.0;
        for (int j = 0; j < count; ++j) sum += weights[j] * k_[j][i];
        (*out)[i] = base[i] + h * sum;
      }
    }
  }
  // From this many states on, the stage-outer loops are faster (7 states: 6 % a Fig. 14 run); with 2 they are
  // 15 % slower (loop overhead).
  static constexpr int kStageOuterMinStates = 4;

  static constexpr double kSafety = 0.9;        // step-size controller safety factor
  static constexpr double kMinFactor = 0.333;   // smallest step change per step
  static constexpr double kMaxFactor = 6.0;     // largest step growth per step

  Dop853Options options_;
  double t_ = 0.0;
  double t_previous_ = 0.0;
  double h_ = 0.0;       // size of the last accepted step
  double h_next_ = 0.0;  // proposed size of the next step
  double inverse_h_ = 0.0;  // 1/h_ of the step whose dense output is ready (0 for a step of size 0)
  Vector y_ = Vector::Zero();
  Vector y_previous_ = Vector::Zero();
  // k_[j] holds stage j+1 of the current step; k_[12] = f(t+h, y1). After acceptance the new f(t, y) is
  // kept in f_end_ and moved to k_[0] when the next step starts (the step's own stages stay intact for
  // the dense output until then).
  std::array<Vector, detail::dop853::kDenseStages> k_{};
  Vector f_end_ = Vector::Zero();
  std::array<Vector, 8> dense_{};
  Vector work_ = Vector::Zero();
  bool dense_ready_ = false;
  bool stages_current_ = false;  // k_[0] is f(t_, y_) of the current state
  long num_evaluations_ = 0;
  long num_accepted_ = 0;
  long num_rejected_ = 0;
};

// ---------------------------------------------------------------- implementation

template <int N>
double Dop853<N>::ScaledRms(const Vector& v, const Vector& y_a, const Vector& y_b) const {
  double sum = 0.0;
  for (int i = 0; i < N; ++i) {
    const double scale = options_.abs_tol + options_.rel_tol * std::max(std::abs(y_a[i]), std::abs(y_b[i]));
    const double ratio = v[i] / scale;
    sum += ratio * ratio;
  }
  return std::sqrt(sum / N);
}

template <int N>
void Dop853<N>::ScaledMeanSquares(const Vector& a, const Vector& b, const Vector& y_a, const Vector& y_b,
                                  double* mean_a, double* mean_b) const {
  double sum_a = 0.0;
  double sum_b = 0.0;
  for (int i = 0; i < N; ++i) {
    const double inverse_scale =
        1.0 / (options_.abs_tol + options_.rel_tol * std::max(std::abs(y_a[i]), std::abs(y_b[i])));
    const double ratio_a = a[i] * inverse_scale;
    const double ratio_b = b[i] * inverse_scale;
    sum_a += ratio_a * ratio_a;
    sum_b += ratio_b * ratio_b;
  }
  *mean_a = sum_a / N;
  *mean_b = sum_b / N;
}

template <int N>
template <class Rhs>
void Dop853<N>::Reset(const Rhs& rhs, double t, const Vector& y, double step_hint) {
  t_ = t;
  t_previous_ = t;
  y_ = y;
  y_previous_ = y;
  dense_ready_ = false;
  Evaluate(rhs, t_, y_, k_[0]);
  f_end_ = k_[0];
  stages_current_ = true;
  if (step_hint > 0.0 && std::isfinite(step_hint)) {
    h_next_ = std::min(step_hint, options_.max_step);
    return;
  }
  // Starting step (Hairer, Nørsett & Wanner, Sect. II.4): a step of size h0 from the derivative norms,
  // refined with the second derivative estimated from one explicit Euler step.
  const double norm_y = ScaledRms(y_, y_, y_);
  const double norm_f = ScaledRms(k_[0], y_, y_);
  double h0 = (norm_y < 1e-5 || norm_f < 1e-5) ? 1e-6 : 0.01 * norm_y / norm_f;
  h0 = std::min(h0, options_.max_step);
  work_ = y_ + h0 * k_[0];
  Evaluate(rhs, t_ + h0, work_, k_[1]);
  const double norm_second = ScaledRms(k_[1] - k_[0], y_, y_) / h0;
  const double larger = std::max(norm_second, norm_f);
  const double h1 = larger <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : EighthRoot(0.01 / larger);
  h_next_ = std::min({100.0 * h0, h1, options_.max_step});
}

template <int N>
template <class Rhs>
StepStatus Dop853<N>::Step(const Rhs& rhs, double t_limit) {
  namespace tab = detail::dop853;
  if (!stages_current_) {
    k_[0] = f_end_;
    stages_current_ = true;
  }
  bool rejected_before = false;
  for (;;) {
    const double remaining = t_limit - t_;
    // Round-off floor of the time variable: steps below it cannot advance t.
    const double h_min = 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_));
    double h = std::min({h_next_, options_.max_step, remaining});
    if (!(h > h_min) && remaining > h_min) return StepStatus::kStepTooSmall;
    if (!(remaining > 0.0)) return StepStatus::kStepTooSmall;
    if (remaining - h < h_min) h = remaining;  // land exactly on t_limit instead of leaving a sliver

    // Plain loops over the components: as fast as Eigen's expressions when optimised, and far faster in
    // unoptimised (debug, sanitizer) builds.
    for (int s = 1; s < tab::kStages; ++s) {
      Combine(tab::kA[s], s, h, y_, &work_);
      Evaluate(rhs, t_ + tab::kC[s] * h, work_, k_[s]);
    }
    Vector y_new;
    Combine(tab::kB, tab::kStages, h, y_, &y_new);
    Vector err5 = Vector::Zero();
    Vector err3 = Vector::Zero();
    if constexpr (N >= kStageOuterMinStates) {
      for (int j = 0; j < tab::kStages; ++j) {
        const double w5 = tab::kE5[j], w3 = tab::kB[j] - tab::kBhh[j];
        if (w5 == 0.0 && w3 == 0.0) continue;
        for (int i = 0; i < N; ++i) {
          err5[i] += w5 * k_[j][i];
          err3[i] += w3 * k_[j][i];
        }
      }
    } else {
      for (int i = 0; i < N; ++i) {
        double sum5 = 0.0;
        double sum3 = 0.0;
        for (int j = 0; j < tab::kStages; ++j) {
          sum5 += tab::kE5[j] * k_[j][i];
          sum3 += (tab::kB[j] - tab::kBhh[j]) * k_[j][i];
        }
        err5[i] = sum5;
        err3[i] = sum3;
      }
    }
    // Combined error estimate of DOP853: h·|err5|² / sqrt(|err5|² + 0.01·|err3|²), RMS-scaled. Both mean
    // squares in one pass over the components (one scale each), without the square roots of the norms.
    double e5_squared = 0.0;
    double e3_squared = 0.0;
    ScaledMeanSquares(err5, err3, y_, y_new, &e5_squared, &e3_squared);
    const double denominator = e5_squared + 0.01 * e3_squared;
    double err = denominator > 0.0 ? h * e5_squared / std::sqrt(denominator) : 0.0;
    bool finite = std::isfinite(err) && y_new.allFinite();
    if (finite && err <= 1.0) {
      Evaluate(rhs, t_ + h, y_new, k_[12]);
      finite = k_[12].allFinite();
    }
    if (!finite) {
      h_next_ = 0.2 * h;
      ++num_rejected_;
      rejected_before = true;
      continue;
    }
    if (err <= 1.0) {
      double factor = err > 0.0 ? kSafety / EighthRoot(err) : kMaxFactor;
      factor = std::clamp(factor, kMinFactor, kMaxFactor);
      if (rejected_before) factor = std::min(factor, 1.0);
      t_previous_ = t_;
      y_previous_ = y_;
      t_ = (h == remaining) ? t_limit : t_ + h;
      h_ = t_ - t_previous_;
      y_ = y_new;
      f_end_ = k_[12];
      h_next_ = h * factor;
      dense_ready_ = false;
      stages_current_ = false;
      ++num_accepted_;
      return StepStatus::kOk;
    }
    h_next_ = h * std::max(kMinFactor, kSafety / EighthRoot(err));
    ++num_rejected_;
    rejected_before = true;
  }
}

template <int N>
template <class Rhs>
void Dop853<N>::PrepareDense(const Rhs& rhs) {
  namespace tab = detail::dop853;
  if (dense_ready_) return;
  const double h = h_;
  for (int s = 13; s < tab::kDenseStages; ++s) {
    Combine(tab::kA[s], s, h, y_previous_, &work_);
    Evaluate(rhs, t_previous_ + tab::kC[s] * h, work_, k_[s]);
  }
  for (int i = 0; i < N; ++i) {
    const double r2 = y_[i] - y_previous_[i];
    const double r3 = h * k_[0][i] - r2;
    dense_[0][i] = y_previous_[i];
    dense_[1][i] = r2;
    dense_[2][i] = r3;
    dense_[3][i] = r2 - h * k_[12][i] - r3;
    if constexpr (N < kStageOuterMinStates) {
      for (int d = 0; d < 4; ++d) {
        double sum = 0.0;
        for (int j = 0; j < tab::kDenseStages; ++j) sum += tab::kD[d][j] * k_[j][i];
        dense_[4 + d][i] = h * sum;
      }
    }
  }
  if constexpr (N >= kStageOuterMinStates) {
    for (int d = 0; d < 4; ++d) {
      std::array<double, N> sum{};  // stage-outer, as in Combine
      for (int j = 0; j < tab::kDenseStages; ++j) {
        const double w = tab::kD[d][j];
        if (w == 0.0) continue;
        for (int i = 0; i < N; ++i) sum[i] += w * k_[j][i];
      }
      for (int i = 0; i < N; ++i) dense_[4 + d][i] = h * sum[i];
    }
  }
  inverse_h_ = h > 0.0 ? 1.0 / h : 0.0;
  dense_ready_ = true;
}

template <int N>
void Dop853<N>::Interpolate(double t, Vector* y) const {
  const double theta = (t - t_previous_) * inverse_h_;  // by the reciprocal: one division a step, not a call
  const double theta1 = 1.0 - theta;
  for (int i = 0; i < N; ++i) (*y)[i] = DenseComponent(i, theta, theta1);
}

template <int N>
template <int First, int Count>
void Dop853<N>::InterpolateComponents(double t, Eigen::Matrix<double, Count, 1>* y) const {
  static_assert(First >= 0 && Count > 0 && First + Count <= N, "components outside the state");
  const double theta = (t - t_previous_) * inverse_h_;
  const double theta1 = 1.0 - theta;
  for (int i = 0; i < Count; ++i) (*y)[i] = DenseComponent(First + i, theta, theta1);
}

}  // namespace rockfit::core
