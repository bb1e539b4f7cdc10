// Fuzz target body: the --columns and --mounting option grammars (io::ColumnMap::Parse,
// io::Mounting::Parse). Beyond "no crash, only documented errors", whatever parses must round-trip:
// ColumnMap::ToString parses back to the same text, and Mounting::text() parses back to the same
// rotation (the canonical text keeps 9 significant digits).
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "rockfit/io/column_map.hpp"
#include "rockfit/io/mounting.hpp"

namespace rockfit::fuzz {

namespace option_grammars_detail {

// Two parses of the canonical mounting text differ by its rounding to 9 significant digits.
constexpr double kMountingRoundTripTolerance = 1e-8;

[[noreturn]] inline void RoundTripFailed(const char* grammar, std::string_view text) {
  std::fprintf(stderr, "rockfit fuzz: %s text does not round-trip: '%.*s'\n", grammar, static_cast<int>(text.size()),
               text.data());
  std::abort();
}

}  // namespace option_grammars_detail

inline void OptionGrammars(std::string_view input) {
  const std::string_view text = input;
  ExpectDocumentedOutcome([&] {
    const io::ColumnMap map = io::ColumnMap::Parse(text);
    const std::string canonical = map.ToString();
    if (io::ColumnMap::Parse(canonical).ToString() != canonical)
      option_grammars_detail::RoundTripFailed("column map", text);
  });
  ExpectDocumentedOutcome([&] {
    const io::Mounting mounting = io::Mounting::Parse(text);
    const io::Mounting again = io::Mounting::Parse(mounting.text());
    if (!mounting.R_BS().allFinite()) option_grammars_detail::RoundTripFailed("mounting (non-finite rotation)", text);
    if ((again.R_BS() - mounting.R_BS()).cwiseAbs().maxCoeff() > option_grammars_detail::kMountingRoundTripTolerance)
      option_grammars_detail::RoundTripFailed("mounting", text);
  });
}

}  // namespace rockfit::fuzz
