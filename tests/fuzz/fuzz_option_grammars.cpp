// libFuzzer target: the --columns and --mounting option grammars (io::ColumnMap::Parse,
// io::Mounting::Parse). Beyond "no crash, only documented errors", whatever parses must round-trip:
// ColumnMap::ToString parses back to the same text, and Mounting::text() parses back to the same
// rotation (the canonical text keeps 9 significant digits).
#include <cstddef>
#include <cstdint>

#include "option_grammars_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::OptionGrammars(rockfit::fuzz::AsText(data, size));
  return 0;
}
