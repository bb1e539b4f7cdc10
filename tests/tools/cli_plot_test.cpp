// `rockfit plot euler|summary`: real PNG/SVG pictures of the requested size; a clear message without gnuplot.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "png_header.hpp"
#include "synthetic_campaign.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

class CliPlot : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("cli_plot");
    trials_ = new std::vector<SyntheticTrial>(WriteSyntheticCampaign(dir_->path(), {0.03, 0.05, 0.08}, 2));
  }
  static void TearDownTestSuite() {
    delete trials_;
    delete dir_;
  }
  static std::string Manifest() { return (dir_->path() / "campaign.toml").string(); }
  static ScratchDir* dir_;
  static std::vector<SyntheticTrial>* trials_;
};
ScratchDir* CliPlot::dir_ = nullptr;
std::vector<SyntheticTrial>* CliPlot::trials_ = nullptr;

TEST_F(CliPlot, EulerFigureIsARealPngOfTheRequestedSize) {
  const auto out = dir_->path() / "euler.png";
  const CommandResult r = RunRockfit({"plot", "euler", Manifest(), "--trial", "B1-A-1", "-o", out.string(), "--width",
                                      "1000", "--height", "900", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PngHeader png = ReadPngHeader(out);
  ASSERT_TRUE(png.valid);
  EXPECT_EQ(png.width, 1000u);
  EXPECT_EQ(png.height, 900u);
  // Three panels of curves are far more than a blank canvas.
  EXPECT_GT(std::filesystem::file_size(out), 30000u);
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["kind"], "euler");
  EXPECT_GT(json["impacts"].get<int>(), 15);
}

TEST_F(CliPlot, SummaryFigureFromTheManifestAndFromHdf5) {
  const auto png = dir_->path() / "summary.png";
  const CommandResult from_manifest = RunRockfit({"plot", "summary", Manifest(), "-o", png.string(), "--width", "1200",
                                                  "--height", "520"});
  ASSERT_EQ(from_manifest.exit_code, 0) << from_manifest.err;
  const PngHeader size = ReadPngHeader(png);
  ASSERT_TRUE(size.valid);
  EXPECT_EQ(size.width, 1200u);
  EXPECT_EQ(size.height, 520u);
  EXPECT_GT(std::filesystem::file_size(png), 20000u);

  const auto h5 = dir_->path() / "summary.h5";
  ASSERT_EQ(RunRockfit({"summary", Manifest(), "-o", h5.string()}).exit_code, 0);
  const auto svg = dir_->path() / "summary.svg";
  const CommandResult from_hdf5 = RunRockfit({"plot", "summary", h5.string(), "-o", svg.string()});
  ASSERT_EQ(from_hdf5.exit_code, 0) << from_hdf5.err;
  const std::string text = ReadWholeFile(svg);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("position A"), std::string::npos);
  EXPECT_NE(text.find("position B"), std::string::npos);
}

TEST_F(CliPlot, EulerFigureFromAStoredTrial) {
  const auto h5 = dir_->path() / "corrected.h5";
  ASSERT_EQ(RunRockfit({"correct", Manifest(), "--trial", "B2-B-1", "-o", h5.string()}).exit_code, 0);
  const auto out = dir_->path() / "stored.png";
  const CommandResult r = RunRockfit({"plot", "euler", h5.string(), "-o", out.string(), "--from", "0", "--to", "4"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(ReadPngHeader(out).valid);
}

TEST_F(CliPlot, WithoutGnuplotTheMessageSaysHowToInstallIt) {
  ::setenv("ROCKFIT_GNUPLOT", "/nonexistent/gnuplot", 1);
  const auto out = dir_->path() / "none.png";
  const CommandResult r = RunRockfit({"plot", "summary", Manifest(), "-o", out.string()});
  ::unsetenv("ROCKFIT_GNUPLOT");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("apt-get install gnuplot-nox"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A plot killed by a signal leaves its scratch directory in TMPDIR; the next plot removes those of processes
// that no longer run and leaves the others alone.
TEST_F(CliPlot, ScratchDirectoriesOfDeadProcessesAreRemovedByTheNextPlot) {
  const ScratchDir tmp("cli_plot_tmpdir");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);  // `child` is a pid of no running process now
  const auto orphan = tmp.path() / ("rockfit-plot-" + std::to_string(child) + "-0");
  const auto alive = tmp.path() / ("rockfit-plot-" + std::to_string(::getpid()) + "-7");
  std::filesystem::create_directories(orphan);
  std::filesystem::create_directories(alive);
  std::ofstream(orphan / "figure.gp") << "plot x\n";
  const char* old_tmpdir = std::getenv("TMPDIR");
  const std::string saved = old_tmpdir ? old_tmpdir : "";
  ::setenv("TMPDIR", tmp.path().c_str(), 1);
  const CommandResult r =
      RunRockfit({"plot", "summary", Manifest(), "-o", (dir_->path() / "after-kill.png").string()});
  if (old_tmpdir) ::setenv("TMPDIR", saved.c_str(), 1); else ::unsetenv("TMPDIR");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(orphan));
  EXPECT_TRUE(std::filesystem::exists(alive));
  // Its own scratch directory is gone too.
  std::size_t left = 0;
  for (const auto& entry : std::filesystem::directory_iterator(tmp.path())) left += entry.path() != alive ? 1 : 0;
  EXPECT_EQ(left, 0u);
}

TEST_F(CliPlot, WrongPictureExtensionIsAUsageError) {
  const CommandResult r = RunRockfit({"plot", "summary", Manifest(), "-o", (dir_->path() / "x.jpg").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(".png or .svg"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rockfit::testing
