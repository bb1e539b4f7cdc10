// CLI tests of `rockfit impact edge|facet`: they run the real binary.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace rockfit::testing {
namespace {

// The block of the paper's Fig. 11.
const std::vector<std::string> kBlock = {"--b1", "0.05", "--b2", "0.03", "--h", "0.2", "--mass", "1"};

std::vector<std::string> Args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.begin() + 2, kBlock.begin(), kBlock.end());
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

void ExpectKeys(const nlohmann::json& j, const std::vector<std::string>& keys) {
  for (const auto& key : keys) EXPECT_TRUE(j.contains(key)) << "missing key " << key << " in " << j.dump();
}

TEST(CliImpact, FacetJsonHasTheDocumentedKeysAndTheNoSpinOutcome) {
  const CommandResult r = RunRockfit(Args({"impact", "facet"}, {"--omega-minus", "0,1,0", "--lambda-lat", "0.3",
                                                                 "--lambda-lon", "0.8", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ExpectKeys(j, {"kind", "status", "omega_plus", "omega_plus_body", "tau", "contact_after", "delta_energy",
                 "energy_before", "candidates", "within_bounds", "energy_nonincreasing", "contact_before", "tau_rule"});
  EXPECT_EQ(j["kind"], "facet");
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["contact_before"], "V1V2");
  EXPECT_EQ(j["contact_after"], "V4");  // λ_lat > 0 → V_{b+2} (docs/design.md §3 erratum)
  EXPECT_EQ(j["tau_rule"], "no-spin");
  EXPECT_EQ(j["omega_plus"][2].get<double>(), 0.0);  // (24)
  EXPECT_TRUE(j["within_bounds"].get<bool>());
  EXPECT_TRUE(j["energy_nonincreasing"].get<bool>());
  EXPECT_LT(j["delta_energy"].get<double>(), 0.0);
  ASSERT_EQ(j["candidates"].size(), 4u);
  for (const auto& c : j["candidates"]) ExpectKeys(c, {"contact", "feasible", "omega_plus"});
  EXPECT_TRUE(j["candidates"][3]["feasible"].get<bool>());
  EXPECT_FALSE(j["candidates"][2]["feasible"].get<bool>());
}

TEST(CliImpact, FacetPivotEdgeInEitherOrderIsTheSameEdge) {
  const std::vector<std::string> tail = {"--omega-minus", "0,1,0", "--lambda-lat", "-0.4", "--json"};
  const CommandResult a = RunRockfit(Args({"impact", "facet"}, [&] { auto t = tail; t.insert(t.end(), {"--pivot-edge", "1,2"}); return t; }()));
  const CommandResult b = RunRockfit(Args({"impact", "facet"}, [&] { auto t = tail; t.insert(t.end(), {"--pivot-edge", "2,1"}); return t; }()));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_EQ(nlohmann::json::parse(a.out)["contact_after"], "V3");
}

TEST(CliImpact, FacetWithFixedTauWithoutASingleFeasibleVertexPrintsTheStatusAndExitsWithThree) {
  // τ = 1e-4 N·m·s on the block of Fig. 11: (λ_lat, λ_lon) = (−1, −1.6) has no feasible vertex, (0.8, −1.8) has two.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--lambda-lat", "-1", "--lambda-lon", "-1.6"}, "infeasible"},
      {{"--lambda-lat", "0.8", "--lambda-lon", "-1.8"}, "ambiguous"}};
  for (const auto& [params, status] : cases) {
    std::vector<std::string> tail = {"--omega-minus", "0,1,0", "--tau", "1e-4", "--json"};
    tail.insert(tail.end(), params.begin(), params.end());
    const CommandResult r = RunRockfit(Args({"impact", "facet"}, tail));
    EXPECT_EQ(r.exit_code, 3) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["status"], status);
    EXPECT_TRUE(j["omega_plus"].is_null());
    EXPECT_TRUE(j["contact_after"].is_null());
    EXPECT_EQ(j["tau"].get<double>(), 1e-4);
    ASSERT_EQ(j["candidates"].size(), 4u);
    int feasible = 0;
    for (const auto& c : j["candidates"]) feasible += c["feasible"].get<bool>() ? 1 : 0;
    EXPECT_EQ(feasible, status == "infeasible" ? 0 : 2);
    EXPECT_NE(r.err.find(status), std::string::npos) << r.err;
  }
}

TEST(CliImpact, EdgeJsonHasTheDocumentedKeysAndSingularLambdas) {
  const CommandResult r = RunRockfit(Args({"impact", "edge"}, {"--pivot", "3", "--landing", "4", "--tilt", "0.05",
                                                                "--omega-minus", "0.5,-0.3,0.1", "--lambda", "0.6", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ExpectKeys(j, {"kind", "status", "omega_plus", "omega_plus_body", "tau", "contact_after", "delta_energy",
                 "energy_before", "singular_lambdas", "within_bounds", "energy_nonincreasing"});
  EXPECT_EQ(j["kind"], "edge");
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["contact_before"], "V3");
  EXPECT_EQ(j["tau"].get<double>(), 0.0);
  EXPECT_FALSE(j["singular_lambdas"].empty());
  // ω⁺ in B is ω⁺ in W rotated by R_WBᵀ: same length.
  double norm_w = 0.0, norm_b = 0.0;
  for (int i = 0; i < 3; ++i) {
    norm_w += std::pow(j["omega_plus"][i].get<double>(), 2);
    norm_b += std::pow(j["omega_plus_body"][i].get<double>(), 2);
  }
  EXPECT_NEAR(norm_w, norm_b, 1e-14);
}

TEST(CliImpact, EdgeAtASingularLambdaReportsTheStatusAndExitsWithThree) {
  const CommandResult roots = RunRockfit(Args({"impact", "edge"}, {"--pivot", "1", "--landing", "2", "--omega-minus",
                                                                    "0.2,-1,0", "--tilt", "0.1", "--json"}));
  ASSERT_EQ(roots.exit_code, 0) << roots.err;
  const auto singular = nlohmann::json::parse(roots.out)["singular_lambdas"];
  ASSERT_FALSE(singular.empty());
  const CommandResult r = RunRockfit(Args({"impact", "edge"}, {"--pivot", "1", "--landing", "2", "--omega-minus", "0.2,-1,0",
                                                                "--tilt", "0.1", "--lambda", singular[0].dump(), "--json"}));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["status"], "singular");
  EXPECT_TRUE(j["omega_plus"].is_null());
  EXPECT_NE(r.err.find("singular"), std::string::npos);
}

TEST(CliImpact, HumanReadableTableNamesStatusAndContact) {
  const CommandResult r = RunRockfit(Args({"impact", "facet"}, {"--omega-minus", "0,1,0", "--lambda-lon", "0.8"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("status          ok"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("contact after   V3V4"), std::string::npos) << r.out;  // λ_lat = 0: edge contact
}

struct BadArgument {
  std::vector<std::string> args;
  std::string named;  // the message must name this
};

TEST(CliImpact, BadArgumentsExitWithOneAndNameTheArgument) {
  const std::vector<BadArgument> cases = {
      {Args({"impact", "edge"}, {"--pivot", "1", "--landing", "3", "--omega-minus", "1,0,0"}), "--landing"},
      {Args({"impact", "edge"}, {"--pivot", "5", "--landing", "1", "--omega-minus", "1,0,0"}), "--pivot"},
      {Args({"impact", "edge"}, {"--pivot", "1", "--landing", "2", "--omega-minus", "1,0,0", "--tilt", "-0.1"}), "--tilt"},
      {Args({"impact", "edge"}, {"--pivot", "1", "--landing", "2", "--omega-minus", "1,0,0", "--lambda", "nan"}), "--lambda"},
      {Args({"impact", "edge"}, {"--pivot", "1", "--landing", "2", "--omega-minus", "1,0"}), "--omega-minus"},
      {Args({"impact", "edge"}, {"--pivot", "1", "--landing", "2"}), "--omega-minus"},
      {Args({"impact", "facet"}, {"--omega-minus", "0,1,0", "--pivot-edge", "1,3"}), "--pivot-edge"},
      {Args({"impact", "facet"}, {"--omega-minus", "0,1,0", "--pivot-edge", "0,1"}), "--pivot-edge"},
      {Args({"impact", "facet"}, {"--omega-minus", "0,1,x"}), "--omega-minus"},
      {Args({"impact", "facet"}, {"--omega-minus", "0,1,0", "--tau", "inf"}), "--tau"},
      {{"impact", "facet", "--b1", "0.05", "--h", "0.2", "--mass", "1", "--omega-minus", "0,1,0"}, "--b2"},
  };
  for (const BadArgument& c : cases) {
    const CommandResult r = RunRockfit(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.named << ": " << r.err;
    EXPECT_NE(r.err.find(c.named), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(CliImpact, HelpDocumentsTheExitCodeForNumericalStatuses) {
  for (const char* kind : {"edge", "facet"}) {
    const CommandResult r = RunRockfit({"impact", kind, "--help"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("3 the map has no single answer"), std::string::npos) << r.out;
  }
}

}  // namespace
}  // namespace rockfit::testing
