#include "rockfit/core/planar_avrf.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

// Identities between (3)–(6) hold to a few ulps of r ≈ 1.
constexpr double kAvrfTol = 1e-15;

PlanarBlock Fig11BlockAboutY() { return PlanarBlockAboutY(Block::FromMass(0.05, 0.03, 0.20, 1.0)); }

TEST(PlanarAvrf, PlanarBlocksTakeTheInertiaAndHalfWidthOfTheirPlane) {
  const Block block = Block::FromMass(0.05, 0.03, 0.20, 1.0);
  const PlanarBlock y = PlanarBlockAboutY(block);
  const PlanarBlock x = PlanarBlockAboutX(block);
  EXPECT_DOUBLE_EQ(y.theta_kg_m2, (0.05 * 0.05 + 0.2 * 0.2) / 3.0);
  EXPECT_DOUBLE_EQ(y.b_m, 0.05);
  EXPECT_DOUBLE_EQ(x.theta_kg_m2, (0.03 * 0.03 + 0.2 * 0.2) / 3.0);
  EXPECT_DOUBLE_EQ(x.b_m, 0.03);
  EXPECT_DOUBLE_EQ(x.h_m, 0.2);
  EXPECT_DOUBLE_EQ(x.mass_kg, 1.0);
}

TEST(PlanarAvrf, ChatzisAtLambdaOneIsHousnerAndAtZeroIsOne) {
  for (const PlanarBlock& p : {Fig11BlockAboutY(), PlanarBlock{2.0, 0.01, 0.3, 0.1}}) {
    EXPECT_NEAR(AvrfChatzis(p, 1.0), AvrfHousner(p), kAvrfTol);
    EXPECT_EQ(AvrfChatzis(p, 0.0), 1.0);
  }
}

TEST(PlanarAvrf, KalliontzisIsChatzisWithLambdaEqualToVSquared) {
  const PlanarBlock p = Fig11BlockAboutY();
  for (double v = 0.0; v <= 1.0; v += 0.125) EXPECT_NEAR(AvrfKalliontzis(p, v), AvrfChatzis(p, v * v), kAvrfTol);
  EXPECT_NEAR(AvrfKalliontzis(p, 1.0), AvrfHousner(p), kAvrfTol);
}

TEST(PlanarAvrf, HousnerConservesAngularMomentumAboutTheLandingCorner) {
  // (1): θω⁻ + mh²ω⁻ − mb²ω⁻ = θω⁺ + mh²ω⁺ + mb²ω⁺ with ω⁺ = r ω⁻.
  const PlanarBlock p = Fig11BlockAboutY();
  const double r = AvrfHousner(p);
  const double lhs = p.theta_kg_m2 + p.mass_kg * p.h_m * p.h_m - p.mass_kg * p.b_m * p.b_m;
  const double rhs = r * (p.theta_kg_m2 + p.mass_kg * p.h_m * p.h_m + p.mass_kg * p.b_m * p.b_m);
  EXPECT_NEAR(lhs, rhs, 1e-17);
}

TEST(PlanarAvrf, TherKollarLiesBetweenHousnerAndOne) {
  // The paper (Sect. 2): the two-impact model (5) gives an AVRF in (r_Hou, 1).
  const PlanarBlock p = Fig11BlockAboutY();
  EXPECT_GT(AvrfTherKollar(p), AvrfHousner(p));
  EXPECT_LT(AvrfTherKollar(p), 1.0);
  // Written out: (θ + mh²) / (θ + mh² + mb²).
  const double j0 = p.theta_kg_m2 + p.mass_kg * p.h_m * p.h_m;
  EXPECT_DOUBLE_EQ(AvrfTherKollar(p), j0 / (j0 + p.mass_kg * p.b_m * p.b_m));
}

TEST(PlanarAvrf, InverseOfChatzisRoundTrips) {
  const PlanarBlock p = Fig11BlockAboutY();
  for (double lambda = -3.0; lambda <= 3.0; lambda += 0.25) {
    EXPECT_NEAR(LambdaFromAvrf(p, AvrfChatzis(p, lambda)), lambda, 1e-12) << "λ = " << lambda;
  }
  for (double r = -0.9; r <= 2.0; r += 0.1) {
    EXPECT_NEAR(AvrfChatzis(p, LambdaFromAvrf(p, r)), r, 1e-13) << "r = " << r;
  }
  EXPECT_EQ(LambdaFromAvrf(p, 1.0), 0.0);
  EXPECT_NEAR(LambdaFromAvrf(p, AvrfHousner(p)), 1.0, 1e-13);
}

TEST(PlanarAvrf, InverseRejectsMinusOneAndNonFiniteValues) {
  const PlanarBlock p = Fig11BlockAboutY();
  EXPECT_THROW(LambdaFromAvrf(p, -1.0), InvalidArgument);
  EXPECT_THROW(LambdaFromAvrf(p, std::numeric_limits<double>::quiet_NaN()), InvalidArgument);
  EXPECT_THROW(LambdaFromAvrf(p, std::numeric_limits<double>::infinity()), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::core
