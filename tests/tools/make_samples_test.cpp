// tools/make_samples.sh regenerates the bundled sample campaign bit for bit (two trials and the manifest here;
// .ci/run regenerates all of it).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli_runner.hpp"

namespace rockfit::testing {
namespace {

namespace fs = std::filesystem;

TEST(MakeSamples, RegeneratesTrialsAndManifestBitForBit) {
  const fs::path samples = SourceDir() / "data-samples";
  ASSERT_TRUE(fs::is_regular_file(samples / "manifest.toml")) << samples;
  const fs::path out = fs::temp_directory_path() / ("rockfit_make_samples_" + std::to_string(::getpid()));
  fs::remove_all(out);
  // One trial of each mounting, one of them with the half-rate orientation stream.
  const std::string command = ShellQuote((SourceDir() / "tools" / "make_samples.sh").string()) + " " +
                              ShellQuote(RockfitBinary().string()) + " " + ShellQuote(out.string()) +
                              " block1-A-1 block4-B-2 >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(ReadWholeFile(out / "manifest.toml"), ReadWholeFile(samples / "manifest.toml"));
  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(out / "recordings")) {
    const fs::path committed = samples / "recordings" / entry.path().filename();
    ASSERT_TRUE(fs::is_regular_file(committed)) << committed;
    EXPECT_TRUE(ReadWholeFile(entry.path()) == ReadWholeFile(committed))
        << entry.path().filename() << " differs from the committed sample; if the simulator or the measurement "
        << "model changed on purpose, regenerate with tools/make_samples.sh and commit";
    ++compared;
  }
  EXPECT_EQ(compared, 2u * 7u);  // 6 CSV files (no rotation matrix) and the truth per trial
  for (const char* record : {"cp-seed1-0.30g.AT2", "cp-seed2-0.45g.AT2"}) {
    EXPECT_TRUE(ReadWholeFile(out / "ground-motions" / record) == ReadWholeFile(samples / "ground-motions" / record))
        << record << " differs from the committed generated ground motion";
  }
  fs::remove_all(out);
}

}  // namespace
TEST(MakeSamples, RegeneratesTheCsvSamplesBitForBit) {
  const fs::path samples = SourceDir() / "data-samples" / "csv";
  if (!fs::is_regular_file("/usr/bin/python3")) GTEST_SKIP() << "tools/make_csv_samples.py needs /usr/bin/python3";
  const fs::path out = fs::temp_directory_path() / ("rockfit_make_csv_samples_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string command = "/usr/bin/python3 " + ShellQuote((SourceDir() / "tools" / "make_csv_samples.py").string()) +
                              " " + ShellQuote(out.string()) + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  for (const char* file : {"phyphox/Gyroscope.csv", "sensor-logger/Gyroscope.csv", "sensor-logger/TotalAcceleration.csv",
                           "arduino/log.csv", "quoted/trial.csv"}) {
    EXPECT_TRUE(ReadWholeFile(out / file) == ReadWholeFile(samples / file))
        << file << " differs from the committed sample; regenerate with tools/make_csv_samples.py and commit";
  }
  fs::remove_all(out);
}

}  // namespace rockfit::testing
