// The files of one original x-IMU GUI export: "<prefix>_<Type>.csv", one file per packet type
// (docs/file-formats.md §1.1, §1.7). Files are grouped by their known type suffix, never by
// the text before the first '_' (base names may contain '_'); names are compared case-insensitively.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rockfit::io {

struct XimuGuiFileSet {
  std::filesystem::path prefix;  // directory / base name, e.g. "data/LoggedData"
  std::optional<std::filesystem::path> cal_inertial;  // _CalInertialAndMag.csv (v12+) or _CalInertialMagnetic.csv (v7–v11)
  std::optional<std::filesystem::path> raw_inertial;  // _RawInertialAndMag.csv / _RawInertialMagnetic.csv (lsb)
  std::optional<std::filesystem::path> euler_angles;
  std::optional<std::filesystem::path> quaternion;
  std::optional<std::filesystem::path> rotation_matrix;
  std::optional<std::filesystem::path> registers;
  std::optional<std::filesystem::path> date_time;
  std::vector<std::filesystem::path> all;  // every "<prefix>_<known type>.csv" found

  // Looks for the files of `prefix` in its directory. Never throws; absent files stay empty.
  static XimuGuiFileSet Find(const std::filesystem::path& prefix);
};

// The type suffixes the x-IMU GUI writes, all versions ("CalInertialAndMag", "EulerAngles", …).
const std::vector<std::string>& XimuGuiFileTypes();

// "LoggedData_EulerAngles.csv" → "LoggedData"; std::nullopt unless the name is
// "<base>_<known type>.csv" (case-insensitive) with a non-empty base.
std::optional<std::string> XimuGuiBaseName(std::string_view file_name);

// The bases in `directory` that have a calibrated inertial file, sorted.
std::vector<std::string> XimuGuiBasesIn(const std::filesystem::path& directory);

}  // namespace rockfit::io
