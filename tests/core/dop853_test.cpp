// The DOP853 integrator: its tableau satisfies the order conditions, the solution and the continuous
// extension converge at their orders, and the error control meets the requested tolerance.
#include "dop853.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

namespace tab = detail::dop853;

// Exact rational arithmetic is not needed: the coefficients carry 30 digits, so each condition holds to
// a few ulps of the largest term (the weights reach |b| ≈ 6, the dense weights ≈ 500).
constexpr double kOrderConditionTol = 1e-13;

TEST(Dop853Tableau, RowSumsEqualTheNodes) {
  for (int s = 0; s < tab::kDenseStages; ++s) {
    double sum = 0.0;
    for (int j = 0; j < s; ++j) sum += tab::kA[s][j];
    EXPECT_NEAR(sum, tab::kC[s], kOrderConditionTol) << "stage " << s + 1;
  }
}

TEST(Dop853Tableau, WeightsSatisfyTheQuadratureConditionsUpToOrderEight) {
  // Σ b_i c_i^k = 1/(k+1) for k = 0..7 (the bushy-tree conditions of an 8th-order method).
  for (int k = 0; k <= 7; ++k) {
    double sum = 0.0;
    for (int i = 0; i < tab::kStages; ++i) sum += tab::kB[i] * std::pow(tab::kC[i], k);
    EXPECT_NEAR(sum, 1.0 / (k + 1), kOrderConditionTol) << "k = " << k;
  }
}

TEST(Dop853Tableau, ErrorEstimatorsVanishOnPolynomialsTheyIntegrateExactly) {
  // Both estimators are differences of two quadratures that are exact for low degrees.
  for (int k = 0; k <= 2; ++k) {
    double e5 = 0.0;
    double e3 = 0.0;
    for (int i = 0; i < tab::kStages; ++i) {
      e5 += tab::kE5[i] * std::pow(tab::kC[i], k);
      e3 += (tab::kB[i] - tab::kBhh[i]) * std::pow(tab::kC[i], k);
    }
    EXPECT_NEAR(e5, 0.0, kOrderConditionTol) << "k = " << k;
    EXPECT_NEAR(e3, 0.0, kOrderConditionTol) << "k = " << k;
  }
}

// y'' = −y written as a first-order system; exact solution (cos t, −sin t) from (1, 0).
struct Oscillator {
  void operator()(double, const Eigen::Vector2d& y, Eigen::Vector2d& dydt) const {
    dydt[0] = y[1];
    dydt[1] = -y[0];
  }
};

// Integrates with fixed steps (error control disabled by a huge tolerance) and returns the error at t_end.
double FixedStepError(double h, double t_end) {
  Dop853Options options;
  options.rel_tol = 0.5;
  options.abs_tol = 1e6;
  options.max_step = h;
  Dop853<2> integrator(options);
  integrator.Reset(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0), h);
  while (integrator.t() < t_end) {
    EXPECT_EQ(integrator.Step(Oscillator{}, t_end), StepStatus::kOk);
  }
  return (integrator.y() - Eigen::Vector2d(std::cos(t_end), -std::sin(t_end))).norm();
}

TEST(Dop853, GlobalErrorConvergesAtOrderEight) {
  const double e1 = FixedStepError(0.4, 8.0);
  const double e2 = FixedStepError(0.2, 8.0);
  const double order = std::log2(e1 / e2);
  EXPECT_GT(order, 7.6);
  EXPECT_LT(order, 8.6);
}

TEST(Dop853, ContinuousExtensionConvergesAtOrderSeven) {
  // Local error of the interpolant at an interior point of a single step from the exact state.
  const auto interpolation_error = [](double h) {
    Dop853Options options;
    options.rel_tol = 0.5;
    options.abs_tol = 1e6;
    Dop853<2> integrator(options);
    integrator.Reset(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0), h);
    EXPECT_EQ(integrator.Step(Oscillator{}, h), StepStatus::kOk);
    integrator.PrepareDense(Oscillator{});
    double worst = 0.0;
    for (double theta : {0.13, 0.5, 0.77}) {
      Eigen::Vector2d y;
      integrator.Interpolate(theta * h, &y);
      worst = std::max(worst, (y - Eigen::Vector2d(std::cos(theta * h), -std::sin(theta * h))).norm());
    }
    return worst;
  };
  const double e1 = interpolation_error(0.8);
  const double e2 = interpolation_error(0.4);
  // A local error of order 7 scales as h^8.
  const double order = std::log2(e1 / e2);
  EXPECT_GT(order, 7.5);
  EXPECT_LT(order, 9.0);
}

TEST(Dop853, ContinuousExtensionMatchesTheStepEnds) {
  Dop853<2> integrator(Dop853Options{});
  integrator.Reset(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0));
  ASSERT_EQ(integrator.Step(Oscillator{}, 10.0), StepStatus::kOk);
  integrator.PrepareDense(Oscillator{});
  Eigen::Vector2d y;
  integrator.Interpolate(integrator.t_previous(), &y);
  EXPECT_EQ(y, integrator.y_previous());
  integrator.Interpolate(integrator.t(), &y);
  EXPECT_NEAR((y - integrator.y()).norm(), 0.0, 1e-15);
}

// A linear system of 7 states (the size of vertex rocking, whose stage sums run stage by stage): y' = A y with a
// rotation in (y0, y1), a decay in y2 and couplings among y3..y6.
struct SevenStates {
  void operator()(double, const Eigen::Matrix<double, 7, 1>& y, Eigen::Matrix<double, 7, 1>& dydt) const {
    dydt << y[1], -y[0], -0.3 * y[2], y[4] - 0.1 * y[3], -y[3] + 0.2 * y[6], 0.5 * y[0] - y[5], -0.7 * y[4];
  }
};

TEST(Dop853, ComponentInterpolationGivesTheBitsOfTheWholeState) {
  using Vector7 = Eigen::Matrix<double, 7, 1>;
  Dop853<7> integrator(Dop853Options{});
  Vector7 y0;
  y0 << 1.0, 0.0, 2.0, 0.3, -0.4, 0.5, -0.6;
  integrator.Reset(SevenStates{}, 0.0, y0);
  int checked = 0;
  while (integrator.t() < 5.0) {
    ASSERT_EQ(integrator.Step(SevenStates{}, 5.0), StepStatus::kOk);
    integrator.PrepareDense(SevenStates{});
    for (double theta : {0.0, 0.21, 0.5, 0.93, 1.0}) {
      const double t = integrator.t_previous() + theta * (integrator.t() - integrator.t_previous());
      Vector7 all;
      integrator.Interpolate(t, &all);
      Eigen::Vector3d tail;
      integrator.InterpolateComponents<4, 3>(t, &tail);
      Eigen::Matrix<double, 2, 1> head;
      integrator.InterpolateComponents<0, 2>(t, &head);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(tail[i], all[4 + i]) << t;
      for (int i = 0; i < 2; ++i) EXPECT_EQ(head[i], all[i]) << t;
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);
}

TEST(Dop853, AdaptiveStepsMeetTheRequestedTolerance) {
  for (double rel_tol : {1e-6, 1e-9, 1e-12}) {
    Dop853Options options;
    options.rel_tol = rel_tol;
    options.abs_tol = rel_tol;
    Dop853<2> integrator(options);
    integrator.Reset(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0));
    const double t_end = 2.0 * M_PI;
    while (integrator.t() < t_end) ASSERT_EQ(integrator.Step(Oscillator{}, t_end), StepStatus::kOk);
    EXPECT_DOUBLE_EQ(integrator.t(), t_end);  // the last step lands on the limit
    const double error = (integrator.y() - Eigen::Vector2d(1.0, 0.0)).norm();
    // The global error after one period stays within a small multiple of the local tolerance.
    EXPECT_LT(error, 100.0 * rel_tol) << "rel_tol " << rel_tol;
  }
}

TEST(Dop853, MaxStepBoundsEveryStep) {
  Dop853Options options;
  options.max_step = 0.01;
  Dop853<2> integrator(options);
  integrator.Reset(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0));
  while (integrator.t() < 1.0) {
    ASSERT_EQ(integrator.Step(Oscillator{}, 1.0), StepStatus::kOk);
    EXPECT_LE(integrator.t() - integrator.t_previous(), 0.01 * (1.0 + 1e-12));
  }
}

// y' = y² from y(0) = 1 blows up at t = 1: the integrator must stop with a status, not loop or return NaN.
struct BlowUp {
  void operator()(double, const Eigen::Matrix<double, 1, 1>& y, Eigen::Matrix<double, 1, 1>& dydt) const {
    dydt[0] = y[0] * y[0];
  }
};

TEST(Dop853, BlowUpEndsWithStepTooSmall) {
  Dop853<1> integrator(Dop853Options{});
  integrator.Reset(BlowUp{}, 0.0, Eigen::Matrix<double, 1, 1>(1.0));
  StepStatus status = StepStatus::kOk;
  int steps = 0;
  while (status == StepStatus::kOk && integrator.t() < 2.0 && steps < 100000) {
    status = integrator.Step(BlowUp{}, 2.0);
    ++steps;
  }
  EXPECT_EQ(status, StepStatus::kStepTooSmall);
  EXPECT_LT(integrator.t(), 1.0 + 1e-9);  // stops at the singularity (to the accuracy of the solution)
  EXPECT_TRUE(integrator.y().allFinite());
}

TEST(Dop853Options, RejectsNonsense) {
  Dop853Options options;
  options.rel_tol = 0.0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options = Dop853Options{};
  options.abs_tol = -1.0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  options = Dop853Options{};
  options.max_step = 0.0;
  EXPECT_THROW(options.Validate(), InvalidArgument);
  EXPECT_NO_THROW(Dop853Options{}.Validate());
}

}  // namespace
}  // namespace rockfit::core
