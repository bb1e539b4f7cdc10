// The planar release: the quadrature T(α) against an independent quadrature, and the energy relations.
#include "rockfit/core/planar_rocking.hpp"

#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "simulation_cases.hpp"

namespace rockfit::core {
namespace {

// T(α) with the substitution ψ = α(1 − s²), which removes the endpoint singularity:
//   T = ∫₀¹ 2αs ds / √(K·2 sin(θ_c − α + αs²/2)·sin(αs²/2)),
// integrated with composite 5-point Gauss–Legendre on many panels (the integrand is smooth on [0, 1]).
double FallTimeBySubstitution(const PlanarRocker& r, double alpha) {
  static constexpr std::array<double, 5> kNodes = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                                   0.5384693101056831, 0.9061798459386640};
  static constexpr std::array<double, 5> kWeights = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                                     0.4786286704993665, 0.2369268850561891};
  const int panels = 400;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double a = static_cast<double>(p) / panels;
    const double half = 0.5 / panels;
    for (int i = 0; i < 5; ++i) {
      const double s = a + half * (1.0 + kNodes[i]);
      const double drop = 2.0 * std::sin(r.critical_angle_rad - alpha + 0.5 * alpha * s * s) *
                          std::sin(0.5 * alpha * s * s);
      sum += half * kWeights[i] * 2.0 * alpha * s / std::sqrt(r.K() * drop);
    }
  }
  return sum;
}

PlanarRocker TestRocker() {
  return PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2);
}

TEST(PlanarRocking, FallTimeMatchesAnIndependentQuadrature) {
  const PlanarRocker rocker = TestRocker();
  for (double alpha : {0.001, 0.02, 0.1, 0.197, 0.24}) {
    EXPECT_NEAR(FallTime(rocker, alpha), FallTimeBySubstitution(rocker, alpha), 1e-13) << "α = " << alpha;
  }
}

TEST(PlanarRocking, FallTimeGrowsWithoutBoundTowardsTheCriticalAngle) {
  // Released at the balance point the block never falls: T(α) → ∞ as α → θ_c.
  const PlanarRocker rocker = TestRocker();
  EXPECT_GT(FallTime(rocker, rocker.critical_angle_rad - 1e-6), 3.0 * FallTime(rocker, 0.2));
  EXPECT_EQ(FallTime(rocker, 0.0), 0.0);
  EXPECT_THROW(FallTime(rocker, rocker.critical_angle_rad), InvalidArgument);
  EXPECT_THROW(FallTime(rocker, -0.1), InvalidArgument);
}

TEST(PlanarRocking, LandingRateFollowsFromEnergy) {
  const PlanarRocker rocker = TestRocker();
  const double alpha = 0.15;
  const double rate = LandingRate(rocker, alpha);
  // ½ J ω² = m g (z_C(α) − z_C(0)) with z_C(ψ) = R cos(θ_c − ψ).
  const double drop = rocker.arm_m * (std::cos(rocker.critical_angle_rad - alpha) - std::cos(rocker.critical_angle_rad));
  EXPECT_NEAR(0.5 * rocker.inertia_kg_m2 * rate * rate, rocker.mass_kg * rocker.gravity_m_s2 * drop, 1e-14);
  const std::optional<double> back = AmplitudeFromLandingRate(rocker, rate);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(*back, alpha, 1e-13);
  EXPECT_FALSE(AmplitudeFromLandingRate(rocker, 1.01 * LandingRate(rocker, rocker.critical_angle_rad)).has_value());
}

}  // namespace
}  // namespace rockfit::core
