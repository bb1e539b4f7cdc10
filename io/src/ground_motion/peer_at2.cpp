#include "rockfit/io/peer_at2.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/io/input_limits.hpp"
#include "text/input_problem.hpp"
#include "text/number_parsing.hpp"
#include "text/text_file.hpp"

namespace rockfit::io {
namespace {

// The NPTS line is searched for in this many lines from the top (PEER and NGA headers have four).
constexpr std::size_t kMaxHeaderLines = 10;

std::string Upper(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return out;
}

// Lines without their line ends (LF, CRLF, CR CR LF, lone CR).
std::vector<std::string_view> SplitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(begin, end - begin);
    while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    begin = end + 1;
  }
  return lines;
}

// The token after `key=` in an upper-cased line, or empty.
std::string_view ValueAfter(std::string_view upper_line, std::string_view key, std::size_t* column) {
  const std::size_t at = upper_line.find(key);
  if (at == std::string_view::npos) return {};
  std::size_t p = upper_line.find('=', at + key.size());
  if (p == std::string_view::npos) return {};
  ++p;
  while (p < upper_line.size() && (upper_line[p] == ' ' || upper_line[p] == '\t')) ++p;
  std::size_t e = p;
  while (e < upper_line.size() && upper_line[e] != ',' && upper_line[e] != ' ' && upper_line[e] != '\t') ++e;
  *column = p + 1;
  return upper_line.substr(p, e - p);
}

struct Header {
  std::size_t line_index = 0;  // 0-based line of NPTS
  long long npts = -1;
  double dt_s = 0.0;
};

[[noreturn]] void ThrowBadHeader(const std::string& name, std::size_t line, std::size_t column,
                                 const std::string& found, const std::string& expected) {
  ThrowBadInput({{name, line, column}, "AT2 header", found, expected,
                 "Check that this is a PEER AT2 acceleration record (a header line such as `NPTS=  4000, DT= .01000 "
                 "SEC` before the values); other formats can be read as CSV (--record-format csv)."});
}

Header ParseHeaderLine(const std::string& name, std::size_t index, std::string_view line) {
  const std::string upper = Upper(line);
  Header h;
  h.line_index = index;
  std::size_t npts_col = 0;
  std::size_t dt_col = 0;
  std::string_view npts_text = ValueAfter(upper, "NPTS", &npts_col);
  std::string_view dt_text = ValueAfter(upper, "DT", &dt_col);
  if (npts_text.empty() && dt_text.empty()) {
    // NGA form: "7998   0.0050   NPTS, DT".
    std::istringstream in{std::string(line)};
    std::string a, b;
    in >> a >> b;
    npts_col = 1;
    dt_col = line.find(b) + 1;
    const auto n = ParseInteger(a);
    const ParsedNumber d = ParseReal(b);
    if (!n) ThrowBadHeader(name, index + 1, npts_col, QuoteCell(a), "the number of points before `NPTS, DT`");
    if (d.status != NumberStatus::kOk)
      ThrowBadHeader(name, index + 1, dt_col, QuoteCell(b), "the time step in seconds");
    h.npts = *n;
    h.dt_s = d.value;
  } else {
    const auto n = ParseInteger(npts_text);
    if (!n) ThrowBadHeader(name, index + 1, npts_col, QuoteCell(npts_text), "a whole number after NPTS=");
    const ParsedNumber d = ParseReal(dt_text);
    if (d.status != NumberStatus::kOk) {
      ThrowBadHeader(name, index + 1, dt_col, dt_text.empty() ? "no DT=" : QuoteCell(dt_text),
                     "the time step in seconds after DT= (e.g. `DT= .01000 SEC`)");
    }
    h.npts = *n;
    h.dt_s = d.value;
  }
  if (h.npts < 2) ThrowBadHeader(name, index + 1, npts_col, "NPTS = " + std::to_string(h.npts), "at least 2 points");
  if (static_cast<unsigned long long>(h.npts) > kMaxRecordSamples) {
    ThrowBadHeader(name, index + 1, npts_col, "NPTS = " + std::to_string(h.npts),
                   "at most " + std::to_string(kMaxRecordSamples) +
                       " points, the largest record rockfit reads "
                       "(docs/file-formats.md, \"Limits\")");
  }
  if (!(h.dt_s > 0.0)) ThrowBadHeader(name, index + 1, dt_col, "DT = " + std::string(dt_text), "a positive time step");
  return h;
}

// Splits a whitespace token into numbers: fixed-width fields of a negative value may touch the one before
// ("0.00630-0.00128"); a sign that does not follow an exponent letter starts a new number.
void SplitToken(std::string_view token, std::vector<std::pair<std::size_t, std::string_view>>* pieces,
                std::size_t offset) {
  std::size_t start = 0;
  for (std::size_t i = 1; i < token.size(); ++i) {
    const char c = token[i];
    const char before = token[i - 1];
    if ((c == '-' || c == '+') && before != 'E' && before != 'e' && before != 'D' && before != 'd') {
      pieces->push_back({offset + start, token.substr(start, i - start)});
      start = i;
    }
  }
  pieces->push_back({offset + start, token.substr(start)});
}

}  // namespace

double PeerRecord::PeakAbs_g() const {
  double peak = 0.0;
  for (double a : accel_g) peak = std::max(peak, std::abs(a));
  return peak;
}

PeerRecord ParsePeerAt2(const std::string& text, const std::string& display_name) {
  const std::vector<std::string_view> lines = SplitLines(text);
  if (lines.empty()) {
    ThrowBadInput({{display_name}, "", "an empty file", "a PEER AT2 record", "Give the path of an AT2 file."});
  }
  std::size_t header_index = lines.size();
  for (std::size_t i = 0; i < std::min(lines.size(), kMaxHeaderLines); ++i) {
    if (Upper(lines[i]).find("NPTS") != std::string::npos) {
      header_index = i;
      break;
    }
  }
  if (header_index == lines.size()) {
    ThrowBadHeader(display_name, 0, 0, "no line with NPTS in the first " + std::to_string(kMaxHeaderLines) + " lines",
                   "a header line with the number of points and the time step");
  }
  const Header header = ParseHeaderLine(display_name, header_index, lines[header_index]);
  PeerRecord record;
  record.source = display_name;
  for (std::size_t i = 0; i < header_index; ++i) record.header_lines.emplace_back(TrimSpaces(lines[i]));
  record.npts = static_cast<std::size_t>(header.npts);
  record.dt_s = header.dt_s;
  // NPTS comes from the file: reserve no more than the text can hold (a value takes at least two bytes, a digit
  // and a separator), so that a damaged NPTS is a wrong count reported below, never a huge allocation.
  record.accel_g.reserve(std::min(record.npts, text.size() / 2 + 1));

  std::vector<std::pair<std::size_t, std::string_view>> pieces;
  std::size_t last_data_line = header_index + 1;
  for (std::size_t i = header_index + 1; i < lines.size(); ++i) {
    const std::string_view line = lines[i];
    pieces.clear();
    std::size_t p = 0;
    while (p < line.size()) {
      while (p < line.size() && (line[p] == ' ' || line[p] == '\t')) ++p;
      std::size_t e = p;
      while (e < line.size() && line[e] != ' ' && line[e] != '\t') ++e;
      if (e > p) SplitToken(line.substr(p, e - p), &pieces, p);
      p = e;
    }
    if (!pieces.empty()) last_data_line = i + 1;
    for (const auto& [column, cell] : pieces) {
      const ParsedNumber value = ParseReal(cell);
      if (value.status != NumberStatus::kOk) {
        ThrowBadInput({{display_name, i + 1, column + 1}, "acceleration value " + std::to_string(record.accel_g.size() + 1),
                       QuoteCell(cell), "a number in units of g such as -.6490293E-04 or 0.00630",
                       "Repair or re-download the record; values must be plain numbers separated by spaces."});
      }
      if (!std::isfinite(value.value * core::kRecordGravity)) {
        ThrowBadInput({{display_name, i + 1, column + 1}, "acceleration value " + std::to_string(record.accel_g.size() + 1),
                       QuoteCell(cell), "a ground acceleration in g that is finite in m/s² as well",
                       "Check the value on this line; the record may be damaged."});
      }
      if (record.accel_g.size() == record.npts) {
        ThrowBadInput({{display_name, i + 1, column + 1}, "", "more values than NPTS = " + std::to_string(record.npts),
                       "exactly NPTS values",
                       "The header and the data disagree: check the NPTS line or whether two records were joined."});
      }
      record.accel_g.push_back(value.value);
    }
  }
  if (record.accel_g.size() != record.npts) {
    ThrowBadInput({{display_name, last_data_line}, "",
                   std::to_string(record.accel_g.size()) + " values (the file ends here)",
                   "NPTS = " + std::to_string(record.npts) + " values as the header on line " +
                       std::to_string(header_index + 1) + " says",
                   "The file is truncated or its header is wrong; download the record again."});
  }
  return record;
}

namespace {

// One value as the PEER database prints it: mantissa in [0.1, 1) without the leading zero, 7 digits, E exponent.
std::string PeerNumber(double value) {
  if (value == 0.0) return "   .0000000E+00";
  int exponent = static_cast<int>(std::floor(std::log10(std::abs(value)))) + 1;
  double mantissa = std::abs(value) / std::pow(10.0, exponent);
  long long digits = std::llround(mantissa * 1e7);
  if (digits >= 10000000) {  // rounding reached 1.0
    digits /= 10;
    ++exponent;
  }
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%s.%07lldE%c%02d", value < 0.0 ? "-" : "", digits, exponent < 0 ? '-' : '+',
                std::abs(exponent));
  std::string text(buffer);
  return std::string(text.size() < 15 ? 15 - text.size() : 0, ' ') + text;
}

// DT as ".00500": at least five decimals, as many more as it takes to read back the step to 1e-9 of it, no
// leading zero. InvalidArgument for a step that no DT field can hold.
std::string PeerStep(double dt_s) {
  constexpr double kStepRelTol = 1e-9;
  constexpr int kMaxDecimals = 15;
  if (!(dt_s > 0.0) || !std::isfinite(dt_s) || dt_s >= 1e9) {
    throw InvalidArgument("cannot write DT = " + std::to_string(dt_s) + " s in an AT2 file: the step must be positive "
                          "and below 1e9 s");
  }
  for (int decimals = 5; decimals <= kMaxDecimals; ++decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, dt_s);
    if (std::abs(std::strtod(buffer, nullptr) - dt_s) > kStepRelTol * dt_s) continue;
    std::string text(buffer);
    if (text.rfind("0.", 0) == 0) text.erase(0, 1);
    return text;
  }
  throw InvalidArgument(fmt::format("cannot write DT = {} s in an AT2 file with up to {} decimals; use a step of at "
                                    "least 1e-9 s", dt_s, kMaxDecimals));
}

}  // namespace

std::string FormatPeerAt2(const PeerRecord& record) {
  std::string out;
  for (std::size_t i = 0; i < 3; ++i) out += (i < record.header_lines.size() ? record.header_lines[i] : std::string()) + "\n";
  if (record.accel_g.size() < 2 || record.accel_g.size() > kMaxRecordSamples) {
    throw InvalidArgument(fmt::format("cannot write an AT2 record of {} values: a record has 2 to {} (the reader's "
                                      "limits)", record.accel_g.size(), kMaxRecordSamples));
  }
  for (std::size_t k = 0; k < record.accel_g.size(); ++k) {
    if (!std::isfinite(record.accel_g[k] * core::kRecordGravity)) {
      throw InvalidArgument(fmt::format("cannot write value {} ({} g) of an AT2 record: not a finite acceleration",
                                        k + 1, record.accel_g[k]));
    }
  }
  out += "NPTS=  " + std::to_string(record.accel_g.size()) + ", DT= " + PeerStep(record.dt_s) + " SEC\n";
  for (std::size_t k = 0; k < record.accel_g.size(); ++k) {
    out += PeerNumber(record.accel_g[k]);
    if (k % 5 == 4 || k + 1 == record.accel_g.size()) out += "\n";
  }
  return out;
}

PeerRecord ReadPeerAt2(const std::filesystem::path& path) {
  return ParsePeerAt2(ReadRegularFile(path, "a PEER AT2 file", kMaxRecordFileBytes), path.string());
}

}  // namespace rockfit::io
