// Fuzz target body: an x-IMU3 data-logger directory, read as `rockfit inspect DIR` reads it
// (io::LoadRecording on the directory). The main file of the input is Inertial.csv; "\n@@@ NAME\n"
// lines start EulerAngles.csv, Quaternion.csv, RotationMatrix.csv, LinearAcceleration.csv and
// EarthAcceleration.csv.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_input.hpp"
#include "recording_invariants.hpp"
#include "rockfit/io/load_recording.hpp"

namespace rockfit::fuzz {

namespace ximu3_detail {

constexpr std::array<std::string_view, 5> kOtherFiles = {"EulerAngles", "Quaternion", "RotationMatrix",
                                                         "LinearAcceleration", "EarthAcceleration"};

inline bool IsOtherFile(std::string_view name) {
  for (auto known : kOtherFiles)
    if (name == known) return true;
  return false;
}

}  // namespace ximu3_detail

inline void Ximu3(std::string_view input) {
  static const ScratchDir dir;
  dir.Clear();
  for (const auto& part : SplitFiles(input)) {
    if (part.name.empty())
      dir.Write("Inertial.csv", part.bytes);
    else if (ximu3_detail::IsOtherFile(part.name))
      dir.Write(part.name + ".csv", part.bytes);
  }
  ExpectDocumentedOutcome([&] {
    io::LoadOptions options;
    options.format = io::RecordingFormat::kXimu3;
    CheckRecording(io::LoadRecording(dir.path(), options));
  });
}

}  // namespace rockfit::fuzz
