#include "rockfit/io/column_map.hpp"

#include <algorithm>
#include <set>
#include <vector>

#include "rockfit/core/errors.hpp"
#include "text/header_matching.hpp"
#include "text/number_parsing.hpp"

namespace rockfit::io {
namespace {

constexpr std::string_view kExample = "time=Time (s)@s;gyro=Gx,Gy,Gz@deg/s;euler=Roll,Pitch,Yaw@deg;accel=Ax,Ay,Az@g";

[[noreturn]] void Refuse(std::string_view spec, const std::string& why) {
  throw InvalidArgument("column map '" + std::string(spec) + "': " + why + " (expected entries key=names@unit " +
                        "separated by ';', e.g. '" + std::string(kExample) + "')");
}

std::vector<std::string> Split(std::string_view text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t stop = text.find(separator, start);
    parts.emplace_back(TrimSpaces(text.substr(start, stop == std::string_view::npos ? std::string_view::npos : stop - start)));
    if (stop == std::string_view::npos) break;
    start = stop + 1;
  }
  return parts;
}

template <typename Unit>
void SetUnit(std::string_view spec, const std::string& key, const std::string& text,
             std::optional<Unit> (*parse)(std::string_view), std::optional<Unit>& unit, const char* allowed) {
  if (text.empty()) return;
  unit = parse(text);
  if (!unit) Refuse(spec, "unit '" + text + "' of " + key + " is not one of " + allowed);
}

void SetTriple(std::string_view spec, const std::string& key, const std::vector<std::string>& names,
               std::array<std::string, 3>& target) {
  if (names.size() != 3) {
    Refuse(spec, key + " needs three column names x,y,z separated by ',', found " + std::to_string(names.size()));
  }
  for (std::size_t i = 0; i < 3; ++i) {
    if (names[i].empty()) Refuse(spec, key + " has an empty column name");
    target[i] = names[i];
  }
}

template <typename Unit>
std::string Entry(const std::string& key, const std::string& names, const std::optional<Unit>& unit) {
  return key + "=" + names + (unit ? "@" + UnitName(*unit) : "");
}

}  // namespace

const std::vector<std::string>& ColumnMapPresets() {
  static const std::vector<std::string> kPresets = {"phyphox", "sensor-logger"};
  return kPresets;
}

ColumnMap ColumnMap::Parse(std::string_view spec) {
  ColumnMap map;
  const std::string name = NormalizeHeader(spec);
  for (const std::string& preset : ColumnMapPresets()) {
    if (name == preset) {
      map.preset = preset;
      return map;
    }
  }
  std::set<std::string> seen;
  for (const std::string& entry : Split(spec, ';')) {
    if (entry.empty()) continue;
    const std::size_t equals = entry.find('=');
    if (equals == std::string::npos) Refuse(spec, "entry '" + entry + "' has no '='");
    const std::string key = NormalizeHeader(entry.substr(0, equals));
    std::string value = entry.substr(equals + 1);
    std::string unit;
    if (const std::size_t at = value.rfind('@'); at != std::string::npos) {
      unit = std::string(TrimSpaces(std::string_view(value).substr(at + 1)));
      value = std::string(TrimSpaces(std::string_view(value).substr(0, at)));
      if (unit.empty()) Refuse(spec, "entry '" + entry + "' has an empty unit after '@'");
    }
    if (!seen.insert(key).second) Refuse(spec, "key '" + key + "' appears twice");
    const std::vector<std::string> names = Split(value, ',');
    if (key == "time") {
      if (names.size() != 1 || names[0].empty()) Refuse(spec, "time needs exactly one column name");
      map.time = names[0];
      SetUnit(spec, key, unit, &ParseTimeUnit, map.time_unit, "s, ms, us, ns");
    } else if (key == "gyro") {
      SetTriple(spec, key, names, map.gyro);
      SetUnit(spec, key, unit, &ParseAngularRateUnit, map.gyro_unit, "deg/s, rad/s");
    } else if (key == "euler") {
      SetTriple(spec, key, names, map.euler);
      SetUnit(spec, key, unit, &ParseAngleUnit, map.euler_unit, "deg, rad");
    } else if (key == "accel") {
      SetTriple(spec, key, names, map.accel);
      SetUnit(spec, key, unit, &ParseAccelerationUnit, map.accel_unit, "g, m/s^2");
    } else {
      Refuse(spec, "unknown key '" + key + "' (keys: time, gyro, euler, accel; or a preset alone: phyphox, sensor-logger)");
    }
  }
  try {
    map.Validate();
  } catch (const InvalidArgument& e) {
    Refuse(spec, e.what());
  }
  return map;
}

void ColumnMap::Validate() const {
  if (is_preset()) {
    const auto& presets = ColumnMapPresets();
    if (std::find(presets.begin(), presets.end(), preset) == presets.end()) {
      throw InvalidArgument("unknown column map preset '" + preset + "' (presets: phyphox, sensor-logger)");
    }
    return;
  }
  if (gyro[0].empty() || gyro[1].empty() || gyro[2].empty()) {
    throw InvalidArgument("the gyroscope columns (gyro=X,Y,Z) are required");
  }
  for (const auto* triple : {&euler, &accel}) {
    const bool any = !(*triple)[0].empty() || !(*triple)[1].empty() || !(*triple)[2].empty();
    const bool all = !(*triple)[0].empty() && !(*triple)[1].empty() && !(*triple)[2].empty();
    if (any && !all) throw InvalidArgument(std::string(triple == &euler ? "euler" : "accel") + " needs all three columns");
  }
  std::set<std::string> names;
  auto add = [&names](const std::string& name) {
    if (name.empty()) return;
    if (!names.insert(NormalizeHeader(name)).second) {
      throw InvalidArgument("column '" + name + "' is used twice");
    }
  };
  add(time);
  for (const auto* triple : {&gyro, &euler, &accel}) {
    for (const std::string& name : *triple) add(name);
  }
}

std::string ColumnMap::ToString() const {
  if (is_preset()) return preset;
  auto join = [](const std::array<std::string, 3>& names) { return names[0] + "," + names[1] + "," + names[2]; };
  std::string text;
  if (has_time()) text += Entry("time", time, time_unit) + ";";
  text += Entry("gyro", join(gyro), gyro_unit);
  if (has_euler()) text += ";" + Entry("euler", join(euler), euler_unit);
  if (has_accel()) text += ";" + Entry("accel", join(accel), accel_unit);
  return text;
}

}  // namespace rockfit::io
