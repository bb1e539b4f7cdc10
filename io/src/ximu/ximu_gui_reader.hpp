// Reader of the original x-IMU GUI CSV set (docs/design.md §5; docs/file-formats.md §1):
// <prefix>_CalInertialAndMag.csv with <prefix>_EulerAngles.csv, _Quaternion.csv or
// _RotationMatrix.csv. Decisions (io/README.md, "Reading recordings"):
//  * Time is t_k = k / f_s per inertial row. Packet numbers are not time: they count packets of all
//    types and do not reveal lost packets. They must increase strictly (else BadInput).
//  * f_s from register 69 in _Registers.csv when present, else LoadOptions::rate_hz (--rate or the
//    manifest), else BadInput. Both given and different: BadInput. _DateTime.csv, when present,
//    cross-checks the rate (a different power of two: BadInput; lost packets: a warning).
//  * Each attitude row belongs to the inertial row with the largest smaller packet number (the
//    device computes the quaternion right after that inertial sample), i.e. to that row's time.
//    Attitude at a lower rate is interpolated (slerp) onto every inertial row; at a higher rate the
//    first attitude row after each inertial row is used. Register 70 (or the ratio of rows) gives its rate.
//  * _Quaternion.csv holds the Earth relative to the sensor, the conjugate of q_WS;
//    _RotationMatrix.csv is R_WS row by row; _EulerAngles.csv is ZYX (roll φx, pitch φy, yaw φz) of R_WS.
//  * A NaN pitch (the GUI writes it at ±90°) is recomputed from the quaternion of the same packet
//    when _Quaternion.csv exists (warning), else BadInput.
//  * Gyroscope samples at the full scale of register 8 are clipped: a warning counts them.
#pragma once

#include "rockfit/io/load_options.hpp"
#include "rockfit/io/recording.hpp"
#include "ximu/ximu_gui_file_set.hpp"

namespace rockfit::io {

// Relative mismatch of two rate estimates beyond which they disagree: a factor-2 mistake is 50 %
// or 100 %; lost packets of a usable recording stay far below.
inline constexpr double kRateMismatchTolerance = 0.2;
// Fewer inertial rows per clock second than (1 − this) × rate: packets were lost, warn.
inline constexpr double kLostPacketTolerance = 0.01;
// A gyroscope sample within one fixed-point step (Q4: 1/16 °/s) of the full scale of register 8 is
// at the rail, i.e. clipped; the reader warns about such samples.
inline constexpr double kGyroscopeRailMargin_dps = 0.0625;
// |‖q‖ − 1| beyond this is not a printed unit quaternion (Q15 and 7 digits give < 1e-4).
inline constexpr double kQuaternionNormTolerance = 0.01;

Recording ReadXimuGuiRecording(const XimuGuiFileSet& files, const LoadOptions& options);

}  // namespace rockfit::io
