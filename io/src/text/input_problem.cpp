#include "text/input_problem.hpp"

#include <string_view>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

std::string FormatPosition(const TextPosition& at) {
  std::string text = at.file;
  if (at.line > 0) {
    text += ":" + std::to_string(at.line);
    if (at.column > 0) text += ":" + std::to_string(at.column);
  }
  return text;
}

std::string FormatProblem(const InputProblem& problem) {
  std::string head = FormatPosition(problem.at);
  if (!problem.subject.empty()) head += (head.empty() ? "" : ": ") + problem.subject;
  std::string body;
  if (!problem.found.empty()) body = "found " + problem.found;
  if (!problem.expected.empty()) body += (body.empty() ? "expected " : ", expected ") + problem.expected;
  std::string text = head.empty() || body.empty() ? head + body : head + ": " + body;
  text += ".";
  if (!problem.todo.empty()) text += " " + problem.todo;
  return text;
}

void ThrowBadInput(const InputProblem& problem) { throw BadInput(FormatProblem(problem)); }

std::string QuoteCell(std::string_view cell) {
  constexpr std::size_t kMaxQuoted = 40;  // characters; longer cells are cut so the message stays one line
  if (cell.empty()) return "an empty cell";
  std::string text;
  for (char c : cell.substr(0, kMaxQuoted)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      static const char* const kHex = "0123456789abcdef";
      text += "\\x";
      text += kHex[byte >> 4];
      text += kHex[byte & 0xf];
    } else {
      text += c;
    }
  }
  if (cell.size() > kMaxQuoted) text += "…";
  return "'" + text + "'";
}

}  // namespace rockfit::io
