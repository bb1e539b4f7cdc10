#include "text/csv_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "rockfit/core/errors.hpp"
#include "text/text_file.hpp"

namespace rockfit::io {
namespace {

struct Span {
  std::size_t begin = 0;
  std::size_t end = 0;
};

const char* const kNumberExample = "a number such as -0.0625 or -6.113857E-05";

bool IsBlank(std::string_view text) { return TrimSpaces(text).empty(); }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }

bool IsPadding(char c, char delimiter) { return c == ' ' || (delimiter != '\t' && c == '\t'); }

// Splits [begin, end) of `text` at `delimiter` into trimmed cells (reusing `cells`). Spaces are trimmed; with tab
// separators tabs are separators, never padding.
void SplitPlainLine(const std::string& text, Span line, char delimiter, std::vector<Span>& cells) {
  cells.clear();
  std::size_t start = line.begin;
  while (true) {
    const void* hit = std::memchr(text.data() + start, delimiter, line.end - start);
    const std::size_t stop = hit ? static_cast<std::size_t>(static_cast<const char*>(hit) - text.data()) : line.end;
    std::size_t b = start;
    std::size_t e = stop;
    while (b < e && IsPadding(text[b], delimiter)) ++b;
    while (e > b && IsPadding(text[e - 1], delimiter)) --e;
    cells.push_back({b, e});
    if (!hit) break;
    start = stop + 1;
  }
}

// A line holding '"': RFC 4180 quoting. A cell whose first non-space character is '"' runs to the next '"' that
// is not doubled; inside it separators are text and "" is one '"'. The quoted text is unescaped in place (it only
// gets shorter), so the span starts where the text does. Returns the offset of a broken quote (unterminated, or
// text after the closing quote) or npos.
std::size_t SplitQuotedLine(std::string& text, Span line, char delimiter, std::vector<Span>& cells) {
  cells.clear();
  std::size_t i = line.begin;
  while (true) {
    while (i < line.end && IsPadding(text[i], delimiter)) ++i;
    if (i < line.end && text[i] == '"') {
      const std::size_t open = i;
      const std::size_t b = i + 1;
      std::size_t out = b;
      std::size_t j = b;
      bool closed = false;
      while (j < line.end) {
        if (text[j] == '"') {
          if (j + 1 < line.end && text[j + 1] == '"') {
            text[out++] = '"';
            j += 2;
            continue;
          }
          closed = true;
          ++j;
          break;
        }
        text[out++] = text[j++];
      }
      if (!closed) return open;
      cells.push_back({b, out});
      while (j < line.end && IsPadding(text[j], delimiter)) ++j;
      if (j == line.end) return std::string::npos;
      if (text[j] != delimiter) return j;
      i = j + 1;
      continue;
    }
    const void* hit = std::memchr(text.data() + i, delimiter, line.end - i);
    const std::size_t stop = hit ? static_cast<std::size_t>(static_cast<const char*>(hit) - text.data()) : line.end;
    const std::size_t quote = text.find('"', i);
    if (quote < stop) return quote;  // a quote inside an unquoted cell
    std::size_t e = stop;
    while (e > i && IsPadding(text[e - 1], delimiter)) --e;
    cells.push_back({i, e});
    if (!hit) return std::string::npos;
    i = stop + 1;
  }
}

// Either of the two above; a broken quote throws BadInput at its line and column.
void SplitLine(std::string& text, Span line, char delimiter, std::vector<Span>& cells, const std::string& name,
               std::size_t line_number) {
  if (std::memchr(text.data() + line.begin, '"', line.end - line.begin) == nullptr) {
    SplitPlainLine(text, line, delimiter, cells);
    return;
  }
  const std::size_t broken = SplitQuotedLine(text, line, delimiter, cells);
  if (broken == std::string::npos) return;
  const bool unterminated = text[broken] == '"' && (broken == line.begin || text.find('"', broken + 1) >= line.end);
  ThrowBadInput({{name, line_number, broken - line.begin + 1},
                 "",
                 unterminated ? "a '\"' that opens a quoted field which does not end on this line"
                              : "a '\"' inside a field, or text after a field's closing '\"'",
                 "fields quoted as in RFC 4180: \"text\" with \"\" for a quote inside, and nothing between the closing "
                 "quote and the next separator",
                 "Quote the whole field and double any quote inside it (\"a \"\"b\"\" c\"), or remove the stray quote."});
}

// The separator is the most frequent of ',', ';' and tab outside quotes.
char DetectDelimiter(std::string_view header) {
  std::ptrdiff_t commas = 0, semicolons = 0, tabs = 0;
  bool quoted = false;
  for (char c : header) {
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    commas += c == ',';
    semicolons += c == ';';
    tabs += c == '\t';
  }
  if (semicolons > commas && semicolons >= tabs) return ';';
  if (tabs > commas && tabs > semicolons) return '\t';
  return ',';
}

std::string DelimiterName(char delimiter) {
  if (delimiter == '\t') return "tab";
  return std::string("'") + delimiter + "'";
}

// Offset of the comma in the first unmistakable decimal-comma number of a ','-separated line, the
// mark of an x-IMU GUI export made with a decimal-comma language: no '.' anywhere in the line, and a
// negative number "-0,125" or a fraction with a leading zero "0,0625" (integers never print as "0625").
std::optional<std::size_t> FindDecimalComma(std::string_view line) {
  if (line.find('.') != std::string_view::npos) return std::nullopt;
  for (std::size_t i = 1; i + 2 < line.size(); ++i) {
    if (line[i] != ',' || !IsDigit(line[i - 1]) || !IsDigit(line[i + 1])) continue;
    std::size_t begin = i;
    while (begin > 0 && IsDigit(line[begin - 1])) --begin;
    std::size_t end = i + 1;
    while (end < line.size() && IsDigit(line[end])) ++end;
    const bool negative = begin > 0 && line[begin - 1] == '-';
    const bool leading_zero_fraction = line[i + 1] == '0' && end - (i + 1) >= 2;
    if (negative || leading_zero_fraction) return i;
  }
  return std::nullopt;
}

}  // namespace

CsvTable CsvTable::ReadFile(const std::filesystem::path& path, std::vector<std::string>& warnings,
                            std::uint64_t max_bytes) {
  std::string text = ReadRegularFile(path, "a CSV file", max_bytes);
  return FromText(std::move(text), path.string(), warnings);
}

namespace {

constexpr const char* kExpectedLayout = "a header line naming the columns, then one line of numbers per sample";

// Refuses what is no text at all (empty, UTF-16, NUL bytes) and drops a UTF-8 byte-order mark with a warning.
void RequireReadableText(std::string* text, const std::string& name, std::vector<std::string>& warnings) {
  if (text->empty()) {
    ThrowBadInput({{name}, "", "an empty file (0 bytes)", kExpectedLayout,
                   "The recording was not written or not copied completely; copy it again from the device or "
                   "its computer."});
  }
  const std::string& t = *text;
  if (t.size() >= 2 && ((t[0] == '\xff' && t[1] == '\xfe') || (t[0] == '\xfe' && t[1] == '\xff'))) {
    ThrowBadInput({{name, 1, 1}, "", "a UTF-16 text file (byte-order mark FF FE or FE FF)", "ASCII or UTF-8 text",
                   "Save the file again as \"CSV UTF-8\" or plain CSV."});
  }
  if (t.size() >= 3 && t.compare(0, 3, "\xef\xbb\xbf") == 0) {
    text->erase(0, 3);
    warnings.push_back(name +
                       ": the file starts with a UTF-8 byte-order mark, which the IMU software never writes (the "
                       "file was re-saved by another program); the mark was ignored");
  }
  if (const std::size_t nul = text->find('\0'); nul != std::string::npos) {
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(text->begin(), text->begin() + nul, '\n'));
    ThrowBadInput({{name, line}, "", "a NUL byte (a binary file)", "a text file with comma-separated values",
                   "An x-IMU .BIN file must first be converted to CSV with the x-IMU GUI (SD card tab); "
                   "otherwise pick the CSV file."});
  }
}

// The cells of the header line (a trailing separator dropped); refuses a first line of numbers only.
void SplitHeader(std::string& body, Span line, char delimiter, const TextPosition& at, std::vector<Span>& cells) {
  SplitLine(body, line, delimiter, cells, at.file, at.line);
  if (cells.size() > 1 && cells.back().begin == cells.back().end) cells.pop_back();  // trailing separator
  for (const Span& cell : cells) {
    const std::string_view text_cell(body.data() + cell.begin, cell.end - cell.begin);
    if (ParseReal(text_cell, DecimalSeparator::kComma).status != NumberStatus::kOk &&
        ParseReal(text_cell).status != NumberStatus::kOk) {
      return;
    }
  }
  const std::string_view content(body.data() + line.begin, line.end - line.begin);
  ThrowBadInput({at, "", "numbers in the first line ('" + std::string(content.substr(0, 40)) + "')",
                 "a header line naming the columns, e.g. 'Packet number,Gyroscope X (deg/s),…'",
                 "Add the header line that the device software writes, or read the file as a generic CSV "
                 "with a header."});
}

// A data line with another number of fields than the header: names the decimal comma when that is the cause.
[[noreturn]] void ThrowWrongFieldCount(const std::string& name, std::size_t line_number, std::string_view content,
                                       std::size_t line_begin, const std::vector<Span>& cells, std::size_t columns,
                                       std::size_t header_line, char delimiter) {
  if (cells.size() > columns && delimiter == ',') {
    if (const auto comma = FindDecimalComma(content)) {
      ThrowBadInput(
          {{name, line_number, *comma + 1},
           "",
           std::to_string(cells.size()) + " fields and numbers written with a decimal comma (" + QuoteCell(content) + ")",
           std::to_string(columns) + " fields (one per header column) with decimal points",
           "The file was written with decimal commas, which x-IMU GUI versions before 13.2 do on Windows set "
           "to a language such as Hungarian or German; such rows cannot be split reliably. Export it again "
           "with x-IMU GUI 13.2 or later, or set Windows' number format to a decimal point (Region: English "
           "(United States)) before exporting. A spreadsheet may also save it with ';' between fields, which "
           "rockfit reads with decimal commas."});
    }
  }
  std::string todo = "Correct or delete line " + std::to_string(line_number) + ".";
  if (cells.size() > columns && delimiter == ',') {
    todo += " If the numbers were written with decimal commas (such as '1,25'), export the file again with "
            "decimal points.";
  }
  ThrowBadInput({{name, line_number, cells.size() > columns ? cells[columns].begin - line_begin + 1 : 1},
                 "",
                 std::to_string(cells.size()) + " fields",
                 std::to_string(columns) + " fields, one per column of the header on line " +
                     std::to_string(header_line) + ", separated by " + DelimiterName(delimiter),
                 todo});
}

}  // namespace

CsvTable CsvTable::FromText(std::string text, std::string display_name, std::vector<std::string>& warnings) {
  CsvTable table;
  table.name_ = std::move(display_name);
  const std::string& name = table.name_;
  RequireReadableText(&text, name, warnings);
  table.text_ = std::move(text);
  std::string& body = table.text_;

  const char eol = body.find('\n') != std::string::npos ? '\n' : (body.find('\r') != std::string::npos ? '\r' : '\n');
  std::vector<Span> cells;
  std::size_t line_number = 0;
  std::size_t blank_lines = 0;
  std::size_t first_blank_line = 0;
  bool have_header = false;
  bool decimal_comma_seen = false;
  std::size_t decimal_comma_line = 0;
  std::size_t start = 0;

  while (start < body.size()) {
    ++line_number;
    std::size_t end = body.find(eol, start);
    const bool terminated = end != std::string::npos;
    if (!terminated) end = body.size();
    Span line{start, end};
    if (eol == '\n' && line.end > line.begin && body[line.end - 1] == '\r') --line.end;
    start = end + 1;
    const std::string_view content(body.data() + line.begin, line.end - line.begin);

    if (IsBlank(content)) {
      if (blank_lines++ == 0) first_blank_line = line_number;
      continue;
    }

    if (!have_header) {
      have_header = true;
      table.delimiter_ = DetectDelimiter(content);
      table.header_line_ = line_number;
      table.header_line_start_ = line.begin;
      SplitHeader(body, line, table.delimiter_, {name, line_number, 1}, cells);
      for (const Span& cell : cells) {
        table.header_.emplace_back(body.data() + cell.begin, cell.end - cell.begin);
        table.header_begin_.push_back(cell.begin);
      }
      if (table.delimiter_ != ',') {
        warnings.push_back(name + ": fields are separated by " + DelimiterName(table.delimiter_) +
                           " instead of ',' (a spreadsheet's export); read with that separator");
      }
      continue;
    }

    SplitLine(body, line, table.delimiter_, cells, name, line_number);
    const std::size_t columns = table.header_.size();
    if (cells.size() == columns + 1 && cells.back().begin == cells.back().end) cells.pop_back();  // trailing separator
    if (cells.size() != columns) {
      if (!terminated && cells.size() < columns) {
        warnings.push_back(FormatPosition({name, line_number}) + ": the last line has " + std::to_string(cells.size()) +
                           " of " + std::to_string(columns) +
                           " fields and no line end: the file was cut off while being written; that line was dropped");
        break;
      }
      ThrowWrongFieldCount(name, line_number, content, line.begin, cells, columns, table.header_line_, table.delimiter_);
    }
    if (!terminated && cells.back().begin == cells.back().end && columns > 1) {
      warnings.push_back(FormatPosition({name, line_number}) +
                         ": the last line ends in an empty field and has no line end: the file was cut off while "
                         "being written; that line was dropped");
      break;
    }
    if (table.delimiter_ != ',' && !decimal_comma_seen &&
        std::memchr(body.data() + line.begin, ',', line.end - line.begin) != nullptr) {
      decimal_comma_seen = true;
      decimal_comma_line = line_number;
    }
    table.ends_with_newline_ = terminated;
    table.row_line_.push_back(line_number);
    table.row_start_.push_back(line.begin);
    for (const Span& cell : cells) {
      table.cell_begin_.push_back(cell.begin);
      table.cell_end_.push_back(cell.end);
    }
  }

  if (!have_header) {
    ThrowBadInput({{name}, "", "only blank lines", kExpectedLayout,
                   "The recording was not written or not copied completely; copy it again."});
  }
  if (blank_lines > 0) {
    warnings.push_back(FormatPosition({name, first_blank_line}) + ": " + std::to_string(blank_lines) +
                       (blank_lines == 1 ? " blank line was" : " blank lines were") + " skipped");
  }
  if (decimal_comma_seen) {
    warnings.push_back(FormatPosition({name, decimal_comma_line}) +
                       ": numbers are written with decimal commas; with " + DelimiterName(table.delimiter_) +
                       " between fields this is unambiguous and they were read as decimal points");
  }
  if (table.row_line_.empty()) {
    ThrowBadInput({{name, table.header_line_}, "", "only the header line", "at least one line of data after it",
                   "The recording holds no samples: check that the device was logging, or pick another file."});
  }
  return table;
}

TextPosition CsvTable::PositionOf(std::size_t row, std::size_t column) const {
  return {name_, row_line_[row], cell_begin_[row * header_.size() + column] - row_start_[row] + 1};
}

TextPosition CsvTable::HeaderPosition(std::size_t column) const {
  return {name_, header_line_, header_begin_[column] - header_line_start_ + 1};
}

std::string CsvTable::DescribeColumn(std::size_t column) const {
  return "column " + std::to_string(column + 1) + " '" + header_[column] + "'";
}

void CsvTable::ThrowBadCell(std::size_t row, std::size_t column, std::string found, std::string expected,
                            std::string todo) const {
  if (IsUnterminatedLastRow(row)) {
    todo += " This is the last line and the file does not end with a line end, so it was probably cut off while "
            "the file was written: delete that line.";
  }
  ThrowBadInput({PositionOf(row, column), DescribeColumn(column), std::move(found), std::move(expected),
                 std::move(todo)});
}

double CsvTable::ParseCell(std::size_t row, std::size_t column, bool allow_nan) const {
  const std::string_view cell = Cell(row, column);
  const ParsedNumber number = ParseReal(cell, decimal_separator());
  if (number.status == NumberStatus::kOk || (allow_nan && number.status == NumberStatus::kNaN)) return number.value;
  const std::string line = std::to_string(Line(row));
  switch (number.status) {
    case NumberStatus::kOk:
    case NumberStatus::kNaN:
      ThrowBadCell(row, column, QuoteCell(cell), "a finite number",
                   "The device wrote no valid value for this sample and rockfit does not invent one: export the "
                   "recording again, or cut the file before or after line " +
                       line + ".");
    case NumberStatus::kInfinite:
    case NumberStatus::kOutOfRange:
      ThrowBadCell(row, column, QuoteCell(cell), "a finite number",
                   "An IMU cannot measure an infinite value: export the recording again, or cut the file before or "
                   "after line " +
                       line + ".");
    case NumberStatus::kEmpty:
      ThrowBadCell(row, column, "an empty cell", kNumberExample, "Fill in or delete line " + line + ".");
    case NumberStatus::kDecimalComma:
      ThrowBadCell(row, column, QuoteCell(cell) + " (a decimal comma)", "a decimal point",
                   "Save the file with '.' as decimal separator, or with ';' between fields (then decimal commas are "
                   "read).");
    case NumberStatus::kNotANumber:
      break;
  }
  ThrowBadCell(row, column, QuoteCell(cell), kNumberExample, "Correct or delete line " + line + ".");
}

double CsvTable::Real(std::size_t row, std::size_t column) const { return ParseCell(row, column, false); }

double CsvTable::RealInSi(std::size_t row, std::size_t column, double to_si) const {
  const double value = Real(row, column) * to_si;
  if (!std::isfinite(value)) {
    ThrowBadCell(row, column, "a value too large to convert to SI units", "a measured value within the sensor's range",
                 "An IMU cannot measure this value: export the recording again, or cut the file before line " +
                     std::to_string(Line(row)) + ".");
  }
  return value;
}

double CsvTable::RealOrNaN(std::size_t row, std::size_t column) const { return ParseCell(row, column, true); }

std::int64_t CsvTable::Integer(std::size_t row, std::size_t column) const {
  const std::string_view cell = Cell(row, column);
  if (const auto value = ParseInteger(cell)) return *value;
  ThrowBadCell(row, column, QuoteCell(cell), "a whole number",
               "Correct or delete line " + std::to_string(Line(row)) + ".");
}

}  // namespace rockfit::io
