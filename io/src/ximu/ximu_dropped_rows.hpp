// Inertial rows missing from an x-IMU GUI set, seen through the attitude packets (docs/file-formats.md §1).
//
// The device sends one attitude (quaternion) packet per inertial packet when both rates are equal, and the GUI
// numbers every packet it writes from one counter: between two consecutive inertial rows there is then exactly
// one attitude packet. Where k ≥ 2 attitude packets lie between two inertial rows, k − 1 inertial rows are
// missing there (a packet lost on the link, or a row removed from the file), and the time base k/f_s would
// shift everything after it by that many samples. The rule is applied only when the files interleave one to
// one almost everywhere (a slower or faster attitude rate, or packet numbers that do not interleave, say
// nothing about the inertial rows).
#pragma once

#include <cstddef>
#include <vector>

namespace rockfit::io {

struct MissingRows {
  std::size_t after_index = 0;  // inertial row after which rows are missing
  std::size_t missing = 0;      // how many
};

// `inertial_packets`, `attitude_packets`: the packet numbers of the two files, each increasing. Empty when the
// files do not interleave one to one in at least kOneToOneFraction of the intervals between inertial rows.
std::vector<MissingRows> FindMissingInertialRows(const std::vector<double>& inertial_packets,
                                                 const std::vector<double>& attitude_packets);

// The sample times of n rows at rate_hz with the missing rows skipped: t_k = (k + rows missing before k)/f_s.
std::vector<double> TimesWithMissingRows(std::size_t n, double rate_hz, const std::vector<MissingRows>& missing);

}  // namespace rockfit::io
