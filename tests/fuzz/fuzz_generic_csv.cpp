// libFuzzer target: a generic CSV file with a column map, read as
// `rockfit inspect FILE.csv --columns MAP [--rate HZ]` reads it. The first line of the input is the
// --columns text (empty: detect x-io style headers); the rest is the CSV file. A first line that starts
// with '!' also passes --rate 256 (the '!' is not part of the map), so that files without a time column
// are reached too.
#include <cstddef>
#include <cstdint>

#include "generic_csv_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::GenericCsv(rockfit::fuzz::AsText(data, size));
  return 0;
}
