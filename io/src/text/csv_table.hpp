// The CSV lexer of the readers: a delimited text file read whole and split into a header and rows of
// cells, with the file, line and column of every cell for messages. Locale-independent, allocation
// per file rather than per cell. Decisions (io/README.md, "Reading recordings"):
//  * LF, CRLF (and old-Mac CR) line ends are accepted, also mixed.
//  * A UTF-8 byte-order mark is removed with a warning (the device never writes one: the file was
//    re-saved by another program). UTF-16 files and binary files are refused.
//  * Fields may be quoted as in RFC 4180 ("Time (s)","a, b","say ""hi"""): separators inside quotes are text,
//    "" is one quote. A quoted field must end on its line (no line breaks inside fields); a stray or
//    unterminated quote is an error at its line and column.
//  * The separator is the most frequent of ',', ';' and tab outside quotes in the header line. With ';' or tab,
//    numbers may use a decimal comma (a spreadsheet's export in many languages); both are warnings.
//  * Header and data cells are trimmed of spaces ("…, Element 2" has a leading space).
//  * A trailing separator (an empty last header cell, e.g. DigitalIO) is ignored.
//  * Blank lines are skipped with a warning.
//  * The last line, when the file does not end with a line end and the line has fewer fields than
//    the header (or ends in an empty field), was cut off while the file was being written: it is
//    dropped with a warning. Any other row of the wrong length is an error.
//  * More fields than the header in a ','-file with "digit,digit" patterns: decimal commas, an error
//    that says how to re-export the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rockfit/io/input_limits.hpp"
#include "text/input_problem.hpp"
#include "text/number_parsing.hpp"

namespace rockfit::io {

class CsvTable {
 public:
  // Reads the regular file at `path` of at most `max_bytes` (text_file.hpp); messages name it as `path.string()`.
  // Throws BadInput when the file cannot be read or used (see above); documented repairs are appended to
  // `warnings`.
  static CsvTable ReadFile(const std::filesystem::path& path, std::vector<std::string>& warnings,
                           std::uint64_t max_bytes = kMaxRecordingFileBytes);
  // The same for text already in memory; `display_name` stands for the file in messages.
  static CsvTable FromText(std::string text, std::string display_name, std::vector<std::string>& warnings);

  const std::string& name() const { return name_; }
  char delimiter() const { return delimiter_; }
  DecimalSeparator decimal_separator() const {
    return delimiter_ == ',' ? DecimalSeparator::kPoint : DecimalSeparator::kComma;
  }
  std::size_t header_line() const { return header_line_; }
  const std::vector<std::string>& header() const { return header_; }
  std::size_t column_count() const { return header_.size(); }
  std::size_t row_count() const { return row_line_.size(); }

  // The trimmed text of a cell; row and column are 0-based.
  std::string_view Cell(std::size_t row, std::size_t column) const {
    const std::size_t k = row * header_.size() + column;
    return std::string_view(text_).substr(cell_begin_[k], cell_end_[k] - cell_begin_[k]);
  }
  // 1-based line number of a data row in the file.
  std::size_t Line(std::size_t row) const { return row_line_[row]; }
  TextPosition PositionOf(std::size_t row, std::size_t column) const;
  TextPosition HeaderPosition(std::size_t column) const;
  // "column 3 'Gyroscope Y (deg/s)'"
  std::string DescribeColumn(std::size_t column) const;
  // True for the last row when the file does not end with a line end (a file cut while written).
  bool IsUnterminatedLastRow(std::size_t row) const { return !ends_with_newline_ && row + 1 == row_count(); }

  // The cell as a finite real number; anything else (text, empty, NaN, Inf, decimal comma in a
  // ','-file) throws BadInput naming file, line, column and header, with what to do.
  double Real(std::size_t row, std::size_t column) const;
  // Real times the factor to SI units (ToSi); a finite value that overflows there (1e308 g) throws BadInput
  // as a non-number would: no sensor measures it.
  double RealInSi(std::size_t row, std::size_t column, double to_si) const;
  // As Real, but NaN is returned as NaN (callers that can repair it, e.g. the x-IMU pitch).
  double RealOrNaN(std::size_t row, std::size_t column) const;
  // The cell as a whole number (packet numbers, microsecond timestamps).
  std::int64_t Integer(std::size_t row, std::size_t column) const;

  // Throws BadInput about one cell: "file:line:col: column c 'header': found F, expected E. TODO".
  [[noreturn]] void ThrowBadCell(std::size_t row, std::size_t column, std::string found, std::string expected,
                                 std::string todo) const;

 private:
  CsvTable() = default;
  double ParseCell(std::size_t row, std::size_t column, bool allow_nan) const;

  std::string name_;
  std::string text_;
  char delimiter_ = ',';
  bool ends_with_newline_ = true;
  std::size_t header_line_ = 0;
  std::size_t header_line_start_ = 0;
  std::vector<std::string> header_;
  std::vector<std::size_t> header_begin_;  // offsets of header cells, for positions
  std::vector<std::size_t> row_line_;
  std::vector<std::size_t> row_start_;  // offset of each row's first character in text_
  std::vector<std::size_t> cell_begin_;
  std::vector<std::size_t> cell_end_;
};

}  // namespace rockfit::io
