// A ground-motion record as CSV (io/README.md, "Ground-motion records"): a header line, then one row per
// sample with a time column or not, and one to three acceleration columns.
//  * time: a column named `t`, `time` or `time_s` (also with a unit in brackets, `time [s]`) in seconds,
//    uniformly spaced (to 1e-6 of the step); without one, the step comes from the options (`--dt`);
//  * components: the other columns in order — first horizontal (along the incidence angle), second
//    horizontal, vertical — or by name: `x`/`h1`, `y`/`h2`, `z`/`v`/`vertical`;
//  * units: g, m/s² or cm/s² (gal), given in the options; never guessed.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockfit::io {

enum class GroundAccelerationUnit { kG, kMetrePerSecond2, kCentimetrePerSecond2 };
// "g", "m/s2", "cm/s2"; throws InvalidArgument for anything else (also accepts "m/s^2", "gal").
GroundAccelerationUnit ParseGroundAccelerationUnit(const std::string& text);
// The canonical spelling, "g", "m/s2" or "cm/s2", which ParseGroundAccelerationUnit reads back.
const char* UnitName(GroundAccelerationUnit unit);
// The factor to m/s² (g is standard gravity, 9.80665 m/s²).
double ToMetrePerSecond2(GroundAccelerationUnit unit);

struct CsvGroundMotionOptions {
  GroundAccelerationUnit unit = GroundAccelerationUnit::kG;
  std::optional<double> dt_s;  // required when the file has no time column
};

struct GroundMotionComponents {
  std::string source;
  double dt_s = 0.0;
  // Up to three components in m/s², each with its role: "h1", "h2" or "v".
  std::vector<std::string> roles;
  std::vector<std::vector<double>> accel_m_s2;
};

// Throws BadInput (file:line:column) for a file that cannot be used.
GroundMotionComponents ReadGroundMotionCsv(const std::filesystem::path& path, const CsvGroundMotionOptions& options);

}  // namespace rockfit::io
