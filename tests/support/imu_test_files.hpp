// Small IMU files of known content for tests: an x-IMU GUI set of a steady spin, written the way the
// GUI writes it (headers verbatim from docs/file-formats.md §1.2, shared packet counter, 7 significant
// digits), and an x-IMU3 Inertial.csv.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace rockfit::testing {

inline const std::string kGuiInertialHeader =
    "Packet number,Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),Accelerometer Y "
    "(g),Accelerometer Z (g),Magnetometer X (G),Magnetometer Y (G),Magnetometer Z (G)";
inline const std::string kGuiEulerHeader =
    "Packet number,Roll | Phi | X (degrees), Pitch | Theta | Y (degrees), Yaw | Psi | Z (degrees)";
inline const std::string kGuiQuaternionHeader = "Packet number,Element 1, Element 2, Element 3, Element 4";
inline const std::string kGuiRegistersHeader = "Packet number,Address,Value,Fixed-point value,Name";
inline const std::string kGuiDateTimeHeader = "Packet number,Year,Month,Day,Hours,Minutes,Seconds";
inline const std::string kXimu3InertialHeader =
    "Timestamp (us),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),Accelerometer Y "
    "(g),Accelerometer Z (g)";

// "%.7g", as the GUI prints single-precision floats.
inline std::string G7(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.7g", value);
  return buffer;
}

// The files of one x-IMU GUI recording of a steady spin about the sensor z axis at `yaw_rate_dps`,
// tilted by a constant roll and pitch (degrees). Inertial rows at `rate_hz`; an attitude packet
// after every `attitude_every`-th inertial packet; a DateTime packet (2 Hz) and the counter shared.
struct GuiSpin {
  std::string inertial;
  std::string euler;
  std::string quaternion;
  std::string date_time;
  std::vector<double> yaw_deg;  // true yaw at each inertial row (unwrapped)
};

inline GuiSpin MakeGuiSpin(std::size_t n, double rate_hz, double yaw_rate_dps, std::size_t attitude_every = 1,
                           double roll_deg = 5.0, double pitch_deg = -3.0) {
  const double kDeg = std::acos(-1.0) / 180.0;
  GuiSpin set;
  set.inertial = kGuiInertialHeader + "\n";
  set.euler = kGuiEulerHeader + "\n";
  set.quaternion = kGuiQuaternionHeader + "\n";
  set.date_time = kGuiDateTimeHeader + "\n";
  long packet = 0;
  const std::size_t date_every = static_cast<std::size_t>(rate_hz / 2.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    const double yaw = yaw_rate_dps * t;
    set.yaw_deg.push_back(yaw);
    // Body rates of a steady yaw with constant roll φ and pitch θ: ω = ψ̇(−sinθ, cosθ sinφ, cosθ cosφ).
    const double phi = roll_deg * kDeg;
    const double theta = pitch_deg * kDeg;
    set.inertial += std::to_string(packet++) + "," + G7(-yaw_rate_dps * std::sin(theta)) + "," +
                    G7(yaw_rate_dps * std::cos(theta) * std::sin(phi)) + "," +
                    G7(yaw_rate_dps * std::cos(theta) * std::cos(phi)) + ",0,0,1,0.1,0.2,0.3\n";
    if (k % attitude_every == 0) {
      const double wrapped = std::remainder(yaw, 360.0);
      set.euler += std::to_string(packet) + "," + G7(roll_deg) + "," + G7(pitch_deg) + "," + G7(wrapped) + "\n";
      // The file's quaternion is the Earth relative to the sensor: the conjugate of q_WS (§1.6).
      const double cy = std::cos(yaw * kDeg / 2), sy = std::sin(yaw * kDeg / 2);
      const double cp = std::cos(theta / 2), sp = std::sin(theta / 2);
      const double cr = std::cos(phi / 2), sr = std::sin(phi / 2);
      const double w = cr * cp * cy + sr * sp * sy;
      const double x = sr * cp * cy - cr * sp * sy;
      const double y = cr * sp * cy + sr * cp * sy;
      const double z = cr * cp * sy - sr * sp * cy;
      set.quaternion += std::to_string(packet) + "," + G7(w) + "," + G7(-x) + "," + G7(-y) + "," + G7(-z) + "\n";
      ++packet;
    }
    if (date_every > 0 && k % date_every == date_every / 3) {
      const long second = 11 + static_cast<long>(t);
      set.date_time += std::to_string(packet++) + ",2000,1,5,0,1," + std::to_string(second) + "\n";
    }
  }
  return set;
}

// An x-IMU3 Inertial.csv at 50 Hz from 19 150 794 µs with the given timestamps' steps (µs).
inline std::string MakeXimu3Inertial(const std::vector<long long>& steps_us) {
  std::string text = kXimu3InertialHeader + "\n";
  long long t = 19150794;
  for (std::size_t k = 0; k <= steps_us.size(); ++k) {
    text += std::to_string(t) + ",0.013032,-0.038818,0.066303,0.000251,0.002156,0.996598\n";
    if (k < steps_us.size()) t += steps_us[k];
  }
  return text;
}

}  // namespace rockfit::testing
