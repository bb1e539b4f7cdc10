#include "ximu/ximu_rtc_rate.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "text/column_lookup.hpp"

namespace rockfit::io {

std::optional<RtcRateEstimate> EstimateRateFromDateTime(const CsvTable& date_time,
                                                        const std::vector<double>& inertial_packets) {
  const auto columns = ResolveColumns(date_time, {{{"Packet number"}, "the shared packet counter"},
                                                  {{"Day"}, "the day of the month"},
                                                  {{"Hours"}, "hours"},
                                                  {{"Minutes"}, "minutes"},
                                                  {{"Seconds"}, "seconds"}});
  // Packet number at which each new clock second was first seen, and that second.
  std::vector<double> change_packet;
  std::vector<std::int64_t> change_second;
  std::int64_t previous = 0;
  // A field outside its clock range is a damaged file (and would overflow the count of seconds below).
  const auto field = [&](std::size_t row, std::size_t column, std::int64_t lo, std::int64_t hi, const char* what) {
    const std::int64_t v = date_time.Integer(row, column);
    if (v < lo || v > hi) {
      date_time.ThrowBadCell(row, column, std::to_string(v), fmt::format("{} from {} to {}", what, lo, hi),
                             "The date-time file is damaged: remove it to use the register rate alone.");
    }
    return v;
  };
  for (std::size_t row = 0; row < date_time.row_count(); ++row) {
    const std::int64_t second = ((field(row, *columns[1], 0, 31, "a day of the month") * 24 +
                                  field(row, *columns[2], 0, 23, "an hour")) * 60 +
                                 field(row, *columns[3], 0, 59, "a minute")) * 60 +
                                field(row, *columns[4], 0, 60, "a second");
    if (row > 0 && second != previous) {
      change_packet.push_back(static_cast<double>(date_time.Integer(row, *columns[0])));
      change_second.push_back(second);
    }
    previous = second;
  }
  std::vector<double> counts;
  for (std::size_t k = 0; k + 1 < change_packet.size(); ++k) {
    if (change_second[k + 1] - change_second[k] != 1) continue;
    if (change_packet[k] < inertial_packets.front() || change_packet[k + 1] > inertial_packets.back()) continue;
    const auto from = std::upper_bound(inertial_packets.begin(), inertial_packets.end(), change_packet[k]);
    const auto to = std::upper_bound(inertial_packets.begin(), inertial_packets.end(), change_packet[k + 1]);
    counts.push_back(static_cast<double>(to - from));
  }
  if (counts.size() < 2) return std::nullopt;
  std::sort(counts.begin(), counts.end());
  const std::size_t mid = counts.size() / 2;
  const double median = counts.size() % 2 ? counts[mid] : 0.5 * (counts[mid - 1] + counts[mid]);
  return RtcRateEstimate{median, counts.size()};
}

}  // namespace rockfit::io
