#include "load/format_detection.hpp"

#include <algorithm>
#include <system_error>
#include <vector>

#include "text/header_matching.hpp"
#include "text/input_problem.hpp"
#include "ximu/ximu_gui_file_set.hpp"

namespace rockfit::io {
namespace {

namespace fs = std::filesystem;

std::string LowerExtension(const fs::path& path) { return NormalizeHeader(path.extension().string()); }

bool HasInertialCsv(const fs::path& directory) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    if (HeaderEquals(entry.path().filename().string(), "Inertial.csv") && entry.is_regular_file(ec)) return true;
  }
  return false;
}

// The x-IMU3 logger writes these; a file with such a name beside Inertial.csv belongs to it.
bool IsXimu3MessageFile(const fs::path& file) {
  static const std::vector<std::string> kNames = {
      "Inertial.csv", "Magnetometer.csv", "HighGAccelerometer.csv", "Quaternion.csv", "RotationMatrix.csv",
      "EulerAngles.csv", "LinearAcceleration.csv", "EarthAcceleration.csv", "AhrsStatus.csv", "Temperature.csv",
      "Battery.csv", "Rssi.csv", "Notification.csv", "Error.csv", "SerialAccessory.csv", "Ltc.csv", "Sync.csv",
      "Button.csv", "Command.json"};
  const std::string name = file.filename().string();
  return std::any_of(kNames.begin(), kNames.end(), [&](const std::string& known) { return HeaderEquals(name, known); });
}

fs::path Parent(const fs::path& path) { return path.has_parent_path() ? path.parent_path() : fs::path("."); }

std::string JoinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "'" : ", '") + name + "'";
  return text;
}

DetectedSource FromDirectory(const fs::path& directory) {
  if (HasInertialCsv(directory)) return {RecordingFormat::kXimu3, directory};
  const std::vector<std::string> bases = XimuGuiBasesIn(directory);
  if (bases.size() == 1) return {RecordingFormat::kXimuGui, directory / bases.front()};
  if (bases.size() > 1) {
    ThrowBadInput({{directory.string()}, "", "several x-IMU recordings: " + JoinNames(bases),
                   "one recording", "Give the prefix of one of them, e.g. " + (directory / bases.front()).string() + "."});
  }
  std::vector<fs::path> devices;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    if (entry.is_directory(ec) && HasInertialCsv(entry.path())) devices.push_back(entry.path());
  }
  std::sort(devices.begin(), devices.end());
  if (devices.size() == 1) return {RecordingFormat::kXimu3, devices.front()};
  if (devices.size() > 1) {
    std::vector<std::string> names;
    for (const fs::path& device : devices) names.push_back(device.filename().string());
    ThrowBadInput({{directory.string()}, "", "x-IMU3 logs of several devices: " + JoinNames(names), "one device",
                   "Give the directory of one device, e.g. '" + devices.front().string() + "'."});
  }
  ThrowBadInput({{directory.string()}, "", "a directory without a recording",
                 "an x-IMU GUI file set (<prefix>_CalInertialAndMag.csv) or an x-IMU3 log (Inertial.csv)",
                 "Give the recording's prefix, directory or CSV file."});
}

}  // namespace

DetectedSource DetectRecordingSource(const fs::path& path, RecordingFormat forced) {
  std::error_code ec;
  const bool exists = fs::exists(path, ec);
  const bool is_directory = exists && fs::is_directory(path, ec);
  const std::string name = path.filename().string();
  const std::optional<std::string> gui_base = XimuGuiBaseName(name);

  switch (forced) {
    case RecordingFormat::kAuto:
      break;
    case RecordingFormat::kXimuGui:
      if (is_directory) return FromDirectory(path);
      return {forced, gui_base ? Parent(path) / *gui_base : path};
    case RecordingFormat::kXimu3:
      return {forced, is_directory ? path : Parent(path)};
    case RecordingFormat::kGenericCsv:
    case RecordingFormat::kRockfitHdf5:
      return {forced, path};
  }

  if (is_directory) return FromDirectory(path);
  if (exists) {
    const std::string extension = LowerExtension(path);
    if (extension == ".h5" || extension == ".hdf5") return {RecordingFormat::kRockfitHdf5, path};
    if (extension == ".bin") {
      ThrowBadInput({{path.string()}, "", "an x-IMU SD-card binary (.BIN)", "CSV files",
                     "Convert it with the x-IMU GUI (SD Card tab, \"Convert\"), then give the CSV prefix."});
    }
    if (extension == ".ximu3") {
      ThrowBadInput({{path.string()}, "", "an x-IMU3 binary log (.ximu3)", "CSV files",
                     "Convert it to CSV with the x-IMU3 GUI's file converter, then give the directory it writes."});
    }
    if (gui_base) return {RecordingFormat::kXimuGui, Parent(path) / *gui_base};
    if (IsXimu3MessageFile(path) && HasInertialCsv(Parent(path))) return {RecordingFormat::kXimu3, Parent(path)};
    return {RecordingFormat::kGenericCsv, path};
  }
  // Not a file: an x-IMU GUI prefix "dir/base"?
  if (!XimuGuiFileSet::Find(path).all.empty()) return {RecordingFormat::kXimuGui, path};
  ThrowBadInput({{path.string()}, "", "no such file, directory or x-IMU prefix",
                 "a recording: an x-IMU prefix (dir/LoggedData), one of its CSV files, an x-IMU3 directory or a CSV file",
                 "Check the path (it is relative to the current directory, or to the manifest)."});
}

}  // namespace rockfit::io
