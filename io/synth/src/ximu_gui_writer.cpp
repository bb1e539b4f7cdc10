#include "rockfit/io/ximu_gui_writer.hpp"

#include <cmath>
#include <filesystem>
#include <utility>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/atomic_file.hpp"
#include "text/dotnet_float_format.hpp"
#include "rockfit/io/synth_random.hpp"
#include "ximu/ximu_register_map.hpp"

namespace rockfit::io {
namespace {

// Verbatim headers of the x-IMU GUI v13 (docs/file-formats.md §1.2).
constexpr const char* kRegistersHeader = "Packet number,Address,Value,Fixed-point value,Name";
constexpr const char* kDateTimeHeader = "Packet number,Year,Month,Day,Hours,Minutes,Seconds";
constexpr const char* kBatteryHeader = "Packet number,Battery voltage (V),Thermometer (degrees C)";
constexpr const char* kInertialHeader =
    "Packet number,Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),"
    "Accelerometer Y (g),Accelerometer Z (g),Magnetometer X (G),Magnetometer Y (G),Magnetometer Z (G)";
constexpr const char* kQuaternionHeader = "Packet number,Element 1, Element 2, Element 3, Element 4";
constexpr const char* kRotationMatrixHeader =
    "Packet number,Element 11, Element 12, Element 13, Element 21, Element 22, Element 23, Element 31, "
    "Element 32, Element 33";
constexpr const char* kEulerHeader =
    "Packet number,Roll | Phi | X (degrees), Pitch | Theta | Y (degrees), Yaw | Psi | Z (degrees)";

// Housekeeping values of the synthetic device: a charged Li-ion cell and a board a little above room
// temperature, with the device's resolutions (battery Q12, thermometer Q8).
constexpr double kBatteryStartV = 4.13;
constexpr double kBatteryDischargeV_per_s = 2e-5;
constexpr double kBatteryNoiseV = 0.0015;
constexpr double kBatteryResolutionV = 1.0 / 4096.0;
constexpr double kThermometerStartC = 32.6;
constexpr double kThermometerWarmingC_per_s = 0.01;
constexpr double kThermometerNoiseC = 0.08;
constexpr double kThermometerResolutionC = 1.0 / 256.0;

// One file of the set and its whole text, written together with the others (atomic_file.hpp).
using CsvFile = FileContent;

class Line {
 public:
  Line(std::string& text, std::int64_t packet, const char* eol) : text_(text), eol_(eol) {
    text_ += std::to_string(packet);
  }
  ~Line() { text_ += eol_; }
  Line& Number(float value) {
    text_ += ',';
    AppendDotNetSingle(text_, value);
    return *this;
  }
  Line& Integer(std::int64_t value) {
    text_ += ',';
    text_ += std::to_string(value);
    return *this;
  }
  Line& Text(const std::string& value) {
    text_ += ',';
    text_ += value;
    return *this;
  }

 private:
  std::string& text_;
  const char* eol_;
};

bool IsLeapYear(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

int DaysInMonth(int year, int month) {
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && IsLeapYear(year) ? 29 : kDays[month - 1];
}

// Integer number of ticks per packet of a periodic stream, or throws.
std::int64_t TicksPerPacket(double inertial_rate_hz, double rate_hz, const char* what) {
  const double ratio = inertial_rate_hz / rate_hz;
  if (ratio < 1.0 || ratio != std::floor(ratio)) {
    throw InvalidArgument(std::string(what) + " (" + std::to_string(rate_hz) +
                          " Hz) must not exceed the inertial rate and must divide it (" +
                          std::to_string(inertial_rate_hz) + " Hz)");
  }
  return static_cast<std::int64_t>(ratio);
}

}  // namespace

CalendarTime CalendarTimeSince2000(std::int64_t seconds) {
  if (seconds < 0) throw InvalidArgument("the real-time clock cannot start before 2000-01-01 00:00:00");
  std::int64_t days = seconds / 86400;
  std::int64_t rest = seconds % 86400;
  CalendarTime c{2000, 1, 1, static_cast<int>(rest / 3600), static_cast<int>(rest % 3600 / 60), static_cast<int>(rest % 60)};
  while (days >= (IsLeapYear(c.year) ? 366 : 365)) days -= IsLeapYear(c.year++) ? 366 : 365;
  while (days >= DaysInMonth(c.year, c.month)) days -= DaysInMonth(c.year, c.month++);
  c.day = 1 + static_cast<int>(days);
  return c;
}

void XimuGuiWriterOptions::Validate(double inertial_rate_hz) const {
  XimuRateRegisterValue(inertial_rate_hz, "the inertial (gyroscope) rate");
  XimuRateRegisterValue(quaternion_rate_hz, "the quaternion rate");
  XimuRateRegisterValue(date_time_rate_hz, "the date/time rate");
  XimuRateRegisterValue(battery_rate_hz, "the battery/thermometer rate");
  if (quaternion_rate_hz == 0.0) throw InvalidArgument("the quaternion rate must not be 0: the Euler angles come from it");
  TicksPerPacket(inertial_rate_hz, quaternion_rate_hz, "the quaternion rate");
  if (date_time_rate_hz > 0.0) TicksPerPacket(inertial_rate_hz, date_time_rate_hz, "the date/time rate");
  if (battery_rate_hz > 0.0) TicksPerPacket(inertial_rate_hz, battery_rate_hz, "the battery/thermometer rate");
  if (rtc_start_s < 0) throw InvalidArgument("rtc_start_s must be ≥ 0 (seconds after 2000-01-01 00:00:00)");
}

std::vector<std::string> WriteXimuGuiCsv(const std::string& prefix, const DeviceSamples& samples,
                                         const XimuGuiWriterOptions& options, XimuPacketLayout* layout) {
  const double rate_hz = samples.rate_hz;
  options.Validate(rate_hz);
  const std::size_t count = samples.size();
  if (count == 0) throw InvalidArgument("no samples to write");
  if (samples.accel_g.size() != count || samples.mag_G.size() != count || samples.quaternion.size() != count ||
      samples.euler_deg.size() != count) {
    throw InvalidArgument("DeviceSamples: every stream needs one entry per inertial sample");
  }
  const char* eol = options.crlf_line_endings ? "\r\n" : "\n";
  const std::int64_t quaternion_every = TicksPerPacket(rate_hz, options.quaternion_rate_hz, "the quaternion rate");
  const std::int64_t date_time_every =
      options.date_time_rate_hz > 0.0 ? TicksPerPacket(rate_hz, options.date_time_rate_hz, "the date/time rate") : 0;
  const std::int64_t battery_every =
      options.battery_rate_hz > 0.0 ? TicksPerPacket(rate_hz, options.battery_rate_hz, "the battery/thermometer rate") : 0;

  CsvFile registers{prefix + "_Registers.csv", std::string(kRegistersHeader) + eol};
  CsvFile date_time{prefix + "_DateTime.csv", std::string(kDateTimeHeader) + eol};
  CsvFile battery{prefix + "_CalBattAndTherm.csv", std::string(kBatteryHeader) + eol};
  CsvFile inertial{prefix + "_CalInertialAndMag.csv", std::string(kInertialHeader) + eol};
  CsvFile quaternion{prefix + "_Quaternion.csv", std::string(kQuaternionHeader) + eol};
  CsvFile rotation{prefix + "_RotationMatrix.csv", std::string(kRotationMatrixHeader) + eol};
  CsvFile euler{prefix + "_EulerAngles.csv", std::string(kEulerHeader) + eol};
  inertial.text.reserve(count * 96);
  quaternion.text.reserve(count * 56);
  euler.text.reserve(count * 40);
  if (options.rotation_matrix_file) rotation.text.reserve(count * 110);

  XimuPacketLayout local_layout;
  XimuPacketLayout& out_layout = layout != nullptr ? *layout : local_layout;
  out_layout = XimuPacketLayout{};
  std::int64_t packet = 0;
  SynthRandom housekeeping(options.seed, SynthStream::kHousekeeping);

  const auto write_date_time = [&](double t_s) {
    const CalendarTime c = CalendarTimeSince2000(options.rtc_start_s + static_cast<std::int64_t>(std::floor(t_s)));
    Line(date_time.text, packet++, eol).Integer(c.year).Integer(c.month).Integer(c.day).Integer(c.hours).Integer(c.minutes).Integer(c.seconds);
  };
  const auto write_battery = [&](double t_s) {
    const double volts = kBatteryStartV - kBatteryDischargeV_per_s * t_s + kBatteryNoiseV * housekeeping.Normal();
    const double celsius = kThermometerStartC + kThermometerWarmingC_per_s * t_s + kThermometerNoiseC * housekeeping.Normal();
    Line(battery.text, packet++, eol)
        .Number(static_cast<float>(std::round(volts / kBatteryResolutionV) * kBatteryResolutionV))
        .Number(static_cast<float>(std::round(celsius / kThermometerResolutionC) * kThermometerResolutionC));
  };

  // Start-up: the clock, every register, then the first periodic housekeeping packets.
  write_date_time(0.0);
  XimuDeviceRates register_settings;
  register_settings.inertial_rate_hz = rate_hz;
  register_settings.quaternion_rate_hz = options.quaternion_rate_hz;
  register_settings.date_time_rate_hz = options.date_time_rate_hz;
  register_settings.battery_rate_hz = options.battery_rate_hz;
  for (const XimuRegister& r : XimuRegisters(register_settings)) {
    Line(registers.text, packet++, eol).Integer(r.address).Integer(r.value).Number(r.FixedPointValue()).Text(r.name);
  }
  if (date_time_every > 0) write_date_time(0.0);
  if (battery_every > 0) write_battery(0.0);

  for (std::size_t n = 0; n < count; ++n) {
    const Eigen::Vector3f& gyro = samples.gyro_dps[n];
    const Eigen::Vector3f& accel = samples.accel_g[n];
    const Eigen::Vector3f& mag = samples.mag_G[n];
    out_layout.inertial.push_back(packet);
    Line(inertial.text, packet++, eol)
        .Number(gyro.x()).Number(gyro.y()).Number(gyro.z())
        .Number(accel.x()).Number(accel.y()).Number(accel.z())
        .Number(mag.x()).Number(mag.y()).Number(mag.z());
    const auto tick = static_cast<std::int64_t>(n);
    if (tick % quaternion_every == 0) {
      const Eigen::Vector4f& q = samples.quaternion[n];
      const Eigen::Vector3f& e = samples.euler_deg[n];
      out_layout.quaternion.push_back(packet);
      Line(quaternion.text, packet, eol).Number(q[0]).Number(q[1]).Number(q[2]).Number(q[3]);
      if (options.rotation_matrix_file) {
        // The GUI's rotation matrix of the file quaternion (QuaternionData.ConvertToRotationMatrix), single precision.
        const float r11 = 2 * q[0] * q[0] - 1 + 2 * q[1] * q[1];
        const float r12 = 2 * (q[1] * q[2] + q[0] * q[3]);
        const float r13 = 2 * (q[1] * q[3] - q[0] * q[2]);
        const float r21 = 2 * (q[1] * q[2] - q[0] * q[3]);
        const float r22 = 2 * q[0] * q[0] - 1 + 2 * q[2] * q[2];
        const float r23 = 2 * (q[2] * q[3] + q[0] * q[1]);
        const float r31 = 2 * (q[1] * q[3] + q[0] * q[2]);
        const float r32 = 2 * (q[2] * q[3] - q[0] * q[1]);
        const float r33 = 2 * q[0] * q[0] - 1 + 2 * q[3] * q[3];
        Line(rotation.text, packet, eol).Number(r11).Number(r12).Number(r13).Number(r21).Number(r22).Number(r23)
            .Number(r31).Number(r32).Number(r33);
      }
      Line(euler.text, packet, eol).Number(e.x()).Number(e.y()).Number(e.z());
      ++packet;
    }
    const double t_next_s = static_cast<double>(tick + 1) / rate_hz;
    if (date_time_every > 0 && (tick + 1) % date_time_every == 0) write_date_time(t_next_s);
    if (battery_every > 0 && (tick + 1) % battery_every == 0) write_battery(t_next_s);
  }
  out_layout.total_packets = packet;

  std::vector<CsvFile> files;
  files.push_back(std::move(registers));
  files.push_back(std::move(date_time));
  if (battery_every > 0) files.push_back(std::move(battery));
  files.push_back(std::move(inertial));
  files.push_back(std::move(quaternion));
  if (options.rotation_matrix_file) files.push_back(std::move(rotation));
  files.push_back(std::move(euler));
  WriteFilesAtomically(files);
  std::vector<std::string> paths;
  for (const auto& f : files) paths.push_back(f.path.string());
  return paths;
}

}  // namespace rockfit::io
