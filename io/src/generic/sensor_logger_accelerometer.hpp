// The accelerometer of a Sensor Logger export, beside its gyroscope (io/README.md, "Generic CSV").
//
// Sensor Logger writes each sensor of a recording to its own file in one folder (Gyroscope.csv,
// TotalAcceleration.csv, Accelerometer.csv, Gravity.csv, …), every file with the header time,seconds_elapsed,z,y,x
// and its own times in nanoseconds since 1970: the sensors run at their own rates and are not sampled together.
// What levels the start of the attitude integrated from the gyro is the specific force with gravity included:
// TotalAcceleration.csv (m/s², +g along +z with the phone flat on its back, as an x-IMU reads it). The app's
// Accelerometer.csv holds the acceleration without gravity (the app's unit reference) and levels nothing; it is
// not read.
//
// The accelerometer is resampled onto the gyro's times by linear interpolation between its two samples around each
// gyro time (exact for a specific force that changes linearly over one accelerometer step; at rest, where it levels
// the start, the error is the sensor noise). The two files' times are compared through their first time cells,
// exactly for whole nanoseconds. Gyro samples up to kAccelerometerEdgeSteps accelerometer steps before its first or
// after its last sample take that end value (phone sensors start and stop a few milliseconds apart); anything
// further apart is two recordings, or times in different bases, and an error at the file:line of both.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "text/csv_table.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {

// The file beside a Sensor Logger Gyroscope.csv that holds the specific force.
inline constexpr const char* kSensorLoggerTotalAcceleration = "TotalAcceleration.csv";
// How many median accelerometer steps a gyro sample may lie outside the accelerometer's times (held at its end):
// phone sensors start a few samples apart; more is another recording or another time base.
inline constexpr double kAccelerometerEdgeSteps = 2.0;

struct SensorLoggerAccelerometer {
  std::vector<Eigen::Vector3d> accel_S;  // specific force at every gyro sample [m/s²], sensor axes
  std::vector<std::string> columns;      // "TotalAcceleration.csv: x", …
  std::vector<std::string> notes;        // what was read and how, for `rockfit inspect`
};

// `accel` is a Sensor Logger sensor file (time, x, y, z in m/s²); `gyro` the gyroscope file, its time column
// `gyro_time_column` in `time_unit`, read as `gyro_t_s` (relative to its first row). Throws BadInput (file:line:
// column) for a missing column, a time that does not increase, or times that do not cover the gyro's (see above).
SensorLoggerAccelerometer ResampleSensorLoggerAccelerometer(const CsvTable& accel, const CsvTable& gyro,
                                                            std::size_t gyro_time_column, TimeUnit time_unit,
                                                            const std::vector<double>& gyro_t_s);

}  // namespace rockfit::io
