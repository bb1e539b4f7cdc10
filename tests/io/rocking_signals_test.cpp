// Checks of the test support itself (tests/support/rocking_signals.hpp): the planar rocking it generates obeys
// its own equations (energy between impacts, (6) at impacts), so the metrics tests compare against truth.
#include "rocking_signals.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace rockfit::testing {
namespace {

TEST(RockingSignals, EnergyIsConservedBetweenImpactsAndReducedByRSquaredAtEach) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.duration_s = 6.0;
  const PlanarRocking motion = SimulatePlanarRocking(block, spec);
  ASSERT_GE(motion.impact_times_s.size(), 20u);
  const double g = core::kStandardGravity, m = block.mass(), b = block.b1(), h = block.h();
  const double radius = std::hypot(b, h), alpha_c = std::atan2(b, h);
  const double J = block.inertia_C_B()(1, 1) + m * radius * radius;
  const auto energy = [&](double phi, double w) {
    return 0.5 * J * w * w + m * g * (radius * std::cos(alpha_c - std::abs(phi)) - h);
  };
  // Release energy m g u(α) with u(α) = b sin α − h (1 − cos α).
  const double e0 = m * g * (b * std::sin(spec.alpha_rad) - h * (1 - std::cos(spec.alpha_rad)));
  std::size_t impact = 0;
  double expected = e0;
  for (std::size_t k = 0; k < motion.t_s.size(); ++k) {
    if (motion.t_s[k] <= spec.release_s) continue;
    while (impact < motion.impact_times_s.size() && motion.impact_times_s[impact] < motion.t_s[k]) {
      expected *= motion.r * motion.r;  // ½Jω⁺² = r²·½Jω⁻²
      ++impact;
    }
    if (impact >= motion.impact_times_s.size()) break;
    EXPECT_NEAR(energy(motion.phi_y_rad[k], motion.omega_y_rad_s[k]), expected, 1e-12 * e0) << "t = " << motion.t_s[k];
  }
}

TEST(RockingSignals, ImpactsFollowChatzisMapAndAlternateSides) {
  const core::Block block = PaperLikeBlock();
  PlanarRockingSpec spec;
  spec.lambda = 0.4;
  spec.duration_s = 8.0;
  const PlanarRocking motion = SimulatePlanarRocking(block, spec);
  ASSERT_GE(motion.impact_times_s.size(), 10u);
  const double m = block.mass(), h = block.h(), b = block.b1(), theta = block.inertia_C_B()(1, 1);
  const double r6 = (theta + m * h * h - m * 0.4 * b * b) / (theta + m * h * h + m * 0.4 * b * b);  // (6)
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_NEAR(motion.omega_plus_rad_s[i] / motion.omega_minus_rad_s[i], r6, 1e-15);
    if (i > 0) {
      EXPECT_LT(motion.omega_minus_rad_s[i] * motion.omega_minus_rad_s[i - 1], 0.0);
    }
  }
  // The first fall starts from rest at φy = −α and has ω_y > 0 (docs/design.md §2).
  EXPECT_GT(motion.omega_minus_rad_s[0], 0.0);
}

}  // namespace
}  // namespace rockfit::testing
