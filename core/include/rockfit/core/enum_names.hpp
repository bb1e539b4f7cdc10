// The inverse of an enum's ToString: every enum whose values are written to a file or a JSON document has a
// `const char* ToString(E)` and a `bool FromString(std::string_view, E*)` beside it, so that a value rockfit wrote
// can be read back or given back as an option. This is the one way those FromString functions are made.
#pragma once

#include <cstddef>
#include <string_view>

namespace rockfit::core {

// The value among `values` whose ToString is `text`: true and *out set, or false and *out untouched.
template <class Enum, std::size_t N>
bool FromStringAmong(std::string_view text, const Enum (&values)[N], Enum* out) {
  for (const Enum value : values) {
    if (text == ToString(value)) {
      *out = value;
      return true;
    }
  }
  return false;
}

}  // namespace rockfit::core
