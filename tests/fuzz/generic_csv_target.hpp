// Fuzz target body: a generic CSV file with a column map, read as
// `rockfit inspect FILE.csv --columns MAP [--rate HZ]` reads it. The first line of the input is the
// --columns text (empty: detect x-io style headers); the rest is the CSV file. A first line that starts
// with '!' also passes --rate 256 (the '!' is not part of the map), so that files without a time column
// are reached too.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "recording_invariants.hpp"
#include "rockfit/io/column_map.hpp"
#include "rockfit/io/load_recording.hpp"

namespace rockfit::fuzz {

inline void GenericCsv(std::string_view input) {
  static const ScratchDir dir;
  const std::string_view text = input;
  const std::size_t line_end = text.find('\n');
  std::string_view columns = text.substr(0, line_end);
  const bool rate_given = !columns.empty() && columns.front() == '!';
  if (rate_given) columns.remove_prefix(1);
  const std::string_view csv = line_end == std::string_view::npos ? std::string_view{} : text.substr(line_end + 1);
  const auto file = dir.Write("recording.csv", csv);
  ExpectDocumentedOutcome([&] {
    io::LoadOptions options;
    options.format = io::RecordingFormat::kGenericCsv;
    if (rate_given) options.rate_hz = 256.0;
    if (!columns.empty()) options.columns = io::ColumnMap::Parse(columns);
    CheckRecording(io::LoadRecording(file, options));
  });
}

}  // namespace rockfit::fuzz
