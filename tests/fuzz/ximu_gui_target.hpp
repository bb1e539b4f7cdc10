// Fuzz target body: the original x-IMU GUI CSV set, read as `rockfit inspect PREFIX` reads it
// (io::LoadRecording on <dir>/LoggedData). The main file of the input is
// LoggedData_CalInertialAndMag.csv; "\n@@@ Registers\n", "\n@@@ DateTime\n", "\n@@@ EulerAngles\n",
// "\n@@@ Quaternion\n" and "\n@@@ RotationMatrix\n" lines start the other files of the set. Without a
// Registers file the target passes --rate 256, as a user must.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input.hpp"
#include "recording_invariants.hpp"
#include "rockfit/io/load_recording.hpp"

namespace rockfit::fuzz {

namespace ximu_gui_detail {

constexpr std::array<std::string_view, 5> kOtherFiles = {"Registers", "DateTime", "EulerAngles", "Quaternion",
                                                         "RotationMatrix"};

inline bool IsOtherFile(std::string_view name) {
  for (auto known : kOtherFiles)
    if (name == known) return true;
  return false;
}

}  // namespace ximu_gui_detail

inline void XimuGui(std::string_view input) {
  static const ScratchDir dir;
  dir.Clear();
  bool registers = false;
  for (const auto& part : SplitFiles(input)) {
    if (part.name.empty())
      dir.Write("LoggedData_CalInertialAndMag.csv", part.bytes);
    else if (ximu_gui_detail::IsOtherFile(part.name))
      dir.Write("LoggedData_" + part.name + ".csv", part.bytes);
    registers = registers || part.name == "Registers";
  }
  ExpectDocumentedOutcome([&] {
    io::LoadOptions options;
    options.format = io::RecordingFormat::kXimuGui;
    if (!registers) options.rate_hz = 256.0;
    CheckRecording(io::LoadRecording(dir.path() / "LoggedData", options));
  });
}

}  // namespace rockfit::fuzz
