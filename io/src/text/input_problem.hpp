// One way to word every bad-input message of the readers: where (file:line:column), what was found,
// what was expected, and what the user can do about it (docs/design.md §5, brief "Bad input").
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

namespace rockfit::io {

// A position in a text file. line and column are 1-based; 0 means "not known / not applicable".
// column counts bytes from the start of the line (equal to characters for ASCII files).
struct TextPosition {
  TextPosition() = default;
  TextPosition(std::string file_name, std::size_t line_number = 0, std::size_t column_number = 0)
      : file(std::move(file_name)), line(line_number), column(column_number) {}

  std::string file;
  std::size_t line = 0;
  std::size_t column = 0;
};

// "file:line:column" with the unknown parts left out ("file:line", "file").
std::string FormatPosition(const TextPosition& at);

struct InputProblem {
  TextPosition at;
  std::string subject;   // what the message is about, e.g. "column 3 'Gyroscope Y (deg/s)'"; may be empty
  std::string found;     // what the file holds, e.g. "'abc'"
  std::string expected;  // what rockfit needs there, e.g. "a number such as -0.0625"
  std::string todo;      // what the user can do, a full sentence
};

// "file:line:col: subject: found F, expected E. TODO"
std::string FormatProblem(const InputProblem& problem);

// Throws rockfit::BadInput with FormatProblem(problem).
[[noreturn]] void ThrowBadInput(const InputProblem& problem);

// Quotes a cell for a message: 'text', shortened to at most 40 characters, "an empty cell" when empty.
std::string QuoteCell(std::string_view cell);

}  // namespace rockfit::io
