// The exact derivatives of a planar run's samples against central differences of the simulator itself, on random
// cases with a fixed seed, and the cases where they are (rightly) not available.
#include "rockfit/core/planar_sensitivity.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/simulator.hpp"
#include "simulation_cases.hpp"

namespace rockfit::core {
namespace {

// Agreement of an exact derivative column with central differences, relative to the column's largest entry: the
// derivatives are exact to the 1e-12 integration tolerance, central differences with the steps below to ~1e-8.
constexpr double kRelativeAgreement = 1e-6;
// Steps of the central differences: large enough that the simulator's round-off (~1e-14 rad/s with closed-form
// swings) divided by the step stays ~1e-9, small enough that the O(h²) truncation stays below ~1e-8 relative.
constexpr double kAlphaStep_rad = 1e-5;
constexpr double kLambdaLonStep = 1e-5;
constexpr double kTimeStep_s = 1e-6;
constexpr double kRate_hz = 256.0;
constexpr double kWindow_s = 1.2;

SimulationOptions Options(double time_shift_s = 0.0) {
  return testing::SampledRateOptions(kWindow_s, kRate_hz, time_shift_s);
}

ModelParameters Planar(double alpha_rad, double lambda_lon) {
  ModelParameters p;
  p.alpha_rad = alpha_rad;
  p.lambda_lon = lambda_lon;
  p.lambda_lat = 0.0;
  p.lambda = 1.0;
  return p;
}

// True when the landings of two runs pair up one to one (same kinds) and no landing moves across a sample time
// between them: then every sample lies in the same swing in both runs and the residual is smooth between them.
bool SameSwingsAtEverySample(const Trajectory& a, const Trajectory& b, const std::vector<double>& times_a,
                             const std::vector<double>& times_b) {
  if (a.impacts.size() != b.impacts.size() || a.t_s.size() != b.t_s.size()) return false;
  for (std::size_t i = 0; i < a.impacts.size(); ++i) {
    if (a.impacts[i].kind != b.impacts[i].kind) return false;
    for (std::size_t k = 0; k < times_a.size(); ++k) {
      // The sample lies before the landing in one run and not in the other.
      if ((times_a[k] < a.impacts[i].t_s) != (times_b[k] < b.impacts[i].t_s)) return false;
    }
  }
  return true;
}

struct Column {
  std::vector<Eigen::Vector3d> exact;
  std::vector<Eigen::Vector3d> central;
};

void ExpectAgreement(const Column& column, const char* what) {
  double scale = 0.0;
  for (const Eigen::Vector3d& d : column.exact) scale = std::max(scale, d.norm());
  ASSERT_GT(scale, 0.0) << what;
  double worst = 0.0;
  for (std::size_t k = 0; k < column.exact.size(); ++k) {
    worst = std::max(worst, (column.exact[k] - column.central[k]).norm() / scale);
  }
  EXPECT_LT(worst, kRelativeAgreement) << what << ": largest difference relative to the column's scale " << scale;
}

TEST(PlanarSensitivity, DerivativesMatchCentralDifferencesOfTheSimulatorOnRandomPlanarRuns) {
  const Block block = testing::Fig14Block();
  const double theta_c = EdgeDynamics(block, 1, 2, kStandardGravity).critical_angle_rad();
  std::mt19937 rng(20261126);
  std::uniform_real_distribution<double> alpha_fraction(0.2, 0.9);
  std::uniform_real_distribution<double> lambda_lon_draw(0.3, 1.0);
  int checked = 0, skipped = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const double alpha = alpha_fraction(rng) * theta_c;
    const double lambda_lon = lambda_lon_draw(rng);
    const SimulationOptions options = Options();
    const Trajectory base = Simulate(block, Planar(alpha, lambda_lon), options);
    const PlanarSensitivitySummary s = PlanarSampleSensitivities(block, Planar(alpha, lambda_lon), options, base);
    ASSERT_TRUE(s.available) << s.reason;
    ASSERT_EQ(s.dw_B.size(), base.w_B.size());

    // The stencils: ±h in α, λ_lon and in every sample time (a shift of the release time t0).
    const Trajectory a_plus = Simulate(block, Planar(alpha + kAlphaStep_rad, lambda_lon), options);
    const Trajectory a_minus = Simulate(block, Planar(alpha - kAlphaStep_rad, lambda_lon), options);
    const Trajectory l_plus = Simulate(block, Planar(alpha, lambda_lon + kLambdaLonStep), options);
    const Trajectory l_minus = Simulate(block, Planar(alpha, lambda_lon - kLambdaLonStep), options);
    const SimulationOptions later = Options(kTimeStep_s), earlier = Options(-kTimeStep_s);
    const Trajectory t_plus = Simulate(block, Planar(alpha, lambda_lon), later);
    const Trajectory t_minus = Simulate(block, Planar(alpha, lambda_lon), earlier);
    const std::vector<double>& times = options.sample_times_s;
    if (!SameSwingsAtEverySample(a_plus, a_minus, times, times) || !SameSwingsAtEverySample(l_plus, l_minus, times, times) ||
        !SameSwingsAtEverySample(t_plus, t_minus, later.sample_times_s, earlier.sample_times_s)) {
      ++skipped;  // a landing crosses a sample time inside a stencil: the residual jumps there
      continue;
    }
    Column alpha_col, lambda_col, time_col;
    for (std::size_t k = 0; k < base.w_B.size(); ++k) {
      const SampleSensitivity& d = s.dw_B[k];
      alpha_col.exact.push_back(d.col(static_cast<int>(SensitivityColumn::kAlpha)));
      alpha_col.central.push_back((a_plus.w_B[k] - a_minus.w_B[k]) / (2.0 * kAlphaStep_rad));
      lambda_col.exact.push_back(d.col(static_cast<int>(SensitivityColumn::kLambdaLon)));
      lambda_col.central.push_back((l_plus.w_B[k] - l_minus.w_B[k]) / (2.0 * kLambdaLonStep));
      // The release is an event too (held before, free after): a time stencil across it is one-sided.
      if (earlier.sample_times_s[k] > 0.0) {
        time_col.exact.push_back(d.col(static_cast<int>(SensitivityColumn::kTime)));
        time_col.central.push_back((t_plus.w_B[k] - t_minus.w_B[k]) / (2.0 * kTimeStep_s));
      }
      EXPECT_EQ(d.col(static_cast<int>(SensitivityColumn::kLambda)).norm(), 0.0) << "λ enters no planar run";
    }
    ExpectAgreement(alpha_col, "d w_B / d alpha");
    ExpectAgreement(lambda_col, "d w_B / d lambda_lon");
    ExpectAgreement(time_col, "d w_B / d t");
    ++checked;
  }
  // The fixed seed gives enough cases without a landing inside a stencil to mean something.
  EXPECT_GE(checked, 8) << skipped << " cases skipped";
}

TEST(PlanarSensitivity, ReportsTheSwingsThroughEveryLandingAndAgreesWithTheSimulatorsSamples) {
  const Block block = testing::Fig14Block();
  const SimulationOptions options = Options();
  const ModelParameters p = Planar(0.15, 0.6);
  const Trajectory run = Simulate(block, p, options);
  const PlanarSensitivitySummary s = PlanarSampleSensitivities(block, p, options, run);
  ASSERT_TRUE(s.available) << s.reason;
  std::size_t landings = 0;
  for (const ImpactRecord& impact : run.impacts) landings += impact.kind == ImpactKind::kFacet ? 1 : 0;
  ASSERT_GE(landings, 2u);
  EXPECT_EQ(static_cast<std::size_t>(s.swings), landings + 1);
  // The derivatives of λ_lat are one-sided at 0 and left undefined.
  EXPECT_TRUE(std::isnan(s.dw_B[1](0, static_cast<int>(SensitivityColumn::kLambdaLat))));
  EXPECT_LT(s.max_disagreement_rad_s, PlanarSensitivityOptions{}.agreement_tol_rad_s);
}

TEST(PlanarSensitivity, NotAvailableForARunThatLeavesThePlane) {
  const Block block = testing::Fig14Block();
  const SimulationOptions options = Options();
  ModelParameters p = Planar(0.15, 0.6);
  p.lambda_lat = 0.3;
  const Trajectory run = Simulate(block, p, options);
  const PlanarSensitivitySummary s = PlanarSampleSensitivities(block, p, options, run);
  EXPECT_FALSE(s.available);
  EXPECT_NE(s.reason.find("lambda_lat"), std::string::npos) << s.reason;
}

TEST(PlanarSensitivity, NotAvailableWhenTheSamplesAreNotThoseOfThePlanarRun) {
  // Samples of another run (another tilt) must be caught by the agreement check, not differentiated.
  const Block block = testing::Fig14Block();
  const SimulationOptions options = Options();
  const Trajectory other = Simulate(block, Planar(0.12, 0.6), options);
  const PlanarSensitivitySummary s = PlanarSampleSensitivities(block, Planar(0.15, 0.6), options, other);
  EXPECT_FALSE(s.available);
  EXPECT_FALSE(s.reason.empty());
}

}  // namespace
}  // namespace rockfit::core
