// The x-IMU GUI CSV set: headers, shared packet counter, rate registers, line endings, number text and
// atomic writing — compared with the format description and, when present, the real recordings.
#include "rockfit/io/ximu_gui_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rockfit/core/errors.hpp"
#include "text/dotnet_float_format.hpp"
#include "test_paths.hpp"

namespace rockfit::io {
namespace {

namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::vector<std::string>> ReadRows(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream text(ReadFile(path));
  std::string line;
  while (std::getline(text, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> cells;
    std::stringstream cells_text(line);
    std::string cell;
    while (std::getline(cells_text, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() / ("rockfit_writer_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Device samples with distinct, recognisable values per sample.
DeviceSamples MakeSamples(std::size_t count, double rate_hz) {
  DeviceSamples d;
  d.rate_hz = rate_hz;
  for (std::size_t n = 0; n < count; ++n) {
    const float k = static_cast<float>(n);
    d.gyro_dps.emplace_back(0.0625f * k, -0.125f * k, 2.0f);
    d.accel_g.emplace_back(-0.02880859f, 0.01660156f + k / 2048.0f, 1.01709f);
    d.mag_G.emplace_back(0.2099609f, 0.03125f, -0.4487305f);
    const Eigen::Quaternionf q(Eigen::AngleAxisf(0.001f * k, Eigen::Vector3f(0.3f, 0.9f, 0.1f).normalized()));
    d.quaternion.emplace_back(q.w(), q.x(), q.y(), q.z());
    d.euler_deg.emplace_back(0.01f * k, -0.02f * k, 1e-5f);
  }
  return d;
}

TEST(XimuGuiWriter, WritesTheSetWithTheGuiHeadersVerbatim) {
  TempDir dir;
  const auto paths = WriteXimuGuiCsv((dir.path() / "trial").string(), MakeSamples(600, 256.0), XimuGuiWriterOptions{});
  EXPECT_EQ(paths.size(), 7u);
  // docs/file-formats.md §1.2 (note the leading spaces).
  const std::map<std::string, std::string> headers = {
      {"Registers", "Packet number,Address,Value,Fixed-point value,Name"},
      {"DateTime", "Packet number,Year,Month,Day,Hours,Minutes,Seconds"},
      {"CalBattAndTherm", "Packet number,Battery voltage (V),Thermometer (degrees C)"},
      {"CalInertialAndMag",
       "Packet number,Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s),Accelerometer X (g),Accelerometer Y "
       "(g),Accelerometer Z (g),Magnetometer X (G),Magnetometer Y (G),Magnetometer Z (G)"},
      {"Quaternion", "Packet number,Element 1, Element 2, Element 3, Element 4"},
      {"RotationMatrix",
       "Packet number,Element 11, Element 12, Element 13, Element 21, Element 22, Element 23, Element 31, Element 32, "
       "Element 33"},
      {"EulerAngles", "Packet number,Roll | Phi | X (degrees), Pitch | Theta | Y (degrees), Yaw | Psi | Z (degrees)"},
  };
  for (const auto& [type, header] : headers) {
    const std::string text = ReadFile(dir.path() / ("trial_" + type + ".csv"));
    EXPECT_EQ(text.substr(0, text.find('\n')), header) << type;
  }
}

TEST(XimuGuiWriter, HeadersAreThoseOfTheRealRecording) {
  ROCKFIT_REQUIRE_REAL_IMU();
  TempDir dir;
  WriteXimuGuiCsv((dir.path() / "trial").string(), MakeSamples(10, 256.0), XimuGuiWriterOptions{});
  const auto real = rockfit::testing::RealImuDir() / "Oscillatory-Motion-Tracking-With-x-IMU" / "LoggedData";
  for (const char* type : {"CalInertialAndMag", "Quaternion", "EulerAngles", "RotationMatrix", "DateTime", "CalBattAndTherm"}) {
    const std::string ours = ReadFile(dir.path() / (std::string("trial_") + type + ".csv"));
    const std::string theirs = ReadFile(real / (std::string("LoggedData_") + type + ".csv"));
    EXPECT_EQ(ours.substr(0, ours.find('\n')), theirs.substr(0, theirs.find('\n'))) << type;
  }
}

TEST(XimuGuiWriter, PacketNumbersAreOneCounterSharedByAllFilesInArrivalOrder) {
  TempDir dir;
  XimuPacketLayout layout;
  const std::size_t count = 1000;
  WriteXimuGuiCsv((dir.path() / "t").string(), MakeSamples(count, 256.0), XimuGuiWriterOptions{}, &layout);
  // Every packet number 0 … total−1 occurs exactly once over the files of distinct packets; the
  // quaternion, rotation-matrix and Euler rows of one packet share its number.
  std::map<std::int64_t, std::string> owner;
  for (const char* type : {"Registers", "DateTime", "CalBattAndTherm", "CalInertialAndMag", "Quaternion"}) {
    const auto rows = ReadRows(dir.path() / (std::string("t_") + type + ".csv"));
    for (std::size_t r = 1; r < rows.size(); ++r) {
      const std::int64_t packet = std::stoll(rows[r][0]);
      EXPECT_TRUE(owner.emplace(packet, type).second) << "packet " << packet << " in " << type << " and " << owner[packet];
    }
  }
  ASSERT_EQ(static_cast<std::int64_t>(owner.size()), layout.total_packets);
  EXPECT_EQ(owner.begin()->first, 0);
  EXPECT_EQ(owner.rbegin()->first, layout.total_packets - 1);
  for (const char* derived : {"RotationMatrix", "EulerAngles"}) {
    const auto rows = ReadRows(dir.path() / (std::string("t_") + derived + ".csv"));
    const auto quaternion_rows = ReadRows(dir.path() / "t_Quaternion.csv");
    ASSERT_EQ(rows.size(), quaternion_rows.size());
    for (std::size_t r = 1; r < rows.size(); ++r) EXPECT_EQ(rows[r][0], quaternion_rows[r][0]);
  }
  // Start-up as the device sends it: clock, 110 registers, clock, battery, then the data stream.
  EXPECT_EQ(owner[0], "DateTime");
  for (std::int64_t p = 1; p <= 110; ++p) EXPECT_EQ(owner[p], "Registers") << p;
  EXPECT_EQ(owner[111], "DateTime");
  EXPECT_EQ(owner[112], "CalBattAndTherm");
  // Each quaternion packet immediately follows its inertial packet; inertial steps are 2, or 3–4 where
  // housekeeping packets fall (docs/file-formats.md §1.4).
  ASSERT_EQ(layout.inertial.size(), count);
  ASSERT_EQ(layout.quaternion.size(), count);
  std::set<std::int64_t> steps;
  for (std::size_t n = 0; n < count; ++n) {
    EXPECT_EQ(layout.quaternion[n], layout.inertial[n] + 1);
    if (n > 0) steps.insert(layout.inertial[n] - layout.inertial[n - 1]);
  }
  EXPECT_EQ(steps, (std::set<std::int64_t>{2, 3, 4}));
}

TEST(XimuGuiWriter, RegistersCarryTheRatesAndTheOrientationStreamIsDecimated) {
  TempDir dir;
  XimuGuiWriterOptions options;
  options.quaternion_rate_hz = 128.0;
  options.date_time_rate_hz = 2.0;
  WriteXimuGuiCsv((dir.path() / "t").string(), MakeSamples(512, 256.0), options);
  const auto registers = ReadRows(dir.path() / "t_Registers.csv");
  ASSERT_EQ(registers.size(), 111u);
  std::map<std::string, std::vector<std::string>> by_name;
  for (std::size_t r = 1; r < registers.size(); ++r) by_name[registers[r][4]] = registers[r];
  EXPECT_EQ(by_name["InertialAndMagneticDataRate"][1], "69");
  EXPECT_EQ(by_name["InertialAndMagneticDataRate"][2], "9");
  EXPECT_EQ(by_name["InertialAndMagneticDataRate"][3], "NaN");
  EXPECT_EQ(by_name["QuaternionDataRate"][1], "70");
  EXPECT_EQ(by_name["QuaternionDataRate"][2], "8");
  EXPECT_EQ(by_name["DateTimeDataRate"][2], "2");
  EXPECT_EQ(by_name["BatterySensitivity"][3], "620");
  EXPECT_EQ(by_name["AlgorithmTareQuat0"][3], "0.9999695");
  EXPECT_EQ(ReadRows(dir.path() / "t_CalInertialAndMag.csv").size(), 513u);
  EXPECT_EQ(ReadRows(dir.path() / "t_EulerAngles.csv").size(), 257u);
  EXPECT_EQ(ReadRows(dir.path() / "t_DateTime.csv").size(), 1u + 2u + 4u);  // two start-up rows, 2 Hz for 2 s
}

TEST(XimuGuiWriter, NumbersAreTheGuiTextOfTheSamples) {
  TempDir dir;
  const DeviceSamples samples = MakeSamples(300, 256.0);
  WriteXimuGuiCsv((dir.path() / "t").string(), samples, XimuGuiWriterOptions{});
  const auto inertial = ReadRows(dir.path() / "t_CalInertialAndMag.csv");
  const auto quaternion = ReadRows(dir.path() / "t_Quaternion.csv");
  const auto euler = ReadRows(dir.path() / "t_EulerAngles.csv");
  for (std::size_t n = 0; n < samples.size(); ++n) {
    ASSERT_EQ(inertial[n + 1].size(), 10u);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(inertial[n + 1][1 + i], FormatDotNetSingle(samples.gyro_dps[n][i]));
      EXPECT_EQ(inertial[n + 1][4 + i], FormatDotNetSingle(samples.accel_g[n][i]));
      EXPECT_EQ(inertial[n + 1][7 + i], FormatDotNetSingle(samples.mag_G[n][i]));
      EXPECT_EQ(euler[n + 1][1 + i], FormatDotNetSingle(samples.euler_deg[n][i]));
    }
    for (int i = 0; i < 4; ++i) EXPECT_EQ(quaternion[n + 1][1 + i], FormatDotNetSingle(samples.quaternion[n][i]));
  }
  EXPECT_EQ(inertial[3][1], "0.125");
  EXPECT_EQ(euler[1][3], "1E-05");
}

TEST(XimuGuiWriter, RotationMatrixIsTheGuiMatrixOfTheFileQuaternion) {
  TempDir dir;
  const DeviceSamples samples = MakeSamples(50, 256.0);
  WriteXimuGuiCsv((dir.path() / "t").string(), samples, XimuGuiWriterOptions{});
  const auto rows = ReadRows(dir.path() / "t_RotationMatrix.csv");
  for (std::size_t n = 0; n < samples.size(); ++n) {
    // docs/file-formats.md §1.6: R = R_Hamilton(conj(q_file)) maps sensor vectors to Earth, row-major.
    const Eigen::Vector4f& q = samples.quaternion[n];
    const Eigen::Matrix3d R = Eigen::Quaterniond(q[0], -q[1], -q[2], -q[3]).toRotationMatrix();
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(std::strtod(rows[n + 1][1 + k].c_str(), nullptr), R(k / 3, k % 3), 1e-6);
  }
}

TEST(XimuGuiWriter, LineEndingsAreLfByDefaultAndCrlfOnRequestWithoutBom) {
  TempDir dir;
  WriteXimuGuiCsv((dir.path() / "lf").string(), MakeSamples(20, 256.0), XimuGuiWriterOptions{});
  XimuGuiWriterOptions crlf;
  crlf.crlf_line_endings = true;
  WriteXimuGuiCsv((dir.path() / "crlf").string(), MakeSamples(20, 256.0), crlf);
  const std::string lf = ReadFile(dir.path() / "lf_CalInertialAndMag.csv");
  const std::string cr = ReadFile(dir.path() / "crlf_CalInertialAndMag.csv");
  EXPECT_EQ(lf.find('\r'), std::string::npos);
  EXPECT_EQ(lf.back(), '\n');
  EXPECT_EQ(lf.substr(0, 6), "Packet");  // no byte-order mark
  EXPECT_EQ(std::count(cr.begin(), cr.end(), '\n'), std::count(cr.begin(), cr.end(), '\r'));
  EXPECT_EQ(cr.substr(cr.size() - 2), "\r\n");
}

TEST(XimuGuiWriter, UnwritableDirectoryIsAnOutputErrorAndLeavesNoFiles) {
  TempDir dir;
  const fs::path missing = dir.path() / "no-such-dir" / "t";
  EXPECT_THROW(WriteXimuGuiCsv(missing.string(), MakeSamples(5, 256.0), XimuGuiWriterOptions{}), OutputError);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(XimuGuiWriter, RewritingReplacesEveryFileCompletely) {
  TempDir dir;
  const std::string prefix = (dir.path() / "t").string();
  WriteXimuGuiCsv(prefix, MakeSamples(400, 256.0), XimuGuiWriterOptions{});
  WriteXimuGuiCsv(prefix, MakeSamples(30, 256.0), XimuGuiWriterOptions{});
  EXPECT_EQ(ReadRows(dir.path() / "t_CalInertialAndMag.csv").size(), 31u);
  for (const auto& entry : fs::directory_iterator(dir.path())) EXPECT_NE(entry.path().extension(), ".tmp");
}

TEST(XimuGuiWriter, RatesThatTheDeviceCannotSendAreRejected) {
  TempDir dir;
  const std::string prefix = (dir.path() / "t").string();
  EXPECT_THROW(WriteXimuGuiCsv(prefix, MakeSamples(5, 100.0), XimuGuiWriterOptions{}), InvalidArgument);
  XimuGuiWriterOptions faster_quaternions;
  faster_quaternions.quaternion_rate_hz = 512.0;
  EXPECT_THROW(WriteXimuGuiCsv(prefix, MakeSamples(5, 256.0), faster_quaternions), InvalidArgument);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(XimuGuiWriter, CalendarTimeCountsFromTheClockResetDate) {
  const auto expect = [](std::int64_t s, CalendarTime e) {
    const CalendarTime c = CalendarTimeSince2000(s);
    EXPECT_EQ(std::vector<int>({c.year, c.month, c.day, c.hours, c.minutes, c.seconds}),
              std::vector<int>({e.year, e.month, e.day, e.hours, e.minutes, e.seconds}))
        << s;
  };
  expect(0, {2000, 1, 1, 0, 0, 0});
  expect(71, {2000, 1, 1, 0, 1, 11});
  expect(59 * 86400, {2000, 2, 29, 0, 0, 0});   // 2000 is a leap year
  expect(366 * 86400, {2001, 1, 1, 0, 0, 0});
  expect(762525296, {2024, 2, 29, 12, 34, 56});  // Python: (datetime(2024,2,29,12,34,56) − datetime(2000,1,1)).total_seconds()
  EXPECT_THROW(CalendarTimeSince2000(-1), InvalidArgument);
}

}  // namespace
}  // namespace rockfit::io
