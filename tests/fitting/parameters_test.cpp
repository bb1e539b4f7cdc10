// Parameter sets: the default bound sets of docs/design.md §7 and validation messages.
#include "rockfit/fitting/parameters.hpp"

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

std::string ValidationMessage(const ParameterSet& set) {
  try {
    set.Validate();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(ParameterSet, EmpiricalBoundsAreWiderThanTheTheoreticalOnes) {
  const ParameterSet emp = ParameterSet::Defaults(BoundsSet::kEmpirical);
  const ParameterSet theo = ParameterSet::Defaults(BoundsSet::kTheoretical);
  for (ParameterId id : {ParameterId::kLambda, ParameterId::kLambdaLat, ParameterId::kLambdaLon}) {
    EXPECT_LT(emp[id].lower, theo[id].lower) << Name(id);
    EXPECT_GT(emp[id].upper, theo[id].upper) << Name(id);
  }
  // (25) with the energy sign λ ≥ 0 (26), and (27) with λ_lon ≥ 0.
  EXPECT_EQ(theo[ParameterId::kLambda].lower, 0.0);
  EXPECT_EQ(theo[ParameterId::kLambda].upper, 1.0);
  EXPECT_EQ(theo[ParameterId::kLambdaLat].lower, -1.0);
  EXPECT_EQ(theo[ParameterId::kLambdaLat].upper, 1.0);
  EXPECT_EQ(theo[ParameterId::kLambdaLon].lower, 0.0);
  EXPECT_EQ(theo[ParameterId::kLambdaLon].upper, 1.0);
  // The paper's fitted values (Fig. 14: λ = 2.185, λ_lat = −2.032) lie inside the empirical set.
  EXPECT_LE(2.185, emp[ParameterId::kLambda].upper);
  EXPECT_GE(-2.032, emp[ParameterId::kLambdaLat].lower);
  EXPECT_NO_THROW(emp.Validate());
  EXPECT_NO_THROW(theo.Validate());
}

TEST(ParameterSet, DefaultsFreeTheFiveParametersOfThePaperAndFixTauEdgeAtZero) {
  const ParameterSet set = ParameterSet::Defaults();
  const std::vector<ParameterId> free = set.FreeIds();
  ASSERT_EQ(free.size(), 5u);
  EXPECT_TRUE(set[ParameterId::kTauEdge].fixed);
  EXPECT_EQ(set.value(ParameterId::kTauEdge), 0.0);
}

TEST(ParameterSet, ValidationNamesTheParameterAndTheProblem) {
  ParameterSet set = ParameterSet::Defaults();
  set[ParameterId::kLambdaLon].value = 3.0;
  EXPECT_NE(ValidationMessage(set).find("lambda_lon"), std::string::npos);
  EXPECT_NE(ValidationMessage(set).find("outside its bounds"), std::string::npos);

  set = ParameterSet::Defaults();
  set[ParameterId::kAlpha].lower = 0.5;
  EXPECT_NE(ValidationMessage(set).find("alpha: lower bound"), std::string::npos);

  set = ParameterSet::Defaults();
  set[ParameterId::kLambda].upper = std::numeric_limits<double>::infinity();
  EXPECT_NE(ValidationMessage(set).find("lambda: the bounds must be finite"), std::string::npos);

  set = ParameterSet::Defaults();
  set[ParameterId::kLambdaLat].lower = set[ParameterId::kLambdaLat].upper = 0.0;
  EXPECT_NE(ValidationMessage(set).find("no room"), std::string::npos);
  set[ParameterId::kLambdaLat].fixed = true;  // a fixed parameter may have a degenerate range
  EXPECT_EQ(ValidationMessage(set), "");
}

TEST(ParameterSet, NamesRoundTripAndUnknownNamesListTheValidOnes) {
  for (ParameterId id : kAllParameters) EXPECT_EQ(ParseParameterName(Name(id)), id);
  try {
    ParseParameterName("lambda_x");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("lambda_lat"), std::string::npos);
  }
  EXPECT_THROW(ParseBoundsSet("wide"), InvalidArgument);
}

TEST(ParameterSet, ToModelCopiesEveryModelParameter) {
  ParameterSet set = ParameterSet::Defaults();
  set[ParameterId::kAlpha].value = 0.15;
  set[ParameterId::kLambda].value = 2.0;
  set[ParameterId::kLambdaLat].value = -1.5;
  set[ParameterId::kLambdaLon].value = 0.4;
  set[ParameterId::kTauEdge].value = 0.01;
  set.set_facet_tau_rule(core::FacetTauRule::kFixed);
  const core::ModelParameters m = set.ToModel();
  EXPECT_EQ(m.alpha_rad, 0.15);
  EXPECT_EQ(m.lambda, 2.0);
  EXPECT_EQ(m.lambda_lat, -1.5);
  EXPECT_EQ(m.lambda_lon, 0.4);
  EXPECT_EQ(m.tau_edge, 0.01);
  EXPECT_EQ(m.facet_tau_rule, core::FacetTauRule::kFixed);
}

}  // namespace
}  // namespace rockfit::fitting
