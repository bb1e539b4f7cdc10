// `rockfit report` (tools/src/cmd_report.cpp, report_builder.cpp) on the bundled sample campaign: the summary of
// all its trials with the fits of only two of them (a partial batch file), the predictive check of those two, a
// fragility study of one of its blocks and one of a block it does not have. What the page must say about each
// gap, that it needs no network, that its element ids are unique, and that without gnuplot it keeps every table
// and names every missing figure. The page in a real browser: tests/tools/report_browser_test.py.
#include <regex>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "build_type.hpp"
#include "cli_runner.hpp"
#include "scratch_dir.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

const char* kFittedTrials[] = {"block1-A-1", "block1-A-2"};
constexpr std::size_t kSampleTrials = 16;  // trials of data-samples/manifest.toml

// The sample manifest with only the blocks and the trials `keep`, its recordings named by absolute path.
std::string SubManifest(const std::vector<std::string>& keep) {
  const std::string text = ReadWholeFile(SourceDir() / "data-samples" / "manifest.toml");
  const std::size_t first_trial = text.find("[[trials]]");
  std::string out = text.substr(0, first_trial);
  for (std::size_t at = first_trial; at != std::string::npos;) {
    const std::size_t next = text.find("[[trials]]", at + 1);
    std::string trial = text.substr(at, next == std::string::npos ? std::string::npos : next - at);
    for (const std::string& id : keep) {
      if (trial.find("id = \"" + id + "\"") != std::string::npos) {
        out += std::regex_replace(trial, std::regex("files = \"recordings/"),
                                  "files = \"" + (SourceDir() / "data-samples" / "recordings").string() + "/");
      }
    }
    at = next;
  }
  return out;
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

class CliReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("cli_report");
    const std::string manifest = (SourceDir() / "data-samples" / "manifest.toml").string();
    const std::string sub = dir_->Write("two.toml", SubManifest({kFittedTrials[0], kFittedTrials[1]})).string();
    const CommandResult s = RunRockfit({"summary", manifest, "-o", Path("campaign.h5")});
    ASSERT_EQ(s.exit_code, 0) << s.err;
    if (!kOptimisedBuild) return;  // the fits below: their tests skip themselves (ROCKFIT_REQUIRE_OPTIMISED_BUILD)
    const CommandResult b = RunRockfit({"batch", sub, "-o", Path("fits.h5"), "--intervals", "fast", "-j", "2"});
    ASSERT_EQ(b.exit_code, 0) << b.err;
    const CommandResult v = RunRockfit({"validate", sub, "--fits", Path("fits.h5"), "-o", Path("validation.h5"),
                                        "--intervals", "fast", "-j", "2"});
    ASSERT_EQ(v.exit_code, 0) << v.err;
    // A study of a block of the campaign (block1, by the manifest) and one of a block of its own size ("block").
    const std::vector<std::string> study = {"--lambda", "1.9", "--lambda-sd", "0.05", "--lambda-lat", "-4",
                                            "--lambda-lat-sd", "0.2", "--lambda-lon", "1.2", "--lambda-lon-sd", "0.05",
                                            "--synthetic-records", "1", "--synthetic-duration", "1.5", "--tail", "1",
                                            "--pga", "0.3,0.6", "--samples", "2", "--seed", "3"};
    std::vector<std::string> own = {"fragility", "--manifest", manifest, "--block", "block1", "-o", Path("fragility.h5")};
    own.insert(own.end(), study.begin(), study.end());
    const CommandResult f = RunRockfit(own);
    ASSERT_EQ(f.exit_code, 0) << f.err;
    std::vector<std::string> other = {"fragility", "--b1", "0.05", "--b2", "0.04", "--h", "0.3", "--density", "2692",
                                      "-o", Path("other_fragility.h5")};
    other.insert(other.end(), study.begin(), study.end());
    const CommandResult o = RunRockfit(other);
    ASSERT_EQ(o.exit_code, 0) << o.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Path(const std::string& name) { return (dir_->path() / name).string(); }

  // `rockfit report` with the summary, the partial fits and `more`; its --json and the page.
  static std::pair<nlohmann::json, std::string> Report(const std::string& name, std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"report", Path("campaign.h5"), "--fits", Path("fits.h5"), "-o", Path(name), "--json"};
    args.insert(args.end(), more.begin(), more.end());
    const CommandResult r = RunRockfit(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return {nlohmann::json::parse(r.out), ReadWholeFile(Path(name))};
  }

  static ScratchDir* dir_;
};
ScratchDir* CliReport::dir_ = nullptr;

TEST_F(CliReport, ABatchFileWithoutSomeTrialsGivesEveryTrialASectionAndNamesEachMissingFit) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const auto [json, html] = Report("partial.html");
  EXPECT_EQ(json["trials"], kSampleTrials);
  EXPECT_EQ(json["trials_fitted"], 2);
  EXPECT_EQ(Count(html, "<section class=\"trial\""), kSampleTrials);
  std::set<std::string> named;
  for (const auto& gap : json["gaps"]) {
    const std::string where = gap["where"];
    if (where.rfind("trial ", 0) == 0 && gap["what"].get<std::string>().find("has no fit") != std::string::npos) {
      named.insert(where.substr(6));
    }
  }
  EXPECT_EQ(named.size(), kSampleTrials - 2) << json["gaps"].dump();
  EXPECT_FALSE(named.count(kFittedTrials[0]));
  EXPECT_NE(html.find("What this report could not show"), std::string::npos);
  EXPECT_NE(html.find("block4-B-2</strong> has no fit in"), std::string::npos);
  EXPECT_EQ(Count(html, "No fit of this trial in the inputs"), kSampleTrials - 2);
  // The two fitted trials have their parameter tables with both intervals.
  EXPECT_EQ(Count(html, "with 68 % and 95 % intervals</caption>"), 2u);
  // Both samples rest before the release and after the rocking: their α is compared with the tilt at rest.
  EXPECT_EQ(Count(html, "<dt>α against the tilt at rest</dt><dd>fitted α "), 2u);
}

TEST_F(CliReport, ModelErrorAndPredictiveCheckSectionsAppearOnlyWhenTheirOutputsExist) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const auto [without, html_without] = Report("no_validation.html");
  EXPECT_EQ(html_without.find("id=\"validation\""), std::string::npos);
  EXPECT_NE(html_without.find("id=\"model-error\""), std::string::npos) << "the batch fits measure the noise floor";
  const auto [with, html_with] = Report("validation.html", {"--validation", Path("validation.h5")});
  EXPECT_NE(html_with.find("id=\"validation\""), std::string::npos);
  EXPECT_NE(html_with.find("<caption>Predictive check per trial</caption>"), std::string::npos);
  // Without fits there is nothing to split into noise and model error.
  const CommandResult r = RunRockfit({"report", Path("campaign.h5"), "-o", Path("summary_only.html"), "--no-figures"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string summary_only = ReadWholeFile(Path("summary_only.html"));
  EXPECT_EQ(summary_only.find("id=\"model-error\""), std::string::npos);
  EXPECT_NE(summary_only.find("no fits file was given"), std::string::npos);
}

TEST_F(CliReport, AFragilityStudyOfABlockTheCampaignLacksIsLeftOutAndNamed) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  const auto [json, html] = Report("fragility.html", {"--fragility", Path("fragility.h5"), "--fragility",
                                                      Path("other_fragility.h5"), "--no-figures"});
  EXPECT_NE(html.find("<h3>Fragility of block1</h3>"), std::string::npos);
  EXPECT_EQ(html.find("<h3>Fragility of block</h3>"), std::string::npos);
  bool named = false;
  for (const auto& gap : json["gaps"]) {
    named = named || gap["what"].get<std::string>().find("block 'block', which is not a block of this campaign") !=
                         std::string::npos;
  }
  EXPECT_TRUE(named) << json["gaps"].dump();
  EXPECT_NE(html.find("which is not a block of this campaign"), std::string::npos);
}

TEST_F(CliReport, WithoutGnuplotEveryTableRendersAndEveryFigureIsNamedMissing) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  ::setenv("ROCKFIT_GNUPLOT", "/nonexistent/gnuplot", 1);
  const auto [json, html] = Report("no_gnuplot.html");
  ::unsetenv("ROCKFIT_GNUPLOT");
  EXPECT_EQ(json["figures"], 0);
  // Summary, parameter ranges, the angles of all 16 trials and the fits of the two fitted ones.
  EXPECT_EQ(json["figures_missing"].size(), 2 + kSampleTrials + 2) << json.dump();
  EXPECT_EQ(Count(html, "<figure class=\"figure figure-missing\""), json["figures_missing"].size());
  EXPECT_EQ(Count(html, "Figure missing: gnuplot was not found"), json["figures_missing"].size());
  EXPECT_EQ(Count(html, "<svg"), 0u);
  EXPECT_GE(Count(html, "<table"), 2 + 2u) << "overview tables and the fitted trials' parameters";
}

TEST_F(CliReport, ThePageIsSelfContainedAndItsElementIdsAreUnique) {
  ROCKFIT_REQUIRE_OPTIMISED_BUILD();
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  const auto [json, html] = Report("figures.html", {"--fragility", Path("fragility.h5")});
  EXPECT_EQ(json["figures_missing"].size(), 0u) << json.dump();
  EXPECT_EQ(json["figures"], 2 + kSampleTrials + 2 + 1);
  // Nothing loaded from elsewhere: no external script, style sheet, image or font.
  EXPECT_EQ(html.find(" src="), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  EXPECT_EQ(std::regex_search(html, std::regex(R"(url\((?!#))")), false);
  EXPECT_EQ(std::regex_search(html, std::regex(R"(href=["'](?!#)[a-z]+:)")), false) << "links only within the page";
  // Ids unique although every gnuplot picture defines the same ones.
  std::set<std::string> ids;
  const std::regex id(R"(\sid=["']([^"']+)["'])");
  std::size_t total = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), id); it != std::sregex_iterator(); ++it, ++total) {
    ids.insert((*it)[1]);
  }
  EXPECT_GT(total, 100u);
  EXPECT_EQ(ids.size(), total);
}

TEST_F(CliReport, AnUnreadableSummaryIsBadInputNamingTheFile) {
  const std::string bad = dir_->Write("not_hdf5.h5", "this is not HDF5\n").string();
  const CommandResult r = RunRockfit({"report", bad, "-o", Path("bad.html")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("not_hdf5.h5"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(Path("bad.html")));
  if (!kOptimisedBuild) return;  // no fits file
  // The fits file as the summary: a rockfit file without /summary.
  const CommandResult wrong = RunRockfit({"report", Path("fits.h5"), "-o", Path("bad.html")});
  EXPECT_EQ(wrong.exit_code, 2) << wrong.err;
  EXPECT_NE(wrong.err.find("fits.h5"), std::string::npos) << wrong.err;
}

TEST_F(CliReport, AFitsFileThatIsNotHdf5IsNamedOnThePage) {
  const std::string bad = dir_->Write("broken_fits.h5", "garbage").string();
  const CommandResult r = RunRockfit({"report", Path("campaign.h5"), "--fits", bad, "-o", Path("broken.html"),
                                      "--no-figures"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = ReadWholeFile(Path("broken.html"));
  EXPECT_NE(html.find("fits file " + bad + "</strong> cannot be read"), std::string::npos);
  EXPECT_EQ(Count(html, "<section class=\"trial\""), kSampleTrials);
  EXPECT_NE(r.err.find("broken_fits.h5"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rockfit::testing
