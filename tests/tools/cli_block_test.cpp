// CLI tests run the real rockfit binary.
#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace rockfit::testing {
namespace {

TEST(CliBlock, PrintsMassAsJson) {
  const CommandResult r = RunRockfit({"block", "--b1", "0.05", "--b2", "0.03", "--h", "0.2", "--mass", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(json["mass"].get<double>(), 1.0);
}

TEST(CliBlock, MissingSizeIsAUsageErrorNamingTheOption) {
  const CommandResult r = RunRockfit({"block", "--b1", "0.05", "--h", "0.2", "--mass", "1"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--b2"), std::string::npos) << r.err;
}

TEST(CliBlock, NegativeSizeIsRejectedWithExitCodeOne) {
  const CommandResult r = RunRockfit({"block", "--b1", "-0.05", "--b2", "0.03", "--h", "0.2", "--mass", "1"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("b1"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rockfit::testing
