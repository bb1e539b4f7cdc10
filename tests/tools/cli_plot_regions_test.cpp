// `rockfit plot regions` (Fig. 11): a real PNG/SVG of the requested size, the cell counts in --json, clear errors.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "png_header.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

// The block of the paper's Fig. 11: m = 1 kg, b1 = 5 cm, b2 = 3 cm, h = 20 cm.
const std::vector<std::string> kFig11Block{"--b1", "0.05", "--b2", "0.03", "--h", "0.2", "--mass", "1"};

std::vector<std::string> Args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

TEST(CliPlotRegions, NoSpinFigureIsARealPngWithTheSignRuleRegions) {
  const ScratchDir dir("cli_plot_regions_nospin");
  const auto out = dir.path() / "fig11a.png";
  const CommandResult r = RunRockfit(Args({"plot", "regions"}, Args(kFig11Block, {"--points", "41", "-o", out.string(),
                                                                                 "--width", "800", "--height", "640", "--json"})));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PngHeader png = ReadPngHeader(out);
  ASSERT_TRUE(png.valid);
  EXPECT_EQ(png.width, 800u);
  EXPECT_EQ(png.height, 640u);
  EXPECT_GT(std::filesystem::file_size(out), 10000u);  // colours, curves and a key, not a blank canvas
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["kind"], "regions");
  EXPECT_EQ(json["pivot_edge"], "V1V2");
  EXPECT_EQ(json["tau_rule"], "no-spin");
  EXPECT_EQ(json["omega_minus"], nlohmann::json::array({0.0, 1.0, 0.0}));
  // 41 columns: 20 with λ_lat < 0 (V3), one at 0 (edge V3V4), 20 with λ_lat > 0 (V4).
  EXPECT_EQ(json["cells"], (nlohmann::json{{"V3", 20 * 41}, {"V3V4", 41}, {"V4", 20 * 41}}));
  EXPECT_GT(json["energy_zero_segments"].get<int>(), 10);
}

TEST(CliPlotRegions, FixedTauFigureShowsInfeasibleAndAmbiguousCellsAsSvg) {
  const ScratchDir dir("cli_plot_regions_tau");
  const auto out = dir.path() / "fig11b.svg";
  const CommandResult r = RunRockfit(
      Args({"plot", "regions"}, Args(kFig11Block, {"--tau", "1e-4", "--points", "41", "-o", out.string(), "--json"})));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(ReadWholeFile(out).find("<svg"), std::string::npos);
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["tau_rule"], "fixed");
  EXPECT_GT(json["cells"].value("infeasible", 0), 0);
  EXPECT_GT(json["cells"].value("ambiguous", 0), 0);
  EXPECT_GT(json["singular_segments"].get<int>(), 0);
}

TEST(CliPlotRegions, OtherPivotEdgeAndRangeChangeTheRegions) {
  const ScratchDir dir("cli_plot_regions_edge");
  const auto out = dir.path() / "edge41.png";
  // Pivot edge V4V1 (b = 1): λ_lat > 0 → V3, λ_lat < 0 → V2; the range excludes λ_lat = 0.
  const CommandResult r = RunRockfit(Args({"plot", "regions"}, Args(kFig11Block, {"--pivot-edge", "4,1", "--lat-range=0.5,1",
                                                                                 "--points", "11", "-o", out.string(), "--json"})));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(ReadPngHeader(out).valid);
  EXPECT_EQ(nlohmann::json::parse(r.out)["cells"], (nlohmann::json{{"V3", 121}}));
}

TEST(CliPlotRegions, BadArgumentsAreUsageErrorsAndWriteNothing) {
  const ScratchDir dir("cli_plot_regions_bad");
  const auto out = dir.path() / "bad.png";
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--pivot-edge", "1,3"},
                                                std::vector<std::string>{"--lat-range=2,-2"},
                                                std::vector<std::string>{"--points", "1"},
                                                std::vector<std::string>{"--omega-minus", "0,0,0"}}) {
    const CommandResult r = RunRockfit(Args({"plot", "regions"}, Args(kFig11Block, Args(extra, {"-o", out.string()}))));
    EXPECT_EQ(r.exit_code, 1) << extra.front() << ": " << r.err;
    EXPECT_FALSE(r.err.empty());
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  const CommandResult jpg = RunRockfit(Args({"plot", "regions"}, Args(kFig11Block, {"-o", (dir.path() / "x.jpg").string()})));
  EXPECT_EQ(jpg.exit_code, 1) << jpg.err;
}

TEST(CliPlotRegions, WithoutGnuplotTheMessageSaysHowToInstallIt) {
  const ScratchDir dir("cli_plot_regions_nognuplot");
  const auto out = dir.path() / "none.png";
  ::setenv("ROCKFIT_GNUPLOT", "/nonexistent/gnuplot", 1);
  const CommandResult r = RunRockfit(Args({"plot", "regions"}, Args(kFig11Block, {"--points", "11", "-o", out.string()})));
  ::unsetenv("ROCKFIT_GNUPLOT");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("apt-get install gnuplot-nox"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace rockfit::testing
