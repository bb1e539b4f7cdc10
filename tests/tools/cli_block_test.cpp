// CLI tests run the real rockfit binary.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "scratch_dir.hpp"

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

TEST(CliBlock, TakesTheBlockFromAManifest) {
  const ScratchDir dir("cli_block");
  const auto manifest = dir.Write("m.toml", "[[blocks]]\nid = \"B3\"\nb1 = 0.05\nb2 = 0.03\nh = 0.2\nmass = 2.5\n");
  const CommandResult r = RunRockfit({"block", "--manifest", manifest.string(), "--block", "B3", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(r.out)["mass"].get<double>(), 2.5);
  const CommandResult unknown = RunRockfit({"block", "--manifest", manifest.string(), "--block", "B4"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("no block 'B4'; known blocks: B3"), std::string::npos) << unknown.err;
  const CommandResult half = RunRockfit({"block", "--manifest", manifest.string()});
  EXPECT_EQ(half.exit_code, 1);
  EXPECT_NE(half.err.find("--block"), std::string::npos) << half.err;
}

}  // namespace
}  // namespace rockfit::testing
