// Paths the tests need: the source tree, the shared real-IMU data (may be absent), the rockfit binary.
#pragma once

#include <filesystem>
#include <string>

namespace rockfit::testing {

inline std::filesystem::path SourceDir() { return ROCKFIT_SOURCE_DIR; }
inline std::filesystem::path RockfitBinary() { return ROCKFIT_BINARY; }
// ../shared/real-imu beside the checkout; empty path when it is not there (a user's fresh clone).
inline std::filesystem::path RealImuDir() {
  const std::filesystem::path dir = std::filesystem::path(ROCKFIT_SHARED_DIR) / "real-imu";
  return std::filesystem::is_directory(dir) ? dir : std::filesystem::path();
}

// ../shared/ground-motions beside the checkout (real PEER AT2 records); empty path when it is not there.
inline std::filesystem::path GroundMotionsDir() {
  const std::filesystem::path dir = std::filesystem::path(ROCKFIT_SHARED_DIR) / "ground-motions";
  return std::filesystem::is_directory(dir) ? dir : std::filesystem::path();
}

}  // namespace rockfit::testing

// Skips the current test when the shared real recordings are absent.
#define ROCKFIT_REQUIRE_REAL_IMU()                                                        \
  do {                                                                                    \
    if (rockfit::testing::RealImuDir().empty()) GTEST_SKIP() << "../shared/real-imu not present"; \
  } while (0)
