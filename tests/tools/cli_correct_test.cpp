// `rockfit correct` writes raw and corrected angles and the impacts, as HDF5 (checked with h5py) or CSV.
#include <fstream>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "python_h5py.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "synthetic_campaign.hpp"
#include "scratch_dir.hpp"

namespace rockfit::testing {
namespace {

std::string FirstLine(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(CliCorrect, WritesHdf5ThatH5pyReadsAndKeepsOtherTrials) {
  const ScratchDir dir("cli_correct");
  const auto trials = WriteSyntheticCampaign(dir.path(), {0.05}, 1);
  const auto out = dir / "corrected.h5";
  for (const auto& t : trials) {
    const CommandResult r = RunRockfit({"correct", t.file.string(), "-o", out.string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["trial"], t.id);
    EXPECT_GT(json["impacts"].get<int>(), 15);
  }
  // Both trials are in the file: the second run kept the first.
  EXPECT_EQ(io::ListTrialsHdf5(out), (std::vector<std::string>{"B1-A-1", "B1-B-1"}));
  ROCKFIT_REQUIRE_H5PY();
  const auto check = RunH5pyScript(R"(
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], 'r')
t = f['trials/B1-A-1']
n = t['time_s'].shape[0]
assert t['euler_zyx_raw_rad'].shape == (n, 3) and t['euler_zyx_corrected_rad'].shape == (n, 3)
assert t['euler_zyx_corrected_rad'].attrs['units'] == 'rad'
k = t['impacts/time_s'].shape[0]
assert k > 15 and t['impacts/sample_index'].shape == (k,)
# Corrected φ_y ≈ 0 at the impacts (within the noise), the raw one is not (drift).
idx = t['impacts/sample_index'][...]
assert np.max(np.abs(t['euler_zyx_corrected_rad'][idx, 1])) < 0.01
assert np.max(np.abs(t['euler_zyx_raw_rad'][idx, 1])) > 0.05
assert t['metrics'].attrs['avrf_status'] == 'no_block'
print('ok')
)", out);
  EXPECT_EQ(check.out, "ok\n");
}

TEST(CliCorrect, WritesCsvWithImpactsBeside) {
  const ScratchDir dir("cli_correct");
  const auto trials = WriteSyntheticCampaign(dir.path(), {0.05}, 1);
  const CommandResult r = RunRockfit({"correct", trials[0].file.string(), "-o", (dir / "c.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(FirstLine(dir / "c.csv"),
            "time_s,w_x_rad_s,w_y_rad_s,w_z_rad_s,phi_z_raw_rad,phi_y_raw_rad,phi_x_raw_rad,phi_z_corrected_rad,"
            "phi_y_corrected_rad,phi_x_corrected_rad,impact_y,anchor_x");
  EXPECT_EQ(FirstLine(dir / "c_impacts.csv"), "angle,time_s,sample_index,anchor_rad,source,omega_peak_rad_s");
  EXPECT_NE(r.out.find("written"), std::string::npos);
}

TEST(CliCorrect, UnknownOutputTypeIsAUsageErrorAndNothingIsWritten) {
  const ScratchDir dir("cli_correct");
  const auto trials = WriteSyntheticCampaign(dir.path(), {0.05}, 1);
  const CommandResult r = RunRockfit({"correct", trials[0].file.string(), "-o", (dir / "c.txt").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(".h5/.hdf5"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.txt"));
}

TEST(CliCorrect, RefusesToOverwriteAFileThatIsNotHdf5) {
  const ScratchDir dir("cli_correct");
  const auto trials = WriteSyntheticCampaign(dir.path(), {0.05}, 1);
  std::ofstream(dir / "notes.h5") << "precious\n";
  const CommandResult r = RunRockfit({"correct", trials[0].file.string(), "-o", (dir / "notes.h5").string()});
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("not an HDF5 file"), std::string::npos) << r.err;
  EXPECT_EQ(FirstLine(dir / "notes.h5"), "precious");
}

TEST(CliCorrect, NoImpactIsExitCodeThreeAndWritesNothing) {
  const ScratchDir dir("cli_correct");
  PlanarRockingSpec spec;
  spec.release_s = 100.0;
  const auto motion = SimulatePlanarRocking(PaperLikeBlock(), spec);
  WriteRecordingHdf5(dir / "still.h5", "still", MeasurePlanar(motion, spec.rate_hz, RealisticImu()).recording);
  const CommandResult r = RunRockfit({"correct", (dir / "still.h5").string(), "-o", (dir / "out.h5").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("no impact"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

}  // namespace
}  // namespace rockfit::testing
