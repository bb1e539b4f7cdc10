// Names, option validation and parameter validation of the simulator.
#include <cmath>
#include <limits>
#include <utility>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core {
namespace {

TEST(SimulationNames, ModesStopConditionsAndEndReasonsHaveTheirDocumentedNames) {
  Mode m;
  m.kind = ModeKind::kEdge;
  m.contact = Contact::Edge(3, 4);
  EXPECT_EQ(m.ToString(), "V3V4");
  m.kind = ModeKind::kVertex;
  m.contact = Contact::Vertex(2);
  EXPECT_EQ(m.ToString(), "V2");
  m.kind = ModeKind::kRest;
  EXPECT_EQ(m.ToString(), "rest");
  EXPECT_STREQ(ToString(StopCondition::kPhase4), "phase4");
  EXPECT_STREQ(ToString(StopCondition::kTMax), "t_max");
  EXPECT_STREQ(ToString(EndReason::kOverturned), "overturned");
  EXPECT_STREQ(ToString(EndReason::kFailed), "failed");
}

TEST(SimulationNames, StopConditionsReadBackFromTheirNames) {
  for (StopCondition stop : {StopCondition::kPhase4, StopCondition::kRest, StopCondition::kOverturned,
                             StopCondition::kTMax}) {
    StopCondition parsed = stop == StopCondition::kTMax ? StopCondition::kPhase4 : StopCondition::kTMax;
    ASSERT_TRUE(FromString(ToString(stop), &parsed)) << ToString(stop);
    EXPECT_EQ(parsed, stop);
  }
  StopCondition unchanged = StopCondition::kRest;
  for (const char* text : {"", "tmax", "Phase4", "failed", "lift_off"}) {
    EXPECT_FALSE(FromString(text, &unchanged)) << "'" << text << "'";
    EXPECT_EQ(unchanged, StopCondition::kRest);
  }
}

TEST(SimulationNames, ImpactKindsReadBackFromTheirNames) {
  const std::pair<ImpactKind, const char*> kinds[] = {{ImpactKind::kFacet, "facet"}, {ImpactKind::kEdge, "edge"},
                                                      {ImpactKind::kZeno, "zeno"},   {ImpactKind::kRest, "rest"},
                                                      {ImpactKind::kUplift, "uplift"}};
  for (const auto& [kind, name] : kinds) {
    EXPECT_STREQ(ToString(kind), name);
    ImpactKind parsed = kind == ImpactKind::kFacet ? ImpactKind::kEdge : ImpactKind::kFacet;
    ASSERT_TRUE(FromString(name, &parsed)) << name;
    EXPECT_EQ(parsed, kind) << name;
  }
  ImpactKind unchanged = ImpactKind::kZeno;
  for (const char* text : {"", "Facet", "facet ", "impact", "V1V2"}) {
    EXPECT_FALSE(FromString(text, &unchanged)) << "'" << text << "'";
    EXPECT_EQ(unchanged, ImpactKind::kZeno);
  }
}

TEST(SimulationNames, FailureReasonsHaveTheirDocumentedNames) {
  EXPECT_STREQ(ToString(FailureReason::kNone), "none");
  EXPECT_STREQ(ToString(FailureReason::kEdgeImpact), "edge_impact");
  EXPECT_STREQ(ToString(FailureReason::kFacetImpact), "facet_impact");
  EXPECT_STREQ(ToString(FailureReason::kIntegratorStep), "integrator_step");
  EXPECT_STREQ(ToString(FailureReason::kImpactCascade), "impact_cascade");
  EXPECT_STREQ(ToString(FailureReason::kMaxImpacts), "max_impacts");
  EXPECT_STREQ(ToString(FailureReason::kEnergyBlowUp), "energy_blow_up");
}

// Expects Validate() to throw InvalidArgument whose message contains `word`.
void ExpectRejected(const SimulationOptions& options, const std::string& word) {
  try {
    options.Validate();
    ADD_FAILURE() << "accepted, expected a complaint about " << word;
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

TEST(SimulationOptions, RejectsEachBadFieldNamingIt) {
  EXPECT_NO_THROW(SimulationOptions{}.Validate());
  SimulationOptions o;
  o.rate_hz = -1.0;
  ExpectRejected(o, "rate");
  o = {};
  o.t_max_s = std::nan("");
  ExpectRejected(o, "t_max");
  o = {};
  o.t_max_s = 1e6;
  o.rate_hz = 1e6;
  ExpectRejected(o, "samples");
  o = {};
  o.release_edge_first = 1;
  o.release_edge_second = 3;
  ExpectRejected(o, "release edge");
  o = {};
  o.zeno_dt_s = -1.0;
  ExpectRejected(o, "zeno_dt");
  o = {};
  o.rest_energy_height_m = -1.0;
  ExpectRejected(o, "rest_energy_height");
  o = {};
  o.rel_tol = 1e-20;
  ExpectRejected(o, "rel_tol");
  o = {};
  o.event_time_tol_s = 0.0;
  ExpectRejected(o, "event_time_tol");
  o = {};
  o.max_step_s = 0.0;
  ExpectRejected(o, "max_step");
  o = {};
  o.max_impacts = 0;
  ExpectRejected(o, "max_impacts");
  o = {};
  o.sample_times_s = {0.0, std::nan("")};
  ExpectRejected(o, "sample time");
  o.sample_times_s = {std::numeric_limits<double>::infinity(), 1.0};
  ExpectRejected(o, "sample time");
  o.sample_times_s = {0.0, 0.5, -std::numeric_limits<double>::infinity()};
  ExpectRejected(o, "sample time");
  o.sample_times_s = {0.0, 0.5, 0.25, 1.0};
  ExpectRejected(o, "ascending order; time 2");
  o.sample_times_s = {-0.5, 0.0, 0.0, 1.0};  // repeated times are allowed, negative ones too
  EXPECT_NO_THROW(o.Validate());
  o = {};
  InitialState s;
  s.contact = Contact{};
  o.initial_state = s;
  ExpectRejected(o, "initial contact");
  s.contact = Contact::Vertex(1);
  s.q_WB = Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0);
  o.initial_state = s;
  ExpectRejected(o, "unit quaternion");
}

TEST(ModelParameters, RejectsNonFiniteValuesAndANonPositiveTilt) {
  EXPECT_NO_THROW(ModelParameters{}.Validate());
  ModelParameters p;
  p.alpha_rad = 0.0;
  EXPECT_THROW(p.Validate(), InvalidArgument);
  EXPECT_NO_THROW(p.Validate(false));  // a run from a given state has no release tilt
  p = {};
  p.lambda_lon = std::numeric_limits<double>::infinity();
  EXPECT_THROW(p.Validate(), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::core
