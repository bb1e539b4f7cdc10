// A small synthetic campaign on disk for CLI tests: blocks of the paper's size with different depths b2,
// positions A and B, a few trials each (3D rocking with known angles, realistic IMU errors), every trial stored
// as rockfit HDF5, and a manifest naming them.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "rocking_signals.hpp"
#include "rockfit/io/campaign_hdf5.hpp"
#include "rockfit/io/hdf5_transaction.hpp"

namespace rockfit::testing {

struct SyntheticTrial {
  std::string id;
  std::string block_id;
  std::string position;
  double b2_m = 0.0;
  double lambda = 0.0;    // Chatzis' λ of the motion
  double r = 0.0;         // r_Cha(λ): what the AVRF should give
  double epsilon = 0.0;   // φx = ε(t)·φy amplitude factor
  std::filesystem::path file;
};

// Writes one recording as rockfit HDF5 with the trial's raw data (metrics computed without a block).
inline void WriteRecordingHdf5(const std::filesystem::path& path, const std::string& trial_id, const io::Recording& rec) {
  io::hdf5::Transaction tx(path, {"/trials/" + trial_id});
  io::WriteFileAttributes(tx.Root(), "test");
  const io::MetricsOptions options;
  io::WriteTrialHdf5(tx.Root(), trial_id, {}, rec, io::ComputeTrialMetrics(rec, std::nullopt, options), options);
  tx.Commit();
}

// `blocks` depths b2 [m]; `trials_per_group` trials per (block, position).
inline std::vector<SyntheticTrial> WriteSyntheticCampaign(const std::filesystem::path& dir,
                                                         const std::vector<double>& blocks_b2_m = {0.03, 0.05, 0.08},
                                                         int trials_per_group = 3) {
  std::filesystem::create_directories(dir / "recordings");
  std::vector<SyntheticTrial> trials;
  std::string manifest = "# synthetic campaign written by the tests\n";
  std::uint32_t seed = 1;
  for (std::size_t b = 0; b < blocks_b2_m.size(); ++b) {
    const double b2 = blocks_b2_m[b];
    const std::string block_id = fmt::format("B{}", b + 1);
    manifest += fmt::format("\n[[blocks]]\nid = \"{}\"\nb1 = 0.05\nb2 = {}\nh = 0.2\ndensity = 2692\n", block_id, b2);
    const core::Block block = PaperLikeBlock(b2);
    for (const char* position : {"A", "B"}) {
      for (int k = 0; k < trials_per_group; ++k) {
        SyntheticTrial t;
        t.block_id = block_id;
        t.position = position;
        t.b2_m = b2;
        t.id = fmt::format("{}-{}-{}", block_id, position, k + 1);
        // AVRF and OPMF depend on b2 and the position (as in the paper's Fig. 6), with trial-to-trial scatter.
        t.lambda = 0.3 + 4.0 * b2 + (position[0] == 'B' ? 0.25 : 0.0) + 0.05 * (k - 1);
        t.r = ChatzisAvrfAboutY(block, t.lambda);
        t.epsilon = 0.004 / b2 * (position[0] == 'B' ? 0.6 : 1.0) * (1.0 + 0.1 * (k - 1));
        PlanarRockingSpec spec;
        spec.lambda = t.lambda;
        spec.alpha_rad = 0.20 - 0.01 * k;
        spec.duration_s = 8.0;
        const auto motion = SimulatePlanarRocking(block, spec);
        const auto measured = Measure3d(motion, spec.rate_hz, t.epsilon, RealisticImu(seed++));
        t.file = dir / "recordings" / (t.id + ".h5");
        WriteRecordingHdf5(t.file, t.id, measured.recording);
        manifest += fmt::format("\n[[trials]]\nid = \"{}\"\nblock = \"{}\"\nposition = \"{}\"\nfiles = \"recordings/{}.h5\"\n"
                                "format = \"rockfit-hdf5\"\n",
                                t.id, block_id, position, t.id);
        trials.push_back(t);
      }
    }
  }
  std::ofstream(dir / "campaign.toml") << manifest;
  return trials;
}

}  // namespace rockfit::testing
