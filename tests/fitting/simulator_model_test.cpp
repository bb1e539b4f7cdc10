// The simulator as a trajectory model: samples exactly where asked, failures as categories, never throws.
#include "rockfit/fitting/simulator_model.hpp"

#include <gtest/gtest.h>

namespace rockfit::fitting {
namespace {

const core::Block kBlock = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);

core::ModelParameters Params(double alpha, double lambda_lat) {
  core::ModelParameters p;
  p.alpha_rad = alpha;
  p.lambda = 0.8;
  p.lambda_lat = lambda_lat;
  p.lambda_lon = 0.6;
  return p;
}

TEST(SimulatorModel, SamplesAreTheSimulatorsOwnAtTheRequestedTimes) {
  const std::vector<double> times = {0.0, 0.013, 0.2, 0.39871, 0.5, 0.73};
  ModelOutput out;
  SimulatorModel(kBlock).Evaluate(Params(0.2, -2.0), times, &out);
  ASSERT_TRUE(out.ok()) << out.failure_detail;
  core::SimulationOptions direct = SimulatorModelOptions::DefaultFittingSimulation();
  direct.sample_times_s = times;
  direct.stop = core::StopCondition::kTMax;
  direct.t_max_s = times.back();
  const core::Trajectory reference = core::Simulate(kBlock, Params(0.2, -2.0), direct);
  ASSERT_EQ(out.w_B.size(), times.size());
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_EQ(out.w_B[k], reference.w_B[k]) << "sample " << k;
  EXPECT_EQ(out.w_B.front(), Eigen::Vector3d::Zero());  // released from rest
  ASSERT_FALSE(out.events.empty());
  EXPECT_EQ(out.events.front().kind, "facet");
  EXPECT_EQ(out.events.front().t_s, reference.impacts.front().t_s);
}

TEST(SimulatorModel, ATiltBeyondTheCriticalAngleIsAFailureNotAnException) {
  ModelOutput out;
  SimulatorModel(kBlock).Evaluate(Params(0.26, 0.0), {0.0, 0.1, 0.5}, &out);  // θ_c = atan(0.05/0.2) = 0.245
  EXPECT_FALSE(out.ok());
  EXPECT_EQ(out.failure, "overturned");
  EXPECT_TRUE(out.w_B.empty());
}

TEST(SimulatorModel, InvalidParametersAreAFailureNotAnException) {
  ModelOutput out;
  SimulatorModel(kBlock).Evaluate(Params(-0.1, 0.0), {0.0, 0.1}, &out);
  EXPECT_FALSE(out.ok());
  EXPECT_EQ(out.failure, "invalid parameters");
  EXPECT_FALSE(out.failure_detail.empty());
}

TEST(SimulationFailureCategory, NamesTheImpactStatusOrTheIntegrator) {
  EXPECT_EQ(SimulationFailureCategory("the edge impact on V3V4 at t = 0.5 s has no solution (map status singular)"),
            "edge impact singular");
  EXPECT_EQ(SimulationFailureCategory("the facet impact after rocking about V1V2 at t = 0.4 s has no solution (map "
                                      "status infeasible)"),
            "facet impact infeasible");
  EXPECT_EQ(SimulationFailureCategory("the integrator could not continue rocking about V3 at t = 1 s"), "integrator");
  EXPECT_EQ(SimulationFailureCategory("more than max_impacts = 10 impacts by t = 1 s"), "too many impacts");
}

}  // namespace
}  // namespace rockfit::fitting
