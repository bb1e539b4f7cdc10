#include "recording/toml_key_depth.hpp"

#include <algorithm>

namespace rockfit::io {

DottedKeyDepth FindDeepDottedKey(std::string_view text, std::size_t max_parts) {
  enum class State { kCode, kComment, kBasic, kLiteral, kMultiBasic, kMultiLiteral };
  State state = State::kCode;
  DottedKeyDepth deepest;
  std::size_t dots = 0;  // dots in the key being read
  std::size_t line = 1;
  std::size_t line_start = 0;
  const auto starts = [&text](std::size_t i, std::string_view what) { return text.substr(i, what.size()) == what; };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      line_start = i + 1;
    }
    switch (state) {
      case State::kComment:
        if (c == '\n') state = State::kCode;
        continue;
      case State::kBasic:
        if (c == '\\') ++i;  // an escaped character, e.g. \"
        else if (c == '"' || c == '\n') state = State::kCode;
        continue;
      case State::kLiteral:
        if (c == '\'' || c == '\n') state = State::kCode;
        continue;
      case State::kMultiBasic:
        if (c == '\\') ++i;
        else if (starts(i, "\"\"\"")) state = State::kCode, i += 2;
        continue;
      case State::kMultiLiteral:
        if (starts(i, "'''")) state = State::kCode, i += 2;
        continue;
      case State::kCode:
        break;
    }
    switch (c) {
      case '#': state = State::kComment; break;
      case '"':
        state = starts(i, "\"\"\"") ? State::kMultiBasic : State::kBasic;
        if (state == State::kMultiBasic) i += 2;
        break;
      case '\'':
        state = starts(i, "'''") ? State::kMultiLiteral : State::kLiteral;
        if (state == State::kMultiLiteral) i += 2;
        break;
      case '.':
        ++dots;
        deepest.parts = std::max(deepest.parts, dots + 1);
        if (dots + 1 > max_parts) {
          deepest.line = line;
          deepest.column = i - line_start + 1;
          return deepest;
        }
        break;
      case '\n': case '=': case ',': case '[': case ']': case '{': case '}':
        dots = 0;
        break;
      default:
        break;
    }
  }
  return deepest;
}

}  // namespace rockfit::io
