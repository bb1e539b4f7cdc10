// The parts of the longest dotted key or table name in a TOML text, counted without parsing it: the TOML parser
// recurses once per part, and a key of tens of thousands of parts (`a.a.a…`) overflows its stack. Strings and
// comments are skipped; a number such as 1.5 counts as a key of two parts, which is harmless.
#pragma once

#include <cstddef>
#include <string_view>

namespace rockfit::io {

struct DottedKeyDepth {
  std::size_t parts = 0;   // of the first key that has more than the limit, else of the longest key
  std::size_t line = 0;    // 1-based line and column of the dot that went over the limit, 0 when none did
  std::size_t column = 0;
};

// Scans `text` and stops at the first dotted key of more than `max_parts` parts.
DottedKeyDepth FindDeepDottedKey(std::string_view text, std::size_t max_parts);

}  // namespace rockfit::io
