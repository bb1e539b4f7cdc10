#include "ximu/ximu_gui_file_set.hpp"

#include <algorithm>
#include <set>
#include <system_error>

#include "text/header_matching.hpp"

namespace rockfit::io {
namespace {

bool EndsWithNoCase(std::string_view text, std::string_view suffix) {
  if (text.size() < suffix.size()) return false;
  return NormalizeHeader(text.substr(text.size() - suffix.size())) == NormalizeHeader(suffix);
}

// The x-IMU GUI type of a file name of `base`, or "" when it is not one.
std::string TypeOf(std::string_view file_name, std::string_view base) {
  if (file_name.size() <= base.size() + 1) return {};
  if (NormalizeHeader(file_name.substr(0, base.size())) != NormalizeHeader(base) || file_name[base.size()] != '_') {
    return {};
  }
  const std::string_view rest = file_name.substr(base.size() + 1);
  for (const std::string& type : XimuGuiFileTypes()) {
    if (NormalizeHeader(rest) == NormalizeHeader(type + ".csv")) return type;
  }
  return {};
}

}  // namespace

const std::vector<std::string>& XimuGuiFileTypes() {
  static const std::vector<std::string> kTypes = {
      "Errors", "Commands", "Registers", "DateTime", "RawBattAndTherm", "CalBattAndTherm", "RawInertialAndMag",
      "CalInertialAndMag", "Quaternion", "RotationMatrix", "EulerAngles", "DigitalIO", "RawAnalogueInput",
      "CalAnalogueInput", "PWMoutput", "CalADXL345bus", "RawADXL345bus",
      // API v7–v11 names (reference §1.7)
      "CalInertialMagnetic", "RawInertialMagnetic", "CalBattTherm", "RawBattTherm", "ErrorMessages",
      "CommandConfirmations"};
  return kTypes;
}

std::optional<std::string> XimuGuiBaseName(std::string_view file_name) {
  for (const std::string& type : XimuGuiFileTypes()) {
    const std::string suffix = "_" + type + ".csv";
    if (file_name.size() > suffix.size() && EndsWithNoCase(file_name, suffix)) {
      return std::string(file_name.substr(0, file_name.size() - suffix.size()));
    }
  }
  return std::nullopt;
}

std::vector<std::string> XimuGuiBasesIn(const std::filesystem::path& directory) {
  std::set<std::string> bases;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    const std::optional<std::string> base = XimuGuiBaseName(name);
    if (!base) continue;
    const std::string type = TypeOf(name, *base);
    if (type == "CalInertialAndMag" || type == "CalInertialMagnetic") bases.insert(*base);
  }
  return {bases.begin(), bases.end()};
}

XimuGuiFileSet XimuGuiFileSet::Find(const std::filesystem::path& prefix) {
  XimuGuiFileSet set;
  set.prefix = prefix;
  const std::filesystem::path directory = prefix.has_parent_path() ? prefix.parent_path() : std::filesystem::path(".");
  const std::string base = prefix.filename().string();
  std::error_code ec;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    if (entry.is_regular_file(ec)) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const std::filesystem::path& file : files) {
    const std::string type = TypeOf(file.filename().string(), base);
    if (type.empty()) continue;
    const std::filesystem::path path = prefix.has_parent_path() ? prefix.parent_path() / file.filename() : file.filename();
    set.all.push_back(path);
    if (type == "CalInertialAndMag" || (type == "CalInertialMagnetic" && !set.cal_inertial)) set.cal_inertial = path;
    if (type == "RawInertialAndMag" || (type == "RawInertialMagnetic" && !set.raw_inertial)) set.raw_inertial = path;
    if (type == "EulerAngles") set.euler_angles = path;
    if (type == "Quaternion") set.quaternion = path;
    if (type == "RotationMatrix") set.rotation_matrix = path;
    if (type == "Registers") set.registers = path;
    if (type == "DateTime") set.date_time = path;
  }
  return set;
}

}  // namespace rockfit::io
