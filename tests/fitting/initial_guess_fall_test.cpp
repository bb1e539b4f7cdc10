// The tabulated planar fall of the phase-1 fit (fitting/src/initial_guess_fall.cpp) against independent computations:
// energy at the angle swept by the tabulated rates, the fall time by quadrature (core/planar_rocking.hpp), and a
// fine RK4 integration of the edge's equation of motion.
#include "rockfit/fitting/initial_guess_fall.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_rocking.hpp"

namespace rockfit::fitting {
namespace {

// T(α): QAWS is exact to ~1e-14 s, the closed form to round-off.
constexpr double kFallTimeToleranceS = 1e-12;
// Energy: ω² against K(cos(θ_c − α) − cos(θ_c − ψ)) with ψ = α − ∫ω dτ by Simpson's rule (exact on the cubic pieces);
// the Hermite error and round-off leave ~1e-11 rad²/s².
constexpr double kEnergyTolerance_rad2_s2 = 1e-10;
// The slope at the nodes against (K/2)·sin(θ_c − ψ) at the same angles (~1e-11 rad/s² seen).
constexpr double kSlopeToleranceRadS2 = 1e-9;
// ω between the nodes against a fixed-step RK4 integration at 1e-5 s (its error ~1e-15 rad/s): ~5e-12 rad/s seen.
constexpr double kRateToleranceRadS = 1e-10;
// The angle swept over the fall is α.
constexpr double kSweptToleranceRad = 1e-11;
// Simpson panels per node interval.
constexpr int kPanels = 8;

struct Case {
  double b1_m, b2_m, h_m;  // half-dimensions of the block
  double alpha_fraction;   // α / θ_c
};

core::PlanarRocker RockerOf(const Case& c) {
  return core::PlanarRockerAboutEdge(core::Block::FromDensity(c.b1_m, c.b2_m, c.h_m, 2692.0), 1, 2);
}

// ψ at each node time of `fall`: α − ∫₀^τ ω dτ by Simpson's rule over kPanels panels per interval.
std::vector<double> TiltsAtNodes(const PlanarFallTable& fall, double alpha_rad) {
  std::vector<double> psi{alpha_rad};
  for (std::size_t i = 0; i + 1 < fall.nodes(); ++i) {
    const double a = fall.node_time_s(i), b = fall.node_time_s(i + 1);
    const double step = (b - a) / kPanels;
    double sum = fall.Rate(a) + fall.Rate(b);
    for (int j = 1; j < kPanels; ++j) sum += (j % 2 == 1 ? 4.0 : 2.0) * fall.Rate(a + step * j);
    psi.push_back(psi.back() - sum * step / 3.0);
  }
  return psi;
}

class PlanarFallTableCases : public ::testing::TestWithParam<Case> {};

TEST_P(PlanarFallTableCases, RatesAndSlopesObeyEnergyAtTheAnglesTheySweep) {
  const core::PlanarRocker rocker = RockerOf(GetParam());
  const double alpha = GetParam().alpha_fraction * rocker.critical_angle_rad;
  const PlanarFallTable fall(rocker, alpha);
  ASSERT_TRUE(fall.closed_form());
  const std::vector<double> psi = TiltsAtNodes(fall, alpha);
  const double theta_c = rocker.critical_angle_rad, K = rocker.K();
  for (std::size_t i = 0; i < fall.nodes(); ++i) {
    const double tau = fall.node_time_s(i);
    const FallRate w = fall.RateAndSlope(tau);
    const double energy = K * (std::cos(theta_c - alpha) - std::cos(theta_c - psi[i]));
    EXPECT_NEAR(w.rate_rad_s * w.rate_rad_s, energy, kEnergyTolerance_rad2_s2) << "τ = " << tau;
    EXPECT_NEAR(w.slope_rad_s2, 0.5 * K * std::sin(theta_c - psi[i]), kSlopeToleranceRadS2) << "τ = " << tau;
  }
  EXPECT_NEAR(psi.back(), 0.0, kSweptToleranceRad) << "the fall sweeps α";
}

TEST_P(PlanarFallTableCases, FallTimeAndLandingRateAreTheQuadratureAndEnergy) {
  const core::PlanarRocker rocker = RockerOf(GetParam());
  const double alpha = GetParam().alpha_fraction * rocker.critical_angle_rad;
  const PlanarFallTable fall(rocker, alpha);
  EXPECT_NEAR(fall.fall_time_s(), core::FallTime(rocker, alpha), kFallTimeToleranceS);
  EXPECT_NEAR(fall.landing_rate_rad_s(), core::LandingRate(rocker, alpha), 1e-12);
  EXPECT_EQ(fall.Rate(-1e-3), 0.0);
  EXPECT_EQ(fall.Rate(fall.fall_time_s() + 0.1), fall.landing_rate_rad_s());
}

TEST_P(PlanarFallTableCases, RatesBetweenNodesMatchAFineIntegration) {
  const core::PlanarRocker rocker = RockerOf(GetParam());
  const double alpha = GetParam().alpha_fraction * rocker.critical_angle_rad;
  const PlanarFallTable fall(rocker, alpha);
  // RK4 of ψ̈ = −(K/2)·sin(θ_c − ψ) from rest at α, compared every 37 steps (off the table's nodes).
  const double h = 1e-5, half_k = 0.5 * rocker.K(), theta_c = rocker.critical_angle_rad;
  auto accel = [&](double p) { return -half_k * std::sin(theta_c - p); };
  double psi = alpha, psi_dot = 0.0;
  int compared = 0;
  for (int n = 1; h * n < fall.fall_time_s(); ++n) {
    const double k1p = psi_dot, k1v = accel(psi);
    const double k2p = psi_dot + 0.5 * h * k1v, k2v = accel(psi + 0.5 * h * k1p);
    const double k3p = psi_dot + 0.5 * h * k2v, k3v = accel(psi + 0.5 * h * k2p);
    const double k4p = psi_dot + h * k3v, k4v = accel(psi + h * k3p);
    psi += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
    psi_dot += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (n % 37 == 0) {
      ASSERT_NEAR(fall.Rate(h * n), -psi_dot, kRateToleranceRadS) << "τ = " << h * n;
      ++compared;
    }
  }
  EXPECT_GT(compared, 100);
}

INSTANTIATE_TEST_SUITE_P(Blocks, PlanarFallTableCases,
                         ::testing::Values(Case{0.05000453, 0.035, 0.2, 0.85},  // the sample blocks' release
                                           Case{0.05000453, 0.06, 0.2, 0.2}, Case{0.05, 0.0695, 0.1506, 0.5},
                                           Case{0.05, 0.035, 0.2, 0.995}));  // slow start near the critical angle

TEST(PlanarFallTable, NextToTheCriticalAngleTheIntegratedNodesObeyEnergyToo) {
  const core::PlanarRocker rocker = RockerOf({0.05000453, 0.035, 0.2, 0.0});
  const double alpha = rocker.critical_angle_rad - 1e-5;  // k² ≈ 2.5e-11: no closed form
  const PlanarFallTable fall(rocker, alpha);
  EXPECT_FALSE(fall.closed_form());
  EXPECT_NEAR(fall.fall_time_s(), core::FallTime(rocker, alpha), kFallTimeToleranceS);
  const std::vector<double> psi = TiltsAtNodes(fall, alpha);
  const double theta_c = rocker.critical_angle_rad, K = rocker.K();
  for (std::size_t i = 0; i < fall.nodes(); i += 97) {
    const double w = fall.Rate(fall.node_time_s(i));
    EXPECT_NEAR(w * w, K * (std::cos(theta_c - alpha) - std::cos(theta_c - psi[i])), kEnergyTolerance_rad2_s2);
  }
  EXPECT_NEAR(psi.back(), 0.0, 1e-9) << "the fall sweeps α (RK4 nodes: ~h⁴ over a long fall)";
}

TEST(PlanarFallTable, TiltOutsideZeroToCriticalAngleIsInvalid) {
  const core::PlanarRocker rocker = RockerOf({0.05000453, 0.035, 0.2, 0.0});
  EXPECT_THROW(PlanarFallTable(rocker, 0.0), InvalidArgument);
  EXPECT_THROW(PlanarFallTable(rocker, rocker.critical_angle_rad), InvalidArgument);
  EXPECT_THROW(PlanarFallTable(rocker, std::nan("")), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
