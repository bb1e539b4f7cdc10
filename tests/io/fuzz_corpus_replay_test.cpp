// Replays the fuzz seed corpora (tests/fuzz/corpus/<target>/) and every fuzz finding kept as a regression file
// (tests/fuzz/regressions/<target>/) through the fuzz targets' own bodies, in the normal suite (and so under
// ASan + UBSan in CI): each input ends with a recording that keeps the reader's promises or with a documented
// error, never another exception, a crash or a sanitizer report.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "../fuzz/app_csv_target.hpp"
#include "../fuzz/generic_csv_target.hpp"
#include "../fuzz/ground_motion_target.hpp"
#include "../fuzz/manifest_target.hpp"
#include "../fuzz/option_grammars_target.hpp"
#include "../fuzz/rockfit_hdf5_target.hpp"
#include "../fuzz/ximu3_target.hpp"
#include "../fuzz/ximu_gui_target.hpp"
#include "cli_runner.hpp"
#include "test_paths.hpp"

namespace rockfit::testing {
namespace {

struct FuzzTarget {
  std::string name;
  std::function<void(std::string_view)> run;
};

const std::vector<FuzzTarget>& Targets() {
  static const std::vector<FuzzTarget> targets = {
      {"ximu_gui", fuzz::XimuGui},       {"ximu3", fuzz::Ximu3},       {"generic_csv", fuzz::GenericCsv},
      {"option_grammars", fuzz::OptionGrammars}, {"manifest", fuzz::Manifest}, {"rockfit_hdf5", fuzz::RockfitHdf5},
      {"ground_motion", fuzz::GroundMotion}, {"app_csv", fuzz::AppCsv}};
  return targets;
}

std::vector<std::filesystem::path> FilesIn(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzCorpusReplay, EverySeedEndsWithARecordingOrADocumentedError) {
  std::size_t seeds = 0;
  for (const auto& target : Targets()) {
    const auto files = FilesIn(SourceDir() / "tests" / "fuzz" / "corpus" / target.name);
    EXPECT_FALSE(files.empty()) << "no seed corpus for " << target.name;
    for (const auto& file : files) {
      SCOPED_TRACE(file.string());
      EXPECT_NO_THROW(target.run(ReadWholeFile(file)));
      ++seeds;
    }
  }
  std::printf("replayed %zu seeds\n", seeds);
}

TEST(FuzzCorpusReplay, EveryFixedFindingEndsWithARecordingOrADocumentedError) {
  for (const auto& target : Targets()) {
    for (const auto& file : FilesIn(SourceDir() / "tests" / "fuzz" / "regressions" / target.name)) {
      SCOPED_TRACE(file.string());
      EXPECT_NO_THROW(target.run(ReadWholeFile(file)));
    }
  }
}

}  // namespace
}  // namespace rockfit::testing
