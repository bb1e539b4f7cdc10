// Matching CSV header cells to the names a reader expects: trimmed, case-insensitive, runs of spaces
// count as one; and, when a name is missing, the closest header cell to suggest instead.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rockfit::io {

// Lower-case ASCII, spaces and tabs trimmed at both ends, inner runs of spaces collapsed to one.
std::string NormalizeHeader(std::string_view header);

// True when the normalized texts are equal.
bool HeaderEquals(std::string_view header, std::string_view expected);

// Levenshtein distance (insertions, deletions, substitutions) between two strings.
std::size_t EditDistance(std::string_view a, std::string_view b);

struct HeaderSuggestion {
  std::size_t index = 0;     // position in the candidate list
  std::size_t distance = 0;  // edit distance between normalized texts
};

// The candidate closest to any of `wanted` (after NormalizeHeader), if it is close enough to be a
// misspelling: at most max(2, length/4) edits. Callers pass only the header cells that no other
// expected column claimed, so that "Gyroscope X" is never offered for a missing "Gyroscope Y".
std::optional<HeaderSuggestion> ClosestHeader(const std::vector<std::string>& candidates,
                                              const std::vector<std::string>& wanted);

// Splits "Gyroscope X (deg/s)" or "gx [deg/s]" into name and unit (both trimmed). Without a final part in
// parentheses or square brackets the unit is empty.
struct HeaderParts {
  std::string name;
  std::string unit;
};
HeaderParts SplitHeaderUnit(std::string_view header);

}  // namespace rockfit::io
