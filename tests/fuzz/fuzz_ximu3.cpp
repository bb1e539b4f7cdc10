// libFuzzer target: an x-IMU3 data-logger directory, read as `rockfit inspect DIR` reads it
// (io::LoadRecording on the directory). The main file of the input is Inertial.csv; "\n@@@ NAME\n"
// lines start EulerAngles.csv, Quaternion.csv, RotationMatrix.csv, LinearAcceleration.csv and
// EarthAcceleration.csv.
#include <cstddef>
#include <cstdint>

#include "ximu3_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::Ximu3(rockfit::fuzz::AsText(data, size));
  return 0;
}
