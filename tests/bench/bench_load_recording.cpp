// Loading speed of a recording (docs/design.md §12: a 45 s, 256 Hz file set should load in well under a
// second). The files are written once to a temporary directory, as the x-IMU GUI writes them.
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <benchmark/benchmark.h>

#include "../support/imu_test_files.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/mounting_estimate.hpp"

namespace {

// A 45 s x-IMU GUI set at 256 Hz (11 520 inertial rows, Euler and quaternion rows after each).
const std::filesystem::path& GuiSet() {
  static const std::filesystem::path prefix = [] {
    const auto dir = std::filesystem::temp_directory_path() / ("rockfit_bench_load_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const rockfit::testing::GuiSpin spin = rockfit::testing::MakeGuiSpin(45 * 256, 256.0, 30.0);
    std::ofstream(dir / "B_CalInertialAndMag.csv") << spin.inertial;
    std::ofstream(dir / "B_EulerAngles.csv") << spin.euler;
    std::ofstream(dir / "B_Quaternion.csv") << spin.quaternion;
    std::ofstream(dir / "B_DateTime.csv") << spin.date_time;
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(std::filesystem::temp_directory_path() /
                                      ("rockfit_bench_load_" + std::to_string(::getpid())),
                                  ec);
    });
    return dir / "B";
  }();
  return prefix;
}

void BM_LoadXimuGuiSet(benchmark::State& state, rockfit::io::OrientationChoice orientation) {
  rockfit::io::LoadOptions options;
  options.rate_hz = 256.0;
  options.orientation = orientation;
  options.mounting = rockfit::io::Mounting::Parse("x,-y,-z");
  std::size_t samples = 0;
  for (auto _ : state) {
    const rockfit::io::Recording recording = rockfit::io::LoadRecording(GuiSet(), options);
    samples = recording.size();
    benchmark::DoNotOptimize(recording.euler_zyx.data());
  }
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK_CAPTURE(BM_LoadXimuGuiSet, euler_45s_256Hz, rockfit::io::OrientationChoice::kEulerAngles)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LoadXimuGuiSet, quaternion_45s_256Hz, rockfit::io::OrientationChoice::kQuaternion)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LoadXimuGuiSet, gyro_only_45s_256Hz, rockfit::io::OrientationChoice::kNone)->Unit(benchmark::kMillisecond);

// The mounting estimate alone (run by every load of an IMU recording with an accelerometer) on a bundled 6 s
// synthetic trial: rest, release, rocking, rest.
void BM_EstimateMounting(benchmark::State& state) {
  const rockfit::io::Recording recording =
      rockfit::io::LoadRecording(std::filesystem::path(ROCKFIT_SOURCE_DIR) / "data-samples/recordings/block2-A-1");
  for (auto _ : state) {
    const rockfit::io::MountingEstimate e = rockfit::io::EstimateMounting(recording);
    benchmark::DoNotOptimize(e.check.angles_deg.data());
  }
  state.counters["samples"] = static_cast<double>(recording.size());
}

BENCHMARK(BM_EstimateMounting)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
