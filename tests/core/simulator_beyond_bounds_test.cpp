// Under a table, impact parameters beyond the bounds (26)/(27): a facet impact that leaves less kinetic energy than
// lifts the COM by rest_energy_height drops its velocity and the contact decides; within the bounds, or above that
// energy, the motion goes on as the equations say (docs/design.md §11a, "Parameters beyond the bounds").
#include <gtest/gtest.h>

#include "rockfit/core/block.hpp"
#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core {
namespace {

// The sample campaign's block2 and the pooled estimates of its position A (λ_lat and λ beyond (27) and (25)).
Block Block2() { return Block::FromDensity(0.05000453, 0.035, 0.2, 2692.0); }

ModelParameters FittedBeyondBounds() {
  ModelParameters p;
  p.lambda = 2.264;
  p.lambda_lat = -1.869;
  p.lambda_lon = 0.2415;
  return p;
}

ModelParameters WithinBounds() {
  ModelParameters p;
  p.lambda = 1.0;
  p.lambda_lat = 0.0;
  p.lambda_lon = 0.9;
  return p;
}

// The flat block lifting about V1V2 with kinetic energy `energy_in_mg_nm` × m·g·1 nm, on a table at rest.
Trajectory RockFromFlat(const ModelParameters& params, double energy_in_mg_nm) {
  const Block block = Block2();
  const EdgeDynamics edge(block, 1, 2, kStandardGravity);
  const double energy_J = energy_in_mg_nm * block.mass() * kStandardGravity * 1e-9;
  const double rate = std::sqrt(2.0 * energy_J / edge.inertia_kg_m2());
  SimulationOptions options;
  options.stop = StopCondition::kRest;
  options.t_max_s = 2.0;
  options.initial_state = InitialState{Contact::Edge(1, 2), Eigen::Quaterniond::Identity(), rate * edge.axis_B()};
  const GroundMotion still = GroundMotion::Uniform(1.0, {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                                         Eigen::Vector3d::Zero()});
  return Simulate(block, params, options, still, GroundStart::kAsOptions);
}

TEST(SimulatorBeyondBounds, ASubNanometreFacetImpactBeyondTheBoundsEndsInRest) {
  const Trajectory tr = RockFromFlat(FittedBeyondBounds(), 0.5);
  ASSERT_EQ(tr.end_reason, EndReason::kRest) << tr.message;
  ASSERT_EQ(tr.impacts.size(), 2u);
  EXPECT_EQ(tr.impacts[0].kind, ImpactKind::kFacet);
  EXPECT_EQ(tr.impacts[1].kind, ImpactKind::kRest);
  EXPECT_GT(tr.max_discarded_rate_rad_s, 0.0);
}

TEST(SimulatorBeyondBounds, AboveTheResolutionTheMotionGoesOn) {
  const Trajectory tr = RockFromFlat(FittedBeyondBounds(), 1e4);
  EXPECT_GT(tr.impacts.size(), 2u);
  EXPECT_EQ(tr.impacts[1].kind == ImpactKind::kRest, false);
}

TEST(SimulatorBeyondBounds, WithinTheBoundsTheContactRuleAloneDecides) {
  const Trajectory tr = RockFromFlat(WithinBounds(), 0.5);
  EXPECT_GT(tr.impacts.size(), 2u);  // facet impacts go on until they accumulate
  EXPECT_NE(tr.end_reason, EndReason::kFailed) << tr.message;
}

}  // namespace
}  // namespace rockfit::core
