// The tabulated planar fall of the phase-1 fit (fitting/src/initial_guess_fall.cpp) against independent computations:
// energy at the angles the tabulated rates sweep, the fall time by quadrature (core/planar_rocking.hpp), and a fine
// RK4 integration of the edge's equation of motion.
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
// Energy: ω² against K(cos(θ_c − α) − cos(θ_c − ψ)) at the even nodes, ψ = α − ∫ω dτ by Simpson's rule over the nodes
// (error ~h⁴/180·|d⁴ω/dτ⁴|·T, ~1e-14 rad): ≤ 1.2e-12 rad²/s² seen.
constexpr double kEnergyTolerance_rad2_s2 = 1e-11;
// The nodes against a fixed-step RK4 integration at 1e-5 s (its error ~1e-15 rad/s): ≤ 8e-13 rad/s seen.
constexpr double kRateToleranceRadS = 1e-11;

struct Case {
  double b1_m, b2_m, h_m;  // half-dimensions of the block
  double alpha_fraction;   // α / θ_c
};

core::PlanarRocker RockerOf(const Case& c) {
  return core::PlanarRockerAboutEdge(core::Block::FromDensity(c.b1_m, c.b2_m, c.h_m, 2692.0), 1, 2);
}

// ψ at the even nodes: α − ∫₀^τ ω dτ by Simpson's rule over pairs of node intervals.
std::vector<double> TiltsAtEvenNodes(const PlanarFallTable& fall, double alpha_rad) {
  const double h = PlanarFallTable::kStepS;
  std::vector<double> psi{alpha_rad};
  for (std::size_t i = 0; i + 2 < fall.nodes(); i += 2) {
    const double swept = h / 3.0 * (fall.node_rate_rad_s(i) + 4.0 * fall.node_rate_rad_s(i + 1) + fall.node_rate_rad_s(i + 2));
    psi.push_back(psi.back() - swept);
  }
  return psi;
}

class PlanarFallTableCases : public ::testing::TestWithParam<Case> {};

TEST_P(PlanarFallTableCases, NodeRatesObeyEnergyAtTheAnglesTheySweep) {
  const core::PlanarRocker rocker = RockerOf(GetParam());
  const double alpha = GetParam().alpha_fraction * rocker.critical_angle_rad;
  const PlanarFallTable fall(rocker, alpha);
  ASSERT_TRUE(fall.closed_form());
  const std::vector<double> psi = TiltsAtEvenNodes(fall, alpha);
  const double theta_c = rocker.critical_angle_rad, K = rocker.K();
  for (std::size_t j = 0; j < psi.size(); ++j) {
    const double w = fall.node_rate_rad_s(2 * j);
    const double energy = K * (std::cos(theta_c - alpha) - std::cos(theta_c - psi[j]));
    ASSERT_NEAR(w * w, energy, kEnergyTolerance_rad2_s2) << "node " << 2 * j;
  }
}

TEST_P(PlanarFallTableCases, TableEndsAtTheFirstNodeAfterTheQuadratureFallTime) {
  const core::PlanarRocker rocker = RockerOf(GetParam());
  const double alpha = GetParam().alpha_fraction * rocker.critical_angle_rad;
  const PlanarFallTable fall(rocker, alpha);
  const double T = core::FallTime(rocker, alpha);
  EXPECT_NEAR(fall.fall_time_s(), T, kFallTimeToleranceS);
  EXPECT_GE(fall.table_end_s(), T - kFallTimeToleranceS);
  EXPECT_LT(fall.table_end_s() - PlanarFallTable::kStepS, T);
  // The last node is just past flat: its rate is the landing rate plus at most one step of the fall's acceleration.
  const double landing = core::LandingRate(rocker, alpha);
  EXPECT_GE(fall.node_rate_rad_s(fall.nodes() - 1), landing - 1e-12);
  EXPECT_LE(fall.node_rate_rad_s(fall.nodes() - 1), landing + 0.5 * rocker.K() * PlanarFallTable::kStepS);
}

TEST_P(PlanarFallTableCases, NodeRatesMatchAFineIntegration) {
  const core::PlanarRocker rocker = RockerOf(GetParam());
  const double alpha = GetParam().alpha_fraction * rocker.critical_angle_rad;
  const PlanarFallTable fall(rocker, alpha);
  // RK4 of ψ̈ = −(K/2)·sin(θ_c − ψ) from rest at α, ten steps per node.
  constexpr int kSubsteps = 10;
  const double h = PlanarFallTable::kStepS / kSubsteps, half_k = 0.5 * rocker.K(), theta_c = rocker.critical_angle_rad;
  auto accel = [&](double p) { return -half_k * std::sin(theta_c - p); };
  double psi = alpha, psi_dot = 0.0;
  for (std::size_t i = 1; i < fall.nodes(); ++i) {
    for (int n = 0; n < kSubsteps; ++n) {
      const double k1p = psi_dot, k1v = accel(psi);
      const double k2p = psi_dot + 0.5 * h * k1v, k2v = accel(psi + 0.5 * h * k1p);
      const double k3p = psi_dot + 0.5 * h * k2v, k3v = accel(psi + 0.5 * h * k2p);
      const double k4p = psi_dot + h * k3v, k4v = accel(psi + h * k3p);
      psi += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
      psi_dot += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
    ASSERT_NEAR(fall.node_rate_rad_s(i), -psi_dot, kRateToleranceRadS) << "node " << i;
  }
}

TEST_P(PlanarFallTableCases, IntegratedNodesAreTheClosedFormOnesToRoundOff) {
  const core::PlanarRocker rocker = RockerOf(GetParam());
  const double alpha = GetParam().alpha_fraction * rocker.critical_angle_rad;
  const PlanarFallTable closed(rocker, alpha);
  const PlanarFallTable integrated(rocker, alpha, PlanarFallTable::Nodes::kIntegrated);
  EXPECT_FALSE(integrated.closed_form());
  ASSERT_EQ(integrated.nodes(), closed.nodes());
  for (std::size_t i = 0; i < closed.nodes(); ++i) {
    ASSERT_NEAR(integrated.node_rate_rad_s(i), closed.node_rate_rad_s(i), kRateToleranceRadS) << "node " << i;
  }
  EXPECT_NEAR(integrated.fall_time_s(), closed.fall_time_s(), kFallTimeToleranceS);
}

INSTANTIATE_TEST_SUITE_P(Blocks, PlanarFallTableCases,
                         ::testing::Values(Case{0.05000453, 0.035, 0.2, 0.85},  // the sample blocks' release
                                           Case{0.05000453, 0.06, 0.2, 0.2}, Case{0.05, 0.0695, 0.1506, 0.5},
                                           Case{0.05, 0.035, 0.2, 0.995}));  // slow start near the critical angle

TEST(PlanarFallTable, RateIsZeroBeforeTheReleaseLinearBetweenNodesAndTheLastNodeAfter) {
  const core::PlanarRocker rocker = RockerOf({0.05000453, 0.035, 0.2, 0.0});
  const PlanarFallTable fall(rocker, 0.2);
  const double h = PlanarFallTable::kStepS;
  EXPECT_EQ(fall.Rate(-1e-3), 0.0);
  EXPECT_EQ(fall.Rate(0.0), 0.0);
  EXPECT_NEAR(fall.Rate(100.25 * h), 0.75 * fall.node_rate_rad_s(100) + 0.25 * fall.node_rate_rad_s(101), 1e-15);
  EXPECT_EQ(fall.Rate(fall.table_end_s() + 0.1), fall.node_rate_rad_s(fall.nodes() - 1));
}

TEST(PlanarFallTable, NextToTheCriticalAngleTheIntegratedNodesObeyEnergyToo) {
  const core::PlanarRocker rocker = RockerOf({0.05000453, 0.035, 0.2, 0.0});
  const double alpha = rocker.critical_angle_rad - 1e-5;  // k² ≈ 2.5e-11: no closed form
  const PlanarFallTable fall(rocker, alpha);
  EXPECT_FALSE(fall.closed_form());
  EXPECT_NEAR(fall.fall_time_s(), core::FallTime(rocker, alpha), kFallTimeToleranceS);
  EXPECT_GE(fall.table_end_s(), fall.fall_time_s() - 1e-9);
  EXPECT_LT(fall.table_end_s() - PlanarFallTable::kStepS, fall.fall_time_s() + 1e-9);
  const std::vector<double> psi = TiltsAtEvenNodes(fall, alpha);
  const double theta_c = rocker.critical_angle_rad, K = rocker.K();
  for (std::size_t j = 0; j < psi.size(); j += 97) {
    const double w = fall.node_rate_rad_s(2 * j);
    EXPECT_NEAR(w * w, K * (std::cos(theta_c - alpha) - std::cos(theta_c - psi[j])), kEnergyTolerance_rad2_s2);
  }
}

TEST(PlanarFallTable, TiltOutsideZeroToCriticalAngleIsInvalid) {
  const core::PlanarRocker rocker = RockerOf({0.05000453, 0.035, 0.2, 0.0});
  EXPECT_THROW(PlanarFallTable(rocker, 0.0), InvalidArgument);
  EXPECT_THROW(PlanarFallTable(rocker, rocker.critical_angle_rad), InvalidArgument);
  EXPECT_THROW(PlanarFallTable(rocker, std::nan("")), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::fitting
