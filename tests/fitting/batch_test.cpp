// The batch: failures isolated, every finished trial stored, resume skips exactly what is done.
#include "rockfit/fitting/batch.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/fitting/fit_store.hpp"
#include "rockfit/io/hdf5_file.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/synth_recording.hpp"

namespace rockfit::fitting {
namespace {

namespace fs = std::filesystem;

// A manifest with two synthetic x-IMU trials and one whose files are missing.
class BatchTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("rockfit_batch_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "raw");
    const core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);
    const double truths[2][4] = {{0.19, 0.9, -1.8, 0.7}, {0.2, 1.2, 2.0, 0.5}};
    for (int i = 0; i < 2; ++i) {
      core::ModelParameters p;
      p.alpha_rad = truths[i][0];
      p.lambda = truths[i][1];
      p.lambda_lat = truths[i][2];
      p.lambda_lon = truths[i][3];
      io::SynthRecordingOptions o;
      o.t0_s = 1.0;
      o.duration_s = 2.5;
      o.measurement.seed = static_cast<std::uint64_t>(40 + i);
      o.files.rotation_matrix_file = false;
      const std::string prefix = (dir_ / "raw" / ("T" + std::to_string(i + 1))).string();
      io::WriteSynthRecording(prefix, block, p, o, io::Synthesize(block, p, o));
    }
    std::ofstream(dir_ / "manifest.toml") << "[[blocks]]\nid = \"B1\"\nb1 = 0.05\nb2 = 0.04\nh = 0.2\ndensity = 2692\n\n"
                                             "[[trials]]\nid = \"T1\"\nblock = \"B1\"\nposition = \"A\"\nfiles = \"raw/T1\"\n\n"
                                             "[[trials]]\nid = \"T2\"\nblock = \"B1\"\nposition = \"B\"\nfiles = \"raw/T2\"\n\n"
                                             "[[trials]]\nid = \"T3\"\nblock = \"B1\"\nposition = \"A\"\nfiles = \"raw/missing\"\n";
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static io::Recording Load(const io::TrialSpec& trial) { return io::LoadRecording(trial.files); }

  // Quick fits: the batch machinery is under test here, not the fit (no global stage, a small budget).
  static BatchOptions Quick() {
    BatchOptions o;
    o.trial.fit.global.enabled = false;
    o.trial.fit.method = FitMethod::kNelderMead;
    o.trial.fit.nelder_mead.max_evaluations = 40;
    o.jobs = 2;
    return o;
  }

  static fs::path dir_;
};
fs::path BatchTest::dir_;

TEST_F(BatchTest, FitsEveryTrialIsolatesFailuresAndLeavesNoSideDirectory) {
  const io::Manifest manifest = io::ReadManifest(dir_ / "manifest.toml");
  const fs::path out = dir_ / "all.h5";
  std::size_t calls = 0;
  const BatchReport r = RunBatch(manifest, out, Quick(), Load, [&](const BatchTrialResult&, std::size_t finished, std::size_t total) {
    ++calls;
    EXPECT_LE(finished, total);
  });
  EXPECT_EQ(calls, 3u);
  EXPECT_EQ(r.ok, 2u);
  EXPECT_EQ(r.failed, 1u);
  EXPECT_EQ(r.trials[2].trial_id, "T3");
  EXPECT_EQ(r.trials[2].status, "failed");
  EXPECT_NE(r.trials[2].message.find("raw/missing"), std::string::npos) << r.trials[2].message;
  EXPECT_FALSE(fs::exists(PartsDirectory(out)));
  const io::hdf5::File file = io::hdf5::File::Open(out);
  EXPECT_EQ(ListFitsHdf5(file.Root()), (std::vector<std::string>{"T1", "T2", "T3"}));
  EXPECT_EQ(ReadFitHdf5(file.Root(), "T3").status, "failed");
  EXPECT_TRUE(file.Root().IsGroup("fit_summary/groups"));
  EXPECT_TRUE(file.Root().IsGroup("blocks/B1"));
}

TEST_F(BatchTest, ResumeSkipsTrialsFittedWithTheSameSettingsAndRefitsWhenTheyChange) {
  const io::Manifest manifest = io::ReadManifest(dir_ / "manifest.toml");
  const fs::path out = dir_ / "resume.h5";
  RunBatch(manifest, out, Quick(), Load);
  BatchOptions resume = Quick();
  resume.resume = true;
  const BatchReport again = RunBatch(manifest, out, resume, Load);
  EXPECT_EQ(again.skipped, 2u);
  EXPECT_EQ(again.failed, 1u);  // failures are retried
  EXPECT_EQ(again.trials[0].status, "skipped");

  BatchOptions changed = resume;
  changed.trial.fit.nelder_mead.max_evaluations = 41;
  const BatchReport refit = RunBatch(manifest, out, changed, Load);
  EXPECT_EQ(refit.skipped, 0u);
  EXPECT_EQ(refit.ok, 2u);
}

TEST_F(BatchTest, ResumeAfterAKillMergesTheFinishedPartsWithoutFittingThemAgain) {
  const io::Manifest manifest = io::ReadManifest(dir_ / "manifest.toml");
  const fs::path out = dir_ / "killed.h5";
  // The state a kill leaves after T1 finished: T1's part in the side directory, no output file yet.
  BatchOptions only_t1 = Quick();
  only_t1.only_trials = {"T1"};
  const fs::path t1_alone = dir_ / "t1_alone.h5";
  const BatchReport first = RunBatch(manifest, t1_alone, only_t1, Load);
  fs::create_directories(PartsDirectory(out));
  fs::rename(t1_alone, PartsDirectory(out) / "T1.h5");
  ASSERT_FALSE(fs::exists(out));

  BatchOptions resume = Quick();
  resume.resume = true;
  const BatchReport r = RunBatch(manifest, out, resume, Load);
  EXPECT_EQ(r.trials[0].status, "skipped");
  EXPECT_EQ(r.trials[1].status, "ok");
  const io::hdf5::File file = io::hdf5::File::Open(out);
  EXPECT_EQ(ReadFitHdf5(file.Root(), "T1").epsilon_rad_s, first.trials[0].epsilon_rad_s);
  EXPECT_EQ(ReadFitHdf5(file.Root(), "T2").status, "ok");
  EXPECT_FALSE(fs::exists(PartsDirectory(out)));
}

TEST_F(BatchTest, AnUnknownTrialIdIsBadInput) {
  const io::Manifest manifest = io::ReadManifest(dir_ / "manifest.toml");
  BatchOptions o = Quick();
  o.only_trials = {"T9"};
  EXPECT_THROW(RunBatch(manifest, dir_ / "x.h5", o, Load), BadInput);
}

}  // namespace
}  // namespace rockfit::fitting
