// The derivatives of the edge and facet maps against central differences of the maps themselves (EdgeImpact,
// FacetImpact), on random configurations with a fixed seed.
#include "rockfit/core/impact_map_derivatives.hpp"

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "rockfit/core/edge_impact.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/facet_impact.hpp"
#include "simulation_cases.hpp"

namespace rockfit::core {
namespace {

// The maps are rational in their inputs; central differences with this step are exact to ~1e-10 relative
// (O(h²) truncation, round-off ~1e-16/h).
constexpr double kStep = 1e-6;
// Agreement relative to the size of the derivative (plus one, for entries that vanish).
constexpr double kRelativeAgreement = 1e-7;

void ExpectClose(const Eigen::Vector3d& exact, const Eigen::Vector3d& central, const char* what) {
  EXPECT_LT((exact - central).norm(), kRelativeAgreement * (1.0 + exact.norm()))
      << what << ": exact " << exact.transpose() << ", central " << central.transpose();
}

Eigen::Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

TEST(ImpactMapDerivatives, EdgeMapDerivativesMatchCentralDifferencesOfEdgeImpact) {
  const Block block = testing::Fig14Block();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> tilt(0.02, 0.4), lambda_draw(-0.5, 2.2), tau_draw(-0.02, 0.02);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int pivot = 1 + trial % 4;
    const int landing = Block::WrapVertex(pivot + ((trial / 4) % 2 == 0 ? 1 : -1));
    // The block on V_pivot with the edge to V_landing on the ground, turned a little about the pivot's other edge.
    const Eigen::Matrix3d R_WB = EdgeImpactAttitude(block, pivot, landing, tilt(rng));
    const Eigen::Vector3d w_minus_B = 1.5 * RandomUnit(rng);
    const EdgeImpactParameters params{lambda_draw(rng), tau_draw(rng)};
    const Eigen::Vector3d up_B = R_WB.transpose() * Eigen::Vector3d::UnitZ();
    const ImpactMapDerivatives d = EdgeImpactDerivatives(block, up_B, pivot, landing, w_minus_B, params);
    const ImpactOutcome map = EdgeImpact(block, R_WB, pivot, landing, R_WB * w_minus_B, params);
    if (!d.ok || map.status != ImpactStatus::kOk) continue;
    auto w_plus = [&](const Eigen::Matrix3d& R, const Eigen::Vector3d& w_B, const EdgeImpactParameters& p) {
      return Eigen::Vector3d(R.transpose() * EdgeImpact(block, R, pivot, landing, R * w_B, p).w_plus_W);
    };
    ExpectClose(d.w_plus_B, map.w_plus_B, "w_plus");
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
      ExpectClose(d.dw_plus_dw_minus.col(j),
                  (w_plus(R_WB, w_minus_B + kStep * e, params) - w_plus(R_WB, w_minus_B - kStep * e, params)) /
                      (2.0 * kStep),
                  "d w_plus / d w_minus");
      // A body-frame turn δθ of the attitude with ω⁻ fixed in B.
      const Eigen::Matrix3d R_plus = R_WB * Eigen::AngleAxisd(kStep, e).toRotationMatrix();
      const Eigen::Matrix3d R_minus = R_WB * Eigen::AngleAxisd(-kStep, e).toRotationMatrix();
      ExpectClose(d.dw_plus_dtheta.col(j),
                  (w_plus(R_plus, w_minus_B, params) - w_plus(R_minus, w_minus_B, params)) / (2.0 * kStep),
                  "d w_plus / d theta");
    }
    EdgeImpactParameters up = params, down = params;
    up.lambda += kStep;
    down.lambda -= kStep;
    ExpectClose(d.dw_plus_dlambda, (w_plus(R_WB, w_minus_B, up) - w_plus(R_WB, w_minus_B, down)) / (2.0 * kStep),
                "d w_plus / d lambda");
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

TEST(ImpactMapDerivatives, FacetMapDerivativesMatchCentralDifferencesOfEachCandidate) {
  const Block block = testing::Fig14Block();
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> lat_draw(-2.0, 2.0), lon_draw(0.1, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int pivot_b = 1 + trial % 4;
    FacetImpactParameters params;
    params.lambda_lat = lat_draw(rng);
    params.lambda_lon = lon_draw(rng);
    const Eigen::Vector3d w_minus_B = 2.0 * RandomUnit(rng);
    for (int a = 1; a <= 4; ++a) {
      const ImpactMapDerivatives d = FacetImpactDerivatives(block, pivot_b, a, w_minus_B, params);
      if (!d.ok) continue;
      auto w_plus = [&](const Eigen::Vector3d& w_B, const FacetImpactParameters& p) {
        const ImpactOutcome out = FacetImpact(block, pivot_b, w_B, p);
        return out.candidates[static_cast<std::size_t>(a - 1)].w_plus;
      };
      ExpectClose(d.w_plus_B, w_plus(w_minus_B, params), "w_plus");
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
        ExpectClose(d.dw_plus_dw_minus.col(j),
                    (w_plus(w_minus_B + kStep * e, params) - w_plus(w_minus_B - kStep * e, params)) / (2.0 * kStep),
                    "d w_plus / d w_minus");
      }
      FacetImpactParameters up = params, down = params;
      up.lambda_lat += kStep;
      down.lambda_lat -= kStep;
      ExpectClose(d.dw_plus_dlambda_lat, (w_plus(w_minus_B, up) - w_plus(w_minus_B, down)) / (2.0 * kStep),
                  "d w_plus / d lambda_lat");
      up = params;
      down = params;
      up.lambda_lon += kStep;
      down.lambda_lon -= kStep;
      ExpectClose(d.dw_plus_dlambda_lon, (w_plus(w_minus_B, up) - w_plus(w_minus_B, down)) / (2.0 * kStep),
                  "d w_plus / d lambda_lon");
      EXPECT_EQ(d.dw_plus_dtheta.norm(), 0.0) << "the flat block's map does not depend on its yaw";
      ++checked;
    }
  }
  EXPECT_GE(checked, 120);
}

TEST(ImpactMapDerivatives, FacetDerivativesRefuseTheFixedTauRule) {
  FacetImpactParameters params;
  params.tau_rule = FacetTauRule::kFixed;
  EXPECT_THROW(FacetImpactDerivatives(testing::Fig14Block(), 2, 3, Eigen::Vector3d(0.0, 1.0, 0.0), params),
               InvalidArgument);
}

}  // namespace
}  // namespace rockfit::core
