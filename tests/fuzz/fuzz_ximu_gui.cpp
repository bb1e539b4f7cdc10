// libFuzzer target: the original x-IMU GUI CSV set, read as `rockfit inspect PREFIX` reads it
// (io::LoadRecording on <dir>/LoggedData). The main file of the input is
// LoggedData_CalInertialAndMag.csv; "\n@@@ Registers\n", "\n@@@ DateTime\n", "\n@@@ EulerAngles\n",
// "\n@@@ Quaternion\n" and "\n@@@ RotationMatrix\n" lines start the other files of the set. Without a
// Registers file the target passes --rate 256, as a user must.
#include <cstddef>
#include <cstdint>

#include "ximu_gui_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::XimuGui(rockfit::fuzz::AsText(data, size));
  return 0;
}
