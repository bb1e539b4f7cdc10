// The gyro scale projected out of (28) (gyro_scale.hpp): the projected scale is a stationary point of (28) in the
// scale (central differences of TrajectoryError itself) and no worse than the least-squares start or 1, scale 1 is
// recovered from data without a scale error, the least-squares start equals an independent weighted least-squares
// solve, scales are clamped to their bounds, silent axes keep 1, and the objective with the scale fits the truth of
// a scaled recording exactly.
#include "rockfit/fitting/gyro_scale.hpp"

#include <cmath>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "analytic_trial.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {
namespace {

// Nodes of a 1-s window with trapezoid weights and a model ω that moves about every axis (a few rad/s), the
// measured ω = S·ω_s plus white noise of σ [rad/s].
struct Problem {
  ErrorNodes nodes;
  std::vector<Eigen::Vector3d> w_s_B;
};

Problem MakeProblem(const Eigen::Vector3d& scale, double noise_rad_s, std::uint64_t seed = 5) {
  Problem p;
  MeasuredSignal signal;
  std::mt19937_64 rng(seed);
  for (int k = 0; k <= 256; ++k) {
    const double t = k / 256.0;
    signal.t_s.push_back(t);
    const Eigen::Vector3d w_s(0.3 * std::sin(9.0 * t), 2.0 * std::cos(4.0 * t) - 1.0, 0.2 * std::sin(13.0 * t + 1.0));
    p.w_s_B.push_back(w_s);
    Eigen::Vector3d noise;
    for (int a = 0; a < 3; ++a) noise[a] = noise_rad_s * testing::NormalDeviate(rng);
    signal.w_B.push_back(scale.cwiseProduct(w_s) + noise);
  }
  EXPECT_TRUE(BuildErrorNodes(signal, 0.0, 1.0, &p.nodes));
  // The nodes are exactly the samples here (t0 and t_end are sample times), so ω_s at the nodes is w_s_B.
  EXPECT_EQ(p.nodes.size(), p.w_s_B.size());
  return p;
}

// argmin_s Σ w_k (y_k − s·x_k)² by a QR solve of the √w-weighted column: independent of the closed form.
double WeightedLeastSquares(const std::vector<double>& weight, const std::vector<double>& x, const std::vector<double>& y) {
  Eigen::MatrixXd a(static_cast<Eigen::Index>(x.size()), 1);
  Eigen::VectorXd b(static_cast<Eigen::Index>(x.size()));
  for (std::size_t k = 0; k < x.size(); ++k) {
    a(static_cast<Eigen::Index>(k), 0) = std::sqrt(weight[k]) * x[k];
    b[static_cast<Eigen::Index>(k)] = std::sqrt(weight[k]) * y[k];
  }
  return a.colPivHouseholderQr().solve(b)[0];
}

TEST(GyroScale, ProjectedScaleOfANoiselessScaledSignalIsTheScale) {
  const Eigen::Vector3d scale(1.02, 0.98, 1.015);
  const Problem p = MakeProblem(scale, 0.0);
  const Eigen::Vector3d s = ProjectedGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(s[a], scale[a], 1e-12) << "axis " << a;
  EXPECT_EQ(ProjectedGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kOff), Eigen::Vector3d::Ones());
}

TEST(GyroScale, TheLeastSquaresStartEqualsAnIndependentWeightedLeastSquaresSolve) {
  const Problem p = MakeProblem(Eigen::Vector3d(1.03, 0.97, 1.01), 0.05);
  const Eigen::Vector3d s = LeastSquaresGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis);
  std::vector<double> x_all, y_all, w_all;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> x, y;
    for (std::size_t k = 0; k < p.nodes.size(); ++k) {
      x.push_back(p.w_s_B[k][a]);
      y.push_back(p.nodes.w_m_B[k][a]);
      x_all.push_back(p.w_s_B[k][a]);
      y_all.push_back(p.nodes.w_m_B[k][a]);
      w_all.push_back(p.nodes.weight_s[k]);
    }
    EXPECT_NEAR(s[a], WeightedLeastSquares(p.nodes.weight_s, x, y), 1e-12) << "axis " << a;
  }
  const Eigen::Vector3d common = LeastSquaresGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kCommon);
  EXPECT_NEAR(common[0], WeightedLeastSquares(w_all, x_all, y_all), 1e-12);
  EXPECT_EQ(common[0], common[1]);
  EXPECT_EQ(common[0], common[2]);
}

// (28) of the model scaled by S, by TrajectoryError itself (independent of the search's slope).
double ErrorAtScale(const Problem& p, const Eigen::Vector3d& scale) {
  std::vector<Eigen::Vector3d> scaled;
  for (const Eigen::Vector3d& w : p.w_s_B) scaled.push_back(scale.cwiseProduct(w));
  return TrajectoryError(p.nodes, scaled);
}

// d(28)/ds_a at `scale` by central differences [rad/s per unit scale].
double ErrorSlope(const Problem& p, const Eigen::Vector3d& scale, const Eigen::Vector3d& along) {
  // Step: (28)'s round-off (~1e-17 rad/s) over it stays ~1e-11, its third-order error h²·|ε‴| ~1e-12.
  constexpr double kStep = 1e-6;
  return (ErrorAtScale(p, scale + kStep * along) - ErrorAtScale(p, scale - kStep * along)) / (2.0 * kStep);
}

// A recording with heavy-tailed noise (a tenth of the nodes hit by a ringing burst of 0.5 rad/s), where the
// least-squares scale and the minimiser of (28) differ clearly; one in six of the ω_y peaks clipped at the rail.
Problem HeavyTailedProblem(const Eigen::Vector3d& scale, bool clip) {
  Problem p = MakeProblem(scale, 0.02, 11);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (Eigen::Vector3d& w : p.nodes.w_m_B) {
    if (unit(rng) < 0.1) w += Eigen::Vector3d(0.5 * unit(rng), -0.5 * unit(rng), 0.3 * unit(rng));
  }
  if (clip) {
    constexpr double kRail_rad_s = 2.9;  // ω_y of the model reaches 3 · 1.0 at most
    p.nodes.censored_axes.assign(p.nodes.size(), 0);
    for (std::size_t k = 0; k < p.nodes.size(); ++k) {
      if (std::abs(p.nodes.w_m_B[k].y()) < kRail_rad_s) continue;
      p.nodes.w_m_B[k].y() = std::copysign(kRail_rad_s, p.nodes.w_m_B[k].y());
      p.nodes.censored_axes[k] = 1u << 1;
    }
  }
  return p;
}

// The slope of (28) at the projected scale: its curvature there (~‖ω‖²/‖misfit‖ ≈ 10² rad/s) times the search's
// tolerance (1e-12) plus the central difference's round-off (~1e-11 rad/s), with a margin of 100.
constexpr double kStationarySlopeRadS = 1e-8;
// The same for per-axis, whose sweeps stop when no axis moves by more than kPerAxisSweepTolerance.
const double kStationaryPerAxisSlopeRadS = 1e3 * kPerAxisSweepTolerance;

TEST(GyroScale, TheProjectedCommonScaleIsAStationaryPointOfTheErrorAndNoWorseThanTheLeastSquaresScaleOrOne) {
  for (bool clip : {false, true}) {
    const Problem p = HeavyTailedProblem(Eigen::Vector3d::Constant(1.03), clip);
    const Eigen::Vector3d s = ProjectedGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kCommon);
    const Eigen::Vector3d least_squares = LeastSquaresGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kCommon);
    EXPECT_EQ(s[0], s[1]);
    EXPECT_EQ(s[0], s[2]);
    const Eigen::Vector3d ones = Eigen::Vector3d::Ones();
    EXPECT_LT(std::abs(ErrorSlope(p, s, ones)), kStationarySlopeRadS) << "clip " << clip << " s " << s[0];
    // The start is not already the answer: there (28) still slopes clearly.
    EXPECT_GT(std::abs(ErrorSlope(p, least_squares, ones)), 1e3 * kStationarySlopeRadS) << "clip " << clip;
    EXPECT_LT(ErrorAtScale(p, s), ErrorAtScale(p, least_squares));
    EXPECT_LT(ErrorAtScale(p, s), ErrorAtScale(p, ones));
    // (28) is convex in s: a stationary point is its minimum, also against points a little away.
    for (double step : {-1e-4, 1e-4, -1e-2, 1e-2}) EXPECT_LT(ErrorAtScale(p, s), ErrorAtScale(p, (s[0] + step) * ones));
  }
}

TEST(GyroScale, TheProjectedPerAxisScaleIsAStationaryPointOfTheErrorInEveryAxis) {
  for (bool clip : {false, true}) {
    const Problem p = HeavyTailedProblem(Eigen::Vector3d(1.03, 0.97, 1.01), clip);
    const Eigen::Vector3d s = ProjectedGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis);
    for (int a = 0; a < 3; ++a) {
      EXPECT_LT(std::abs(ErrorSlope(p, s, Eigen::Vector3d::Unit(a))), kStationaryPerAxisSlopeRadS)
          << "clip " << clip << " axis " << a;
    }
    EXPECT_LT(ErrorAtScale(p, s), ErrorAtScale(p, LeastSquaresGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis)));
  }
}

TEST(GyroScale, ScaleOneIsRecoveredFromDataWithoutAScaleError) {
  // Noiseless: exactly 1, up to the search's tolerance.
  const Problem exact = MakeProblem(Eigen::Vector3d::Ones(), 0.0);
  for (GyroScaleMode mode : {GyroScaleMode::kCommon, GyroScaleMode::kPerAxis}) {
    const Eigen::Vector3d s = ProjectedGyroScale(exact.nodes, exact.w_s_B, mode);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(s[a], 1.0, kGyroScaleTolerance) << ToString(mode) << " axis " << a;
  }
  // With heavy-tailed noise: 1 within the noise's reach on the scale. The common scale's standard deviation is
  // about σ/(‖ω‖·√n) ≈ 0.05/(1.5·16) ≈ 0.002 here (σ the noise and bursts per axis); 0.01 is five of them.
  constexpr double kNoiseReach = 0.01;
  const Problem noisy = HeavyTailedProblem(Eigen::Vector3d::Ones(), false);
  EXPECT_NEAR(ProjectedGyroScale(noisy.nodes, noisy.w_s_B, GyroScaleMode::kCommon)[0], 1.0, kNoiseReach);
}

TEST(GyroScale, ScalesBeyondTheLargestScaleErrorAreClampedToTheBound) {
  const Problem p = MakeProblem(Eigen::Vector3d(1.5, 0.5, 1.0), 0.0);
  const Eigen::Vector3d s = ProjectedGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis);
  EXPECT_EQ(s[0], 1.0 + kMaxGyroScaleError);
  EXPECT_EQ(s[1], 1.0 - kMaxGyroScaleError);
  EXPECT_NEAR(s[2], 1.0, 1e-12);
}

// A reading at the gyro's rail bounds ω and does not measure S·ω: with the peaks of ω_y clipped (censored) the
// scale is the scale of the noiseless recording, where (28) vanishes (the scaled model is beyond the rail at the
// clipped readings, which the censored misfit allows); the least-squares start, taking the clipped values as
// measurements, would be pulled down.
TEST(GyroScale, ReadingsCensoredAtTheRailDoNotEnterTheScale) {
  const Eigen::Vector3d scale(1.02, 0.98, 1.015);
  Problem p = MakeProblem(scale, 0.0);
  constexpr double kRail_rad_s = 0.8;
  p.nodes.censored_axes.assign(p.nodes.size(), 0);
  std::size_t clipped = 0;
  for (std::size_t k = 0; k < p.nodes.size(); ++k) {
    if (std::abs(p.nodes.w_m_B[k].y()) < kRail_rad_s) continue;
    p.nodes.w_m_B[k].y() = std::copysign(kRail_rad_s, p.nodes.w_m_B[k].y());
    p.nodes.censored_axes[k] = 1u << 1;
    ++clipped;
  }
  ASSERT_GT(clipped, 10u);
  const Eigen::Vector3d per_axis = ProjectedGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(per_axis[a], scale[a], 1e-12) << "axis " << a;
  p.nodes.censored_axes.assign(p.nodes.size(), 0);  // the same clipped values taken as measurements
  EXPECT_LT(LeastSquaresGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis)[1], scale[1] - 0.01);
}

TEST(GyroScale, AnAxisWithoutModelMotionKeepsTheScaleOne) {
  Problem p = MakeProblem(Eigen::Vector3d(1.02, 0.98, 1.015), 0.05);
  for (Eigen::Vector3d& w : p.w_s_B) w.z() = 0.0;
  const Eigen::Vector3d s = ProjectedGyroScale(p.nodes, p.w_s_B, GyroScaleMode::kPerAxis);
  EXPECT_EQ(s[2], 1.0);
  EXPECT_NE(s[1], 1.0);
}

TEST(GyroScale, TheObjectiveFitsTheTruthOfAScaledRecordingExactlyWithTheScaleProjectedOut) {
  // A noiseless recording of the analytic model, every axis off by 1–2 %: at the truth, (28) of the unscaled
  // model is the scale error's share of |ω|; with the scale projected out it vanishes and the scale is recovered on
  // the axes the model turns about.
  testing::AnalyticTrial trial = testing::MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Eigen::Vector3d scale(1.02, 0.985, 0.99);
  for (Eigen::Vector3d& w : trial.data.signal.w_B) w = scale.cwiseProduct(w);
  const Objective plain = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  const Objective scaled = plain.WithGyroScale(GyroScaleMode::kPerAxis);
  const Evaluation off = plain.Evaluate(trial.truth);
  const Evaluation on = scaled.Evaluate(trial.truth);
  ASSERT_TRUE(off.feasible && on.feasible);
  EXPECT_GT(off.epsilon_rad_s, 1e-3);
  // Round-off of the model and the sums only (the analytic model is exact to ~1e-12 rad/s).
  constexpr double kExactRadS = 1e-9;
  EXPECT_LT(on.epsilon_rad_s, kExactRadS);
  EXPECT_NEAR(on.gyro_scale.x(), scale.x(), 1e-9);
  EXPECT_NEAR(on.gyro_scale.y(), scale.y(), 1e-9);
  // The analytic model does not turn about z (ω_z ≡ 0, as the exact ε shows): that axis keeps the scale 1.
  EXPECT_EQ(on.gyro_scale.z(), 1.0);
  EXPECT_EQ(off.gyro_scale, Eigen::Vector3d::Ones());
  EXPECT_EQ(scaled.options().gyro_scale, GyroScaleMode::kPerAxis);
  EXPECT_EQ(plain.options().gyro_scale, GyroScaleMode::kOff);
}

TEST(GyroScale, ModesRoundTripTheirNamesAndBadNamesAreRefused) {
  for (GyroScaleMode m : {GyroScaleMode::kOff, GyroScaleMode::kCommon, GyroScaleMode::kPerAxis}) {
    EXPECT_EQ(ParseGyroScaleMode(ToString(m)), m);
  }
  EXPECT_THROW(ParseGyroScaleMode("peraxis"), InvalidArgument);
  FitOptions options;
  options.gyro_scale = GyroScaleMode::kPerAxis;
  // With the exact Jacobian asked for too: the fit then differences (fitter_test.cpp).
  options.ceres.exact_jacobian = true;
  EXPECT_NO_THROW(options.Validate());
}

}  // namespace
}  // namespace rockfit::fitting
