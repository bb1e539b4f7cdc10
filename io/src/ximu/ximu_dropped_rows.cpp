#include "ximu/ximu_dropped_rows.hpp"

#include <algorithm>

namespace rockfit::io {
namespace {

// The files interleave one to one when at least this fraction of the intervals between consecutive inertial
// rows holds exactly one attitude packet (a few lost packets of either kind leave it far above; an attitude
// rate of half or twice the inertial one far below).
constexpr double kOneToOneFraction = 0.9;

}  // namespace

std::vector<MissingRows> FindMissingInertialRows(const std::vector<double>& inertial_packets,
                                                 const std::vector<double>& attitude_packets) {
  const std::size_t n = inertial_packets.size();
  if (n < 2 || attitude_packets.empty()) return {};
  std::vector<std::size_t> between(n - 1, 0);  // attitude packets between rows k and k + 1
  std::size_t j = static_cast<std::size_t>(
      std::upper_bound(attitude_packets.begin(), attitude_packets.end(), inertial_packets.front()) - attitude_packets.begin());
  for (std::size_t k = 0; k + 1 < n; ++k) {
    while (j < attitude_packets.size() && attitude_packets[j] < inertial_packets[k + 1]) {
      if (attitude_packets[j] > inertial_packets[k]) ++between[k];
      ++j;
    }
  }
  const auto one = static_cast<double>(std::count(between.begin(), between.end(), std::size_t{1}));
  if (one < kOneToOneFraction * static_cast<double>(n - 1)) return {};
  std::vector<MissingRows> out;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (between[k] >= 2) out.push_back({k, between[k] - 1});
  }
  return out;
}

std::vector<double> TimesWithMissingRows(std::size_t n, double rate_hz, const std::vector<MissingRows>& missing) {
  std::vector<double> t_s(n);
  std::size_t skipped = 0;
  auto next = missing.begin();
  for (std::size_t k = 0; k < n; ++k) {
    t_s[k] = static_cast<double>(k + skipped) / rate_hz;
    while (next != missing.end() && next->after_index == k) skipped += (next++)->missing;
  }
  return t_s;
}

}  // namespace rockfit::io
