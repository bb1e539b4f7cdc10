// The crafted bad-file corpus (docs/design.md §12): one small recording per case, written into a
// scratch directory by the io tests (LoadRecording) and the CLI tests (rockfit inspect). Each case
// names the fragments its message must contain: the file, "line:column" where one applies, what was
// found. Cases marked `repaired` load, with the fragments in a warning (a documented repair).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "imu_test_files.hpp"

namespace rockfit::testing {

struct BadRecordingCase {
  std::string name;
  std::vector<std::pair<std::string, std::string>> files;  // relative path → exact bytes
  std::string load;                                         // relative path to read
  std::vector<std::string> args;                            // rockfit inspect options, e.g. {"--rate", "256"}
  std::vector<std::string> fragments;                       // expected in the message (or in a warning)
  bool repaired = false;
};

// "name:line:column" of the first `needle` on line `line` (1-based) of `text`, found in the text
// itself so that the expectation does not come from the code under test.
inline std::string At(const std::string& name, const std::string& text, std::size_t line, const std::string& needle) {
  std::size_t start = 0;
  for (std::size_t k = 1; k < line; ++k) start = text.find('\n', start) + 1;
  const std::size_t end = text.find('\n', start);
  const std::size_t column = text.substr(start, end - start).find(needle) + 1;
  return name + ":" + std::to_string(line) + ":" + std::to_string(column) + ":";
}

inline std::vector<BadRecordingCase> BadRecordingCorpus() {
  const std::string kInertial = "LoggedData_CalInertialAndMag.csv";
  const std::string kEuler = "LoggedData_EulerAngles.csv";
  const std::string h = kGuiInertialHeader + "\n";
  const std::string row2 = "0,-0.125,-0.0625,0.125,-0.02880859,0.01660156,1.01709,15.99951,15.99951,15.11475\n";
  const std::string row3 = "2,-0.125,-0.25,0,0.002441406,-0.002441406,0.9736328,15.99951,15.99951,15.09375\n";
  const std::string row4 = "4,-0.0625,-0.1875,0,0.006347656,0.01660156,0.9892578,15.99951,15.99951,15.09375\n";
  const std::string good = h + row2 + row3 + row4;
  const std::vector<std::string> rate = {"--rate", "256"};
  const std::string x3 = "x3/Inertial.csv";
  std::vector<BadRecordingCase> cases;
  auto add = [&cases](BadRecordingCase c) { cases.push_back(std::move(c)); };

  add({"empty_file", {{kInertial, ""}}, "LoggedData", rate, {kInertial + ": found an empty file (0 bytes)"}});
  add({"header_only", {{kInertial, h}}, "LoggedData", rate, {kInertial + ":1: found only the header line"}});
  {
    std::string text = good;
    text.replace(text.find("Gyroscope Y"), 11, "Gyroscop Y");
    add({"misspelled_header", {{kInertial, text}}, "LoggedData", rate,
         {At(kInertial, text, 1, "Gyroscop Y"), "found the header 'Gyroscop Y (deg/s)'", "'Gyroscope Y (deg/s)'"}});
  }
  {
    std::string text = kGuiInertialHeader.substr(0, kGuiInertialHeader.find(",Gyroscope Z")) +
                       kGuiInertialHeader.substr(kGuiInertialHeader.find(",Accelerometer X")) + "\n" +
                       "0,-0.125,-0.0625,-0.02880859,0.01660156,1.01709,15.99951,15.99951,15.11475\n";
    add({"missing_column", {{kInertial, text}}, "LoggedData", rate,
         {kInertial + ":1: found the header", "expected a column 'Gyroscope Z (deg/s)'"}});
  }
  {
    std::string text = h + row2 + "2,-0.125,abc,0,0.002441406,-0.002441406,0.9736328,15.99951,15.99951,15.09375\n" + row4;
    add({"non_numeric_cell", {{kInertial, text}}, "LoggedData", rate,
         {At(kInertial, text, 3, "abc"), "column 3 'Gyroscope Y (deg/s)'", "found 'abc'"}});
  }
  {
    const std::string text = h + "0,-0,125,-0,0625,0,125,-0,02880859,0,01660156,1,01709,15,99951,15,99951,15,11475\n";
    add({"decimal_commas", {{kInertial, text}}, "LoggedData", rate,
         {kInertial + ":2:5:", "decimal comma", "expected 10 fields"}});
  }
  {
    std::string text = h + "0,NaN,-0.0625,0.125,-0.02880859,0.01660156,1.01709,15.99951,15.99951,15.11475\n" + row3;
    add({"nan_in_gyro", {{kInertial, text}}, "LoggedData", rate,
         {At(kInertial, text, 2, "NaN"), "column 2 'Gyroscope X (deg/s)'", "found 'NaN', expected a finite number"}});
  }
  {
    std::string text = h + row2 + row3 + "4,-0.0625,-0.1875,0,0.006347656,0.01660156,Infinity,15.99951,15.99951,15.09375\n";
    add({"infinity_in_accel", {{kInertial, text}}, "LoggedData", rate,
         {At(kInertial, text, 4, "Infinity"), "column 7 'Accelerometer Z (g)'", "found 'Infinity'"}});
  }
  {
    const std::string euler = kGuiEulerHeader + "\n1,0.6381553,0.1729865,0.3898116\n3,0.6381434,NaN,0.3897921\n";
    add({"nan_pitch_without_quaternion", {{kInertial, good}, {kEuler, euler}}, "LoggedData", rate,
         {At(kEuler, euler, 3, "NaN"), "found 'NaN', expected a finite pitch", "_Quaternion.csv"}});
  }
  add({"truncated_last_line", {{kInertial, good + "6,-0.0625,-0.18"}}, "LoggedData", rate,
       {kInertial + ":5: the last line has 3 of 10 fields and no line end", "dropped"}, true});
  add({"truncated_line_inside", {{kInertial, h + row2 + "2,-0.125,-0.25\n" + row4}}, "LoggedData", rate,
       {kInertial + ":3:1: found 3 fields, expected 10 fields"}});
  add({"utf8_bom", {{kInertial, "\xef\xbb\xbf" + good}}, "LoggedData", rate, {kInertial, "byte-order mark"}, true});
  {
    std::string crlf;
    for (char c : good) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    add({"crlf_line_ends", {{kInertial, crlf}}, "LoggedData", rate, {}, true});
  }
  {
    const std::string line3 = "2,-0.125,-0.25,0,0.002441406,-0.002441406,0.9736328,15.99951,15.99951,15.09375,7";
    const std::string extra_column = std::to_string(line3.rfind(',') + 2);  // where the 11th field starts
    add({"row_too_long", {{kInertial, h + row2 + line3 + "\n"}}, "LoggedData", rate,
         {kInertial + ":3:" + extra_column + ":", "found 11 fields, expected 10 fields"}});
  }
  add({"semicolons_and_decimal_commas",
       {{kInertial, "Packet number;Gyroscope X (deg/s);Gyroscope Y (deg/s);Gyroscope Z (deg/s);Accelerometer X (g);"
                    "Accelerometer Y (g);Accelerometer Z (g)\n0;-0,125;-0,0625;0,125;0;0;1\n2;0;0;0;0;0;1\n"}},
       "LoggedData", rate, {"separated by ';'", "decimal commas"}, true});
  add({"utf16_file", {{kInertial, std::string("\xff\xfeP\0a\0", 6)}}, "LoggedData", rate, {kInertial + ":1:1:", "UTF-16"}});
  add({"binary_file", {{kInertial, h + std::string("\x01\x02\0\x03", 4)}}, "LoggedData", rate, {kInertial + ":2:", "NUL byte"}});
  add({"no_header_line", {{kInertial, row2 + row3}}, "LoggedData", rate, {kInertial + ":1:1:", "a header line"}});
  {
    std::string text = h + row2 + "0,-0.125,-0.25,0,0.002441406,-0.002441406,0.9736328,15.99951,15.99951,15.09375\n";
    add({"duplicated_packet_number", {{kInertial, text}}, "LoggedData", rate,
         {kInertial + ":3:1:", "'0' again (as on line 2)"}});
  }
  {
    std::string text = good + "3,0,0,0,0,0,1,0,0,0\n";
    add({"non_monotonic_packet_number", {{kInertial, text}}, "LoggedData", rate,
         {kInertial + ":5:1:", "'3', smaller than '4' on line 4"}});
  }
  add({"packet_number_in_two_files",
       {{kInertial, good}, {kEuler, kGuiEulerHeader + "\n1,0,0,0\n2,0,0,0\n"}}, "LoggedData", rate,
       {kEuler, "packet number 2, which is also an inertial packet"}});
  add({"rate_undetermined", {{kInertial, good}}, "LoggedData", {},
       {kInertial + ": found no LoggedData_Registers.csv beside it", "--rate HZ"}});
  add({"rate_registers_vs_option",
       {{kInertial, good}, {"LoggedData_Registers.csv", kGuiRegistersHeader + "\n70,69,9,NaN,InertialAndMagneticDataRate\n"}},
       "LoggedData", {"--rate", "128"},
       {"LoggedData_Registers.csv:2:7:", "found 9 (256 Hz), expected the rate given with --rate (128 Hz)"}});
  {
    const GuiSpin spin = MakeGuiSpin(256 * 5, 256.0, 30.0);
    add({"rate_registers_vs_clock",
         {{kInertial, spin.inertial}, {"LoggedData_DateTime.csv", spin.date_time},
          {"LoggedData_Registers.csv", kGuiRegistersHeader + "\n1,69,8,NaN,InertialAndMagneticDataRate\n"}},
         "LoggedData", {},
         {"LoggedData_DateTime.csv: found 256 inertial rows per real-time-clock second",
          "expected 128 rows per second, the rate from the registers"}});
  }
  {
    const GuiSpin spin = MakeGuiSpin(64, 256.0, 30.0, 2);
    add({"rate_registers_vs_attitude_rows",
         {{kInertial, spin.inertial}, {kEuler, spin.euler},
          {"LoggedData_Registers.csv", kGuiRegistersHeader + "\n1,69,9,NaN,InertialAndMagneticDataRate\n"
                                                             "1,70,9,NaN,QuaternionDataRate\n"}},
         "LoggedData", {},
         {"LoggedData_Registers.csv:3:6:", "QuaternionDataRate (register 70): found 9 (256 Hz)"}});
  }
  add({"ximu3_duplicated_timestamp", {{x3, MakeXimu3Inertial({19990, 0, 19990})}}, "x3", {},
       {"Inertial.csv:4:1:", "'19170784' again (as on line 3)"}});
  add({"ximu3_non_monotonic_timestamp", {{x3, MakeXimu3Inertial({19990, 19990, -30000})}}, "x3", {},
       {"Inertial.csv:5:1:", "smaller than"}});
  add({"ximu3_rate_mismatch", {{x3, MakeXimu3Inertial({20000, 20000, 20000})}}, "x3", {"--rate", "256"},
       {"Inertial.csv:1:1:", "i.e. 50 Hz", "expected the rate given with --rate (256 Hz)"}});
  add({"generic_csv_without_time_or_rate", {{"g.csv", "Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)\n1,2,3\n"}},
       "g.csv", {}, {"g.csv:1: found no time column", "--rate HZ"}});
  add({"generic_csv_unit_contradiction",
       {{"g.csv", "t (s),Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)\n0,1,2,3\n0.1,1,2,3\n"}}, "g.csv",
       {"--columns", "time=t (s)@s;gyro=Gyroscope X (deg/s),Gyroscope Y (deg/s),Gyroscope Z (deg/s)@rad/s"},
       {"g.csv:1:7: column 2 'Gyroscope X (deg/s)': found the unit 'deg/s', expected 'rad/s'"}});
  add({"generic_csv_unrecognised_columns", {{"g.csv", "a,b,c\n1,2,3\n"}}, "g.csv", {"--rate", "100"},
       {"g.csv:1: found no gyroscope columns that rockfit recognises", "--columns"}});
  add({"quaternion_not_unit",
       {{kInertial, good}, {"LoggedData_Quaternion.csv", kGuiQuaternionHeader + "\n1,0.5,0,0,0\n3,1,0,0,0\n"}},
       "LoggedData", rate, {"LoggedData_Quaternion.csv:2:3:", "a quaternion of norm 0.5"}});
  add({"raw_counts_only", {{"LoggedData_RawInertialAndMag.csv", "Packet number,Gyroscope X (lsb)\n0,1\n"}}, "LoggedData",
       rate, {"LoggedData_RawInertialAndMag.csv", "only raw sensor counts (lsb)"}});
  add({"not_there", {}, "nothing_here", rate, {"nothing_here: found no such file, directory or x-IMU prefix"}});
  return cases;
}

}  // namespace rockfit::testing
