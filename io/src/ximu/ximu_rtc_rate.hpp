// A cross-check of the x-IMU GUI rate with "<prefix>_DateTime.csv", the device's real-time clock
// (1 s resolution; docs/file-formats.md §1.4): the number of inertial packets between two
// consecutive changes of the clock's second is the inertial rate, unless packets were lost.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "text/csv_table.hpp"

namespace rockfit::io {

struct RtcRateEstimate {
  double rows_per_second = 0.0;  // median number of inertial rows per clock second
  std::size_t seconds = 0;       // whole clock seconds counted
};

// `inertial_packets`: the packet numbers of the inertial rows (increasing). Uses only intervals in
// which the clock advanced by exactly one second. std::nullopt when fewer than two such seconds.
// Throws BadInput for unreadable DateTime cells (callers may turn that into a warning).
std::optional<RtcRateEstimate> EstimateRateFromDateTime(const CsvTable& date_time,
                                                        const std::vector<double>& inertial_packets);

}  // namespace rockfit::io
