// `rockfit inspect PATH`: detect the format of a recording and show what was read — rate, duration,
// samples, gaps, columns, value ranges, warnings (docs/design.md §9).
#include <algorithm>
#include <iostream>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "command_registry.hpp"
#include "rockfit/app/mounting_report.hpp"
#include "rockfit/app/recording_input.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/load_recording.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::tools {
namespace {

struct InspectCommand {
  std::string path;
  std::optional<double> rate_hz;
  std::string mounting;
  std::string orientation = "auto";
  std::string format = "auto";
  std::string columns;
  bool json = false;
};

struct Range {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
};

std::array<Range, 3> Ranges(const std::vector<Eigen::Vector3d>& values) {
  std::array<Range, 3> ranges;
  for (const Eigen::Vector3d& v : values) {
    for (std::size_t i = 0; i < 3; ++i) {
      ranges[i].min = std::min(ranges[i].min, v[static_cast<Eigen::Index>(i)]);
      ranges[i].max = std::max(ranges[i].max, v[static_cast<Eigen::Index>(i)]);
    }
  }
  return ranges;
}

nlohmann::json RangesJson(const std::vector<Eigen::Vector3d>& values, const std::array<const char*, 3>& names) {
  nlohmann::json out = nlohmann::json::object();
  const auto ranges = Ranges(values);
  for (std::size_t i = 0; i < 3; ++i) out[names[i]] = {ranges[i].min, ranges[i].max};
  return out;
}

std::string RateSourceText(io::RateSource source) {
  switch (source) {
    case io::RateSource::kRegisters: return "from _Registers.csv, register 69";
    case io::RateSource::kTimestamps: return "from the timestamps, 1 / median step";
    case io::RateSource::kOption: return "from --rate";
    case io::RateSource::kManifest: return "from the manifest";
    case io::RateSource::kFile: break;
  }
  return std::string("from ") + io::ToString(source);
}

io::LoadOptions MakeOptions(const InspectCommand& cmd) {
  io::LoadOptions options;
  options.rate_hz = cmd.rate_hz;
  if (!cmd.mounting.empty()) {
    const io::MountingOption option = io::MountingOption::Parse(cmd.mounting);
    options.mounting = option.given;
    options.estimate_mounting = option.estimate;
  }
  const auto orientation = io::ParseOrientationChoice(cmd.orientation);
  if (!orientation) throw InvalidArgument("--orientation must be auto, euler, quaternion, matrix or none, got '" + cmd.orientation + "'");
  options.orientation = *orientation;
  const auto format = io::ParseFormatName(cmd.format);
  if (!format) {
    throw InvalidArgument("--format must be auto, ximu-gui, ximu3, csv or rockfit-hdf5, got '" + cmd.format + "'");
  }
  options.format = *format;
  if (!cmd.columns.empty()) options.columns = io::ColumnMap::Parse(cmd.columns);
  options.Validate();
  return options;
}

void PrintJsonSummary(const io::Recording& r) {
  nlohmann::json out;
  out["format"] = r.format;
  out["source"] = r.source;
  out["rate_hz"] = r.rate_hz;
  out["rate_source"] = io::ToString(r.rate_source);
  out["samples"] = r.size();
  out["duration_s"] = r.duration_s();
  out["columns"] = r.columns;
  out["gaps"] = nlohmann::json::array();
  for (const io::Gap& gap : r.gaps) {
    out["gaps"].push_back({{"index", gap.index}, {"t_s", gap.t_s}, {"duration_s", gap.duration_s}, {"missing", gap.missing}});
  }
  out["warnings"] = r.warnings;
  out["recognised"] = r.recognised;
  out["orientation_source"] = r.orientation_source;
  out["orientation_rate_hz"] = r.orientation_rate_hz;
  out["mounting"] = r.mounting;
  out["mounting_check"] = MountingJson(r);
  nlohmann::json ranges = nlohmann::json::object();
  ranges["w_B_rad_s"] = RangesJson(r.w_B, {"x", "y", "z"});
  if (r.has_euler()) ranges["euler_zyx_rad"] = RangesJson(r.euler_zyx, {"phi_z", "phi_y", "phi_x"});
  if (r.has_accel()) ranges["accel_B_m_s2"] = RangesJson(r.accel_B, {"x", "y", "z"});
  out["ranges"] = ranges;
  PrintJson(out);
}

void PrintText(const io::Recording& r) {
  std::cout << fmt::format("format       {}\n", r.format)
            << fmt::format("source       {}\n", r.source)
            << fmt::format("rate         {:.6g} Hz ({})\n", r.rate_hz, RateSourceText(r.rate_source))
            << fmt::format("samples      {} over {:.4f} s\n", r.size(), r.duration_s());
  if (r.has_euler()) {
    std::cout << fmt::format("attitude     {} at {:.6g} Hz, on the gyro time base\n", r.orientation_source,
                             r.orientation_rate_hz);
  } else {
    std::cout << "attitude     none\n";
  }
  std::cout << fmt::format("mounting     {}\n", MountingText(r));
  if (r.gaps.empty()) {
    std::cout << "gaps         none\n";
  } else {
    std::size_t missing = 0;
    for (const io::Gap& gap : r.gaps) missing += gap.missing;
    std::cout << fmt::format("gaps         {} ({} samples missing)\n", r.gaps.size(), missing);
    for (const io::Gap& gap : r.gaps) {
      std::cout << fmt::format("  after sample {} at t = {:.4f} s: {:.4f} s, {} missing\n", gap.index, gap.t_s,
                               gap.duration_s, gap.missing);
    }
  }
  std::cout << "ranges       min … max\n";
  const double kDegPerRad = 1.0 / io::kRadPerDeg;
  const auto w = Ranges(r.w_B);
  for (std::size_t i = 0; i < 3; ++i) {
    std::cout << fmt::format("  w_B {}      {:+9.4f} … {:+9.4f} rad/s   ({:+.1f} … {:+.1f} deg/s)\n", "xyz"[i], w[i].min,
                             w[i].max, w[i].min * kDegPerRad, w[i].max * kDegPerRad);
  }
  if (r.has_euler()) {
    const auto e = Ranges(r.euler_zyx);
    const std::array<const char*, 3> names = {"φz yaw  ", "φy pitch", "φx roll "};
    for (std::size_t i = 0; i < 3; ++i) {
      std::cout << fmt::format("  {}   {:+9.4f} … {:+9.4f} rad     ({:+.1f} … {:+.1f} deg)\n", names[i], e[i].min,
                               e[i].max, e[i].min * kDegPerRad, e[i].max * kDegPerRad);
    }
  }
  if (r.has_accel()) {
    const auto a = Ranges(r.accel_B);
    for (std::size_t i = 0; i < 3; ++i) {
      std::cout << fmt::format("  accel_B {}  {:+9.4f} … {:+9.4f} m/s²\n", "xyz"[i], a[i].min, a[i].max);
    }
  }
  std::cout << fmt::format("columns      {}\n", r.columns.size());
  for (const std::string& column : r.columns) std::cout << "  " << column << "\n";
  if (!r.recognised.empty()) {
    std::cout << "recognised\n";
    for (const std::string& note : r.recognised) std::cout << "  " << note << "\n";
  }
  if (r.warnings.empty()) {
    std::cout << "warnings     none\n";
  } else {
    std::cout << fmt::format("warnings     {}\n", r.warnings.size());
    for (const std::string& warning : r.warnings) std::cout << "  " << warning << "\n";
  }
}

int RunInspect(const InspectCommand& cmd) {
  const io::Recording recording = io::LoadRecording(cmd.path, MakeOptions(cmd));
  if (cmd.json) {
    PrintJsonSummary(recording);
  } else {
    PrintText(recording);
  }
  return kExitOk;
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto cmd = std::make_shared<InspectCommand>();
  CLI::App* app = root.add_subcommand(
      "inspect",
      "Read a recording and show what was read: format, sample rate, duration, samples, gaps, columns, value ranges "
      "and warnings");
  app->footer(
      "PATH is one of:\n"
      "  an x-IMU GUI prefix (dir/LoggedData) or any of its files (dir/LoggedData_CalInertialAndMag.csv),\n"
      "  an x-IMU3 logger directory (with Inertial.csv), or a directory holding one recording,\n"
      "  a CSV file with a header (columns recognised from 'Gyroscope X (deg/s)', 'Time (s)', … or given by --columns).\n"
      "x-IMU GUI files hold no time: the rate comes from <prefix>_Registers.csv, else give --rate.\n"
      "Exit codes: 0 read, 1 bad option, 2 the data cannot be used (the message says where and what to do).");
  app->add_option("PATH", cmd->path, "Recording: x-IMU prefix or file, x-IMU3 directory, or CSV file")->required();
  app->add_option("--rate", cmd->rate_hz, "Gyro sample rate [Hz] when the files do not state it (x-IMU without _Registers.csv)");
  app->add_option("--mounting", cmd->mounting,
                  kMountingHelp);
  app->add_option("--orientation", cmd->orientation, "Attitude source: auto, euler, quaternion, matrix or none")
      ->capture_default_str();
  app->add_option("--format", cmd->format, "Force a format: auto, ximu-gui, ximu3, csv, rockfit-hdf5")->capture_default_str();
  app->add_option("--columns", cmd->columns,
                  "Generic CSV column map: 'time=NAME@s;gyro=X,Y,Z@deg/s;euler=ROLL,PITCH,YAW@deg;accel=X,Y,Z@g' "
                  "(units: s|ms|us|ns, deg/s|rad/s, deg|rad, g|m/s^2; '@unit' may be left out when the header ends in "
                  "'(unit)' or '[unit]'), or a preset: phyphox, sensor-logger");
  app->add_flag("--json", cmd->json,
                "Print one JSON object: format, source, rate_hz, rate_source, samples, duration_s, columns, recognised, gaps, "
                "warnings, orientation_source, orientation_rate_hz, mounting, mounting_check (applied, given, estimated, status, "
                "message, angles_deg, std_error_deg, determined, disagreement_deg, release_tilt_rad, release_tilt_std_error_rad, turn_before_fall_deg, warning), ranges "
                "(min/max per channel, SI units)");
  app->callback([cmd] { SetExitCode(RunInspect(*cmd)); });
});

}  // namespace
}  // namespace rockfit::tools
