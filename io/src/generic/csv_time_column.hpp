// The time column of a generic CSV file, as loggers and phone apps write it (io/README.md, "Generic CSV"):
// seconds, milliseconds, microseconds or nanoseconds; relative (since the start or since boot) or absolute (Unix
// epoch, e.g. Sensor Logger's nanoseconds since 1970, 1.7·10^18); whole numbers read exactly as 64-bit integers and
// taken relative to the first before any rounding to double; and counters that wrap, as Arduino's millis() and
// micros() do at 2^32 (and 16-bit timers at 2^16). A wrap is accepted only where the counter drops and the step
// across the wrap, v_k + 2^b − v_{k−1}, is no longer than kWrapStepFactor times the longest step before it; every
// wrap is reported. Anything else that does not increase is an error at the cell's file:line:column.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "text/csv_table.hpp"
#include "rockfit/io/units.hpp"

namespace rockfit::io {

// A step across a wrap may be this many times the longest step before it (a sample lost at the wrap is fine; a
// counter that restarts somewhere else is another recording).
inline constexpr double kWrapStepFactor = 10.0;
// Times whose first value is at least this many seconds are absolute (Unix epoch): 10^8 s is March 1973, longer than
// any logger runs since boot.
inline constexpr double kEpochThreshold_s = 1e8;

struct CsvTimeColumn {
  std::vector<double> t_s;        // relative to the first sample [s]
  bool absolute = false;          // Unix epoch times
  std::size_t wraps = 0;          // how often the counter wrapped
  std::uint64_t wrap_modulus = 0; // 2^16 or 2^32 when it did
  std::vector<std::string> notes; // what was recognised, for `rockfit inspect`
};

// Reads `column` of `table` in `unit`. Throws BadInput (file:line:column) for a cell that is no number, a repeated
// time, or a time that goes backwards other than by a counter's wrap.
CsvTimeColumn ReadCsvTimeColumn(const CsvTable& table, std::size_t column, TimeUnit unit);

}  // namespace rockfit::io
