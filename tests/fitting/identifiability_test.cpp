// "Not identifiable": parameters without influence on (28) are found by their sensitivity, with the reason.
#include "rockfit/fitting/identifiability.hpp"

#include <gtest/gtest.h>

#include "analytic_trial.hpp"

namespace rockfit::fitting {
namespace {

using testing::MakeAnalyticTrial;

TEST(Identifiability, LambdaWithoutEdgeImpactsIsNotIdentifiableAndSaysWhy) {
  // λ_lat = 0: no lateral motion, hence no edge impact in the window (the analytic model's structure).
  const auto trial = MakeAnalyticTrial(0.2, 0.8, 0.0, 0.6);
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  const IdentifiabilityReport r = CheckIdentifiability(objective, trial.truth, IdentifiabilityOptions{});
  EXPECT_EQ(r.edge_impacts_in_window, 0);
  EXPECT_FALSE(r.identifiable[static_cast<std::size_t>(ParameterId::kLambda)]);
  EXPECT_EQ(r.max_abs_change_rad_s[static_cast<std::size_t>(ParameterId::kLambda)], 0.0);
  EXPECT_NE(r.reason[static_cast<std::size_t>(ParameterId::kLambda)].find("no edge impact"), std::string::npos);
  for (ParameterId id : {ParameterId::kT0, ParameterId::kAlpha, ParameterId::kLambdaLat, ParameterId::kLambdaLon}) {
    EXPECT_TRUE(r.identifiable[static_cast<std::size_t>(id)]) << Name(id);
  }
}

TEST(Identifiability, EveryParameterActsWhenEdgeImpactsHappen) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical));
  const IdentifiabilityReport r = CheckIdentifiability(objective, trial.truth, IdentifiabilityOptions{});
  EXPECT_GT(r.edge_impacts_in_window, 0);
  EXPECT_GT(r.facet_impacts_in_window, 0);
  for (ParameterId id : objective.free_ids()) EXPECT_TRUE(r.identifiable[static_cast<std::size_t>(id)]) << Name(id);
  EXPECT_TRUE(r.identifiable[static_cast<std::size_t>(ParameterId::kTauEdge)]);  // fixed counts as identifiable
}

TEST(Identifiability, ImpactParametersAreNotIdentifiableInAWindowEndingBeforeTheFirstImpact) {
  const auto trial = MakeAnalyticTrial(0.2, 0.8, -2.0, 0.6);
  const Objective objective = trial.MakeObjective(trial.Bounded(BoundsSet::kEmpirical)).WithWindowEnd(0.8);
  const IdentifiabilityReport r = CheckIdentifiability(objective, trial.truth, IdentifiabilityOptions{});
  EXPECT_EQ(r.facet_impacts_in_window, 0);
  EXPECT_FALSE(r.identifiable[static_cast<std::size_t>(ParameterId::kLambdaLat)]);
  EXPECT_FALSE(r.identifiable[static_cast<std::size_t>(ParameterId::kLambdaLon)]);
  EXPECT_NE(r.reason[static_cast<std::size_t>(ParameterId::kLambdaLon)].find("no facet impact"), std::string::npos);
  EXPECT_TRUE(r.identifiable[static_cast<std::size_t>(ParameterId::kAlpha)]);
}

}  // namespace
}  // namespace rockfit::fitting
