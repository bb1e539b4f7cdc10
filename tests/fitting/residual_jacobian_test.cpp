// The exact Jacobian of the residuals of (28) against central differences of the residuals themselves (simulator
// model, planar and 3D runs, random points with a fixed seed), and the Ceres back end with it.
#include "rockfit/fitting/residual_jacobian.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/simulator_model.hpp"
#include "simulation_cases.hpp"

namespace rockfit::fitting {
namespace {

// Agreement of each Jacobian column with central differences, relative to the column's largest entry: exact to
// the 1e-12 integration tolerance against differences good to ~1e-8 with the steps below.
constexpr double kRelativeAgreement = 1e-6;
constexpr double kRate_hz = 256.0;
constexpr double kRecording_s = 1.6;
constexpr double kTrueT0_s = 0.3;
constexpr double kWindowEnd_s = 1.3;
// Gyro-like noise on the synthetic recording, so that residuals (and the t0 terms that scale them) are not zero.
constexpr double kNoise_rad_s = 0.01;

std::shared_ptr<const SimulatorModel> Model() {
  return std::make_shared<const SimulatorModel>(testing::Fig14Block());
}

// A planar release at t0 = 0.3 s recorded at 256 Hz (fixed-seed noise).
MeasuredSignal PlanarRecording(double alpha_rad, double lambda_lon, unsigned seed, double noise_rad_s = kNoise_rad_s) {
  MeasuredSignal signal;
  const int n = static_cast<int>(kRecording_s * kRate_hz);
  std::vector<double> after_release;
  for (int k = 0; k <= n; ++k) {
    signal.t_s.push_back(k / kRate_hz);
    after_release.push_back(std::max(0.0, k / kRate_hz - kTrueT0_s));
  }
  core::ModelParameters p;
  p.alpha_rad = alpha_rad;
  p.lambda_lon = lambda_lon;
  p.lambda_lat = 0.0;
  ModelOutput out;
  Model()->Evaluate(p, after_release, &out);
  EXPECT_TRUE(out.ok()) << out.failure_detail;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_rad_s);
  for (const Eigen::Vector3d& w : out.w_B) signal.w_B.push_back(w + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  return signal;
}

// t0, α, λ and λ_lon free; λ_lat fixed at 0 (a planar fit), τ_edge fixed.
Objective PlanarObjective(const MeasuredSignal& signal) {
  ParameterSet p = ParameterSet::Defaults();
  p[ParameterId::kT0] = {kTrueT0_s, kTrueT0_s - 0.05, kTrueT0_s + 0.05, false};
  p[ParameterId::kAlpha].value = 0.15;
  p[ParameterId::kLambda].value = 1.0;
  p[ParameterId::kLambdaLat].value = 0.0;
  p[ParameterId::kLambdaLat].fixed = true;
  p[ParameterId::kLambdaLon].value = 0.6;
  return Objective(signal, kWindowEnd_s, Model(), p);
}

struct Residuals {
  std::vector<NodeResidual> nodes;
  ResidualJacobianSummary summary;
  std::vector<double> node_times_s;
  std::vector<double> event_times_s;
  std::size_t first_sample = 0;
};

Residuals At(const Objective& objective, const Eigen::VectorXd& x, const ResidualScale& scale) {
  Residuals r;
  ErrorNodes nodes;
  ModelOutput output;
  const Evaluation e = objective.EvaluateDetailed(objective.WithFree(x), &nodes, &output, true);
  EXPECT_TRUE(e.feasible) << e.failure_category();
  r.summary = NodeResiduals(objective, nodes, output, scale, &r.nodes);
  r.node_times_s = nodes.t_after_release_s;
  for (const ModelEvent& event : output.events) r.event_times_s.push_back(event.t_s);
  r.first_sample = nodes.first_sample;
  return r;
}

// The two runs of a stencil have the same nodes and no impact moves across a node time between them (then every
// residual is smooth between the stencil points).
bool SmoothBetween(const Residuals& a, const Residuals& b) {
  if (a.nodes.size() != b.nodes.size() || a.first_sample != b.first_sample ||
      a.event_times_s.size() != b.event_times_s.size()) {
    return false;
  }
  for (std::size_t e = 0; e < a.event_times_s.size(); ++e) {
    for (std::size_t i = 0; i < a.node_times_s.size(); ++i) {
      if ((a.node_times_s[i] < a.event_times_s[e]) != (b.node_times_s[i] < b.event_times_s[e])) return false;
    }
  }
  return true;
}

void CheckAgainstCentralDifferences(const ResidualScale& scale, const char* what) {
  const MeasuredSignal signal = PlanarRecording(0.15, 0.6, 7);
  const Objective objective = PlanarObjective(signal);
  ASSERT_EQ(objective.num_free(), 4u);  // t0, α, λ, λ_lon
  // Steps: the simulator's round-off (~1e-14) over the step stays ~1e-9 relative, the O(h²) truncation below 1e-8.
  const Eigen::Vector4d step(1e-6, 1e-6, 1e-5, 1e-5);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> t0_offset(-0.004, 0.004), alpha(0.12, 0.18), lambda_lon(0.45, 0.75);
  int checked = 0;
  for (int trial = 0; trial < 8; ++trial) {
    Eigen::VectorXd x(4);
    x << kTrueT0_s + t0_offset(rng), alpha(rng), 1.0, lambda_lon(rng);
    const Residuals base = At(objective, x, scale);
    ASSERT_TRUE(base.summary.available) << base.summary.reason;
    bool smooth = true;
    std::vector<std::vector<Eigen::Vector3d>> central(4);
    for (int j = 0; j < 4 && smooth; ++j) {
      Eigen::VectorXd xp = x, xm = x;
      xp[j] += step[j];
      xm[j] -= step[j];
      const Residuals plus = At(objective, xp, scale), minus = At(objective, xm, scale);
      // A stencil across a sample time (t0) or an impact across a node time: the residual is not smooth there.
      smooth = SmoothBetween(plus, minus) && SmoothBetween(base, plus);
      for (std::size_t i = 0; smooth && i < base.nodes.size(); ++i) {
        central[static_cast<std::size_t>(j)].push_back((plus.nodes[i].f - minus.nodes[i].f) / (2.0 * step[j]));
      }
    }
    if (!smooth) continue;
    for (int j = 0; j < 4; ++j) {
      double scale_j = 0.0, worst = 0.0;
      for (const NodeResidual& r : base.nodes) scale_j = std::max(scale_j, r.df_dx.col(j).norm());
      for (std::size_t i = 0; i < base.nodes.size(); ++i) {
        worst = std::max(worst, (base.nodes[i].df_dx.col(j) - central[static_cast<std::size_t>(j)][i]).norm());
      }
      if (j == 2) {
        EXPECT_EQ(scale_j, 0.0) << what << ": λ enters no planar run";
        EXPECT_EQ(worst, 0.0) << what;
        continue;
      }
      ASSERT_GT(scale_j, 0.0) << what << " column " << j;
      EXPECT_LT(worst / scale_j, kRelativeAgreement) << what << " column " << j << " (scale " << scale_j << ")";
    }
    ++checked;
  }
  EXPECT_GE(checked, 5) << what << ": too few points without a sample or an impact inside a stencil";
}

// The soft-L1 scaling of (28) over the test's window, as the Ceres stage uses it.
ResidualScale SoftL1Scale() {
  ResidualScale scale;
  scale.kind = ResidualScale::Kind::kSoftL1;
  scale.t_ref_s = kWindowEnd_s - kTrueT0_s;
  scale.nominal_dt_s = 1.0 / kRate_hz;
  return scale;
}

TEST(ResidualJacobian, SoftL1ResidualsMatchCentralDifferencesOnRandomPlanarPoints) {
  CheckAgainstCentralDifferences(SoftL1Scale(), "soft-L1");
}

TEST(ResidualJacobian, LeastSquaresResidualsMatchCentralDifferencesOnRandomPlanarPoints) {
  CheckAgainstCentralDifferences(ResidualScale{}, "least squares");
}

// A 3D release (λ_lat ≠ 0: vertex rocking, edge impacts) at t0 = 0.3 s, recorded at 256 Hz with fixed-seed noise.
MeasuredSignal SpatialRecording(const core::ModelParameters& truth, unsigned seed) {
  MeasuredSignal signal;
  const int n = static_cast<int>(kRecording_s * kRate_hz);
  std::vector<double> after_release;
  for (int k = 0; k <= n; ++k) {
    signal.t_s.push_back(k / kRate_hz);
    after_release.push_back(std::max(0.0, k / kRate_hz - kTrueT0_s));
  }
  ModelOutput out;
  Model()->Evaluate(truth, after_release, &out);
  EXPECT_TRUE(out.ok()) << out.failure_detail;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, kNoise_rad_s);
  for (const Eigen::Vector3d& w : out.w_B) {
    signal.w_B.push_back(w + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  }
  return signal;
}

// t0, α, λ, λ_lat and λ_lon free (τ_edge fixed): the five columns of the 3D Jacobian.
Objective SpatialObjective(const MeasuredSignal& signal) {
  ParameterSet p = ParameterSet::Defaults();
  p[ParameterId::kT0] = {kTrueT0_s, kTrueT0_s - 0.05, kTrueT0_s + 0.05, false};
  p[ParameterId::kAlpha].value = 0.15;
  p[ParameterId::kLambda] = {1.0, 0.0, 2.5, false};
  p[ParameterId::kLambdaLat] = {0.5, -2.5, 2.5, false};
  p[ParameterId::kLambdaLon].value = 0.6;
  return Objective(signal, kWindowEnd_s, Model(), p);
}

void CheckSpatialAgainstCentralDifferences(const ResidualScale& scale, const char* what) {
  core::ModelParameters truth;
  truth.alpha_rad = 0.15;
  truth.lambda = 1.2;
  truth.lambda_lat = 0.6;
  truth.lambda_lon = 0.5;
  const Objective objective = SpatialObjective(SpatialRecording(truth, 17));
  ASSERT_EQ(objective.num_free(), 5u);  // t0, α, λ, λ_lat, λ_lon
  // Five-point stencils (O(h⁴)): the columns of a 3D run grow fast along it, and the three-point stencil's O(h²)
  // truncation alone would reach 1e-6 of them; the simulator's round-off over these steps stays ~1e-8.
  const Eigen::Matrix<double, 5, 1> step = (Eigen::Matrix<double, 5, 1>() << 1e-7, 1e-6, 1e-6, 1e-6, 1e-6).finished();
  const std::array<double, 4> offsets{-2.0, -1.0, 1.0, 2.0};
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> t0_offset(-0.003, 0.003), alpha(0.14, 0.16), lambda(1.0, 1.4),
      lambda_lat(0.4, 0.8), lambda_lon(0.4, 0.6);
  int checked = 0, skipped = 0;
  for (int trial = 0; trial < 8; ++trial) {
    Eigen::VectorXd x(5);
    x << kTrueT0_s + t0_offset(rng), alpha(rng), lambda(rng), lambda_lat(rng), lambda_lon(rng);
    const Residuals base = At(objective, x, scale);
    ASSERT_TRUE(base.summary.available) << what << ": " << base.summary.reason;
    bool smooth = true;
    std::vector<std::vector<Eigen::Vector3d>> central(5);
    for (int j = 0; j < 5 && smooth; ++j) {
      std::array<Residuals, 4> r;
      for (std::size_t s = 0; s < offsets.size() && smooth; ++s) {
        Eigen::VectorXd xs = x;
        xs[j] += offsets[s] * step[j];
        r[s] = At(objective, xs, scale);
        smooth = SmoothBetween(base, r[s]);
      }
      for (std::size_t i = 0; smooth && i < base.nodes.size(); ++i) {
        central[static_cast<std::size_t>(j)].push_back(
            (r[0].nodes[i].f - 8.0 * r[1].nodes[i].f + 8.0 * r[2].nodes[i].f - r[3].nodes[i].f) / (12.0 * step[j]));
      }
    }
    if (!smooth) {
      ++skipped;  // an impact or a sample time inside a stencil (or the modes change): the residual jumps there
      continue;
    }
    for (int j = 0; j < 5; ++j) {
      double scale_j = 0.0, worst = 0.0;
      for (const NodeResidual& r : base.nodes) scale_j = std::max(scale_j, r.df_dx.col(j).norm());
      for (std::size_t i = 0; i < base.nodes.size(); ++i) {
        worst = std::max(worst, (base.nodes[i].df_dx.col(j) - central[static_cast<std::size_t>(j)][i]).norm());
      }
      ASSERT_GT(scale_j, 0.0) << what << " column " << j;
      EXPECT_LT(worst / scale_j, kRelativeAgreement) << what << " column " << j << " (scale " << scale_j << ")";
    }
    ++checked;
  }
  std::printf("%s: %d points checked, %d skipped (an impact or a sample time inside a stencil)\n", what, checked,
              skipped);
  EXPECT_GE(checked, 4) << what << ": too few points without an impact or a sample time inside a stencil";
}

TEST(ResidualJacobian, SoftL1ResidualsMatchCentralDifferencesOnRandom3dPoints) {
  CheckSpatialAgainstCentralDifferences(SoftL1Scale(), "soft-L1, 3D");
}

TEST(ResidualJacobian, LeastSquaresResidualsMatchCentralDifferencesOnRandom3dPoints) {
  CheckSpatialAgainstCentralDifferences(ResidualScale{}, "least squares, 3D");
}

TEST(ResidualJacobian, NotAvailableWhenLambdaLatIsFree) {
  const MeasuredSignal signal = PlanarRecording(0.15, 0.6, 7);
  ParameterSet p = PlanarObjective(signal).parameters();
  p[ParameterId::kLambdaLat].fixed = false;
  const Objective objective = PlanarObjective(signal).WithParameters(p);
  const Residuals r = At(objective, objective.FreeValues(p), ResidualScale{});
  EXPECT_FALSE(r.summary.available);
  EXPECT_NE(r.summary.reason.find("lambda_lat"), std::string::npos) << r.summary.reason;
}

TEST(ResidualJacobian, CeresWithTheExactJacobianFindsThePlanarTruthWithFewerModelRuns) {
  // Noise-free, so that the optimum is the truth (with noise it moves along the ridge t0 + T(α) = const).
  const MeasuredSignal signal = PlanarRecording(0.15, 0.6, 11, 0.0);
  const Objective objective = PlanarObjective(signal);
  Eigen::VectorXd x0(4);
  x0 << kTrueT0_s + 0.0021, 0.146, 1.0, 0.63;
  CeresOptions differences;
  differences.exact_jacobian = false;
  CeresOptions exact;
  exact.exact_jacobian = true;
  const LocalResult a = MakeCeres(differences)->Minimize(objective, x0);
  const LocalResult b = MakeCeres(exact)->Minimize(objective, x0);
  ASSERT_TRUE(a.feasible && b.feasible) << a.termination << " / " << b.termination;
  // Far below the difference steps of the other back end (whose secant slopes limit it to about those).
  EXPECT_NEAR(b.x[0], kTrueT0_s, 1e-6);
  EXPECT_NEAR(b.x[1], 0.15, 1e-6);
  EXPECT_NEAR(b.x[3], 0.6, 1e-5);
  // No worse a fit, from fewer runs of the simulator (one per iteration instead of 2n + 1).
  EXPECT_LE(b.epsilon_rad_s, a.epsilon_rad_s * (1.0 + 1e-3));
  EXPECT_LT(b.evaluations, a.evaluations);
}

TEST(ResidualJacobian, AutoWithExactDerivativesEndsWithCeresAloneAndFitsNoWorseThanNelderMeadThenCeres) {
  // A noisy planar trial from a start off the truth, without the global stage: with exact derivatives `auto` runs
  // the Ceres stage at a soft-L1 scale below the residuals and skips Nelder–Mead; the old order (Nelder–Mead, then
  // the differenced Ceres polish) is the reference.
  const MeasuredSignal signal = PlanarRecording(0.15, 0.6, 13);
  const Objective objective = PlanarObjective(signal);
  ParameterSet start = objective.parameters();
  start[ParameterId::kT0].value = kTrueT0_s + 0.0015;
  start[ParameterId::kAlpha].value = 0.147;
  start[ParameterId::kLambdaLon].value = 0.62;
  FitOptions exact_first;
  exact_first.global.enabled = false;
  exact_first.intervals.method = IntervalMethod::kNone;
  FitOptions reference = exact_first;
  reference.ceres.exact_jacobian = false;
  exact_first.ceres.exact_jacobian = true;
  exact_first.auto_exact_ceres_first = true;
  const FitSummary a = Fit(objective, start, exact_first);
  const FitSummary b = Fit(objective, start, reference);
  ASSERT_TRUE(a.feasible && b.feasible) << a.FullReport() << b.FullReport();
  ASSERT_EQ(a.stages.size(), 2u) << a.FullReport();
  EXPECT_EQ(a.stages[1].name, "ceres");
  EXPECT_EQ(a.kept_stage, "ceres");
  // The criterion for the fit's stages: ε at most 0.1 % above the reference's.
  constexpr double kAllowedRise = 1e-3;
  EXPECT_LE(a.epsilon_rad_s, b.epsilon_rad_s * (1.0 + kAllowedRise)) << a.FullReport() << b.FullReport();
  EXPECT_LT(a.simulations, b.simulations);
}

}  // namespace
}  // namespace rockfit::fitting
