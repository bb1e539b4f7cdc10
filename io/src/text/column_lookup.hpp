// Finding a reader's columns in a CSV header by name, never by position: trimmed, case-insensitive
// header text, several accepted spellings per column ("Packet number" / "Packet Number",
// "(degrees)" / "(deg)"). A missing column is reported with the closest unclaimed header cell.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "text/csv_table.hpp"

namespace rockfit::io {

struct ColumnSpec {
  ColumnSpec(std::vector<std::string> accepted_names, std::string what, bool is_required = true,
             bool match_name_before_unit = false, std::string shown_as = {})
      : names(std::move(accepted_names)),
        meaning(std::move(what)),
        required(is_required),
        name_before_unit(match_name_before_unit),
        display(std::move(shown_as)) {}

  std::vector<std::string> names;  // accepted header texts; the first is the one to suggest
  std::string meaning;             // for messages, e.g. "the gyroscope's y axis in deg/s"
  bool required = true;
  // Compare only the text before a final "(unit)" of the header cell ("Gyroscope X" matches
  // "Gyroscope X (deg/s)" and "Gyroscope X (rad/s)"); the reader then checks the unit with HeaderUnit.
  bool name_before_unit = false;
  // How to write the column in messages when it is not names.front(), e.g. "Gyroscope X (deg/s)".
  std::string display;
};

// The column of each spec (std::nullopt for an optional column that is absent). Throws BadInput for
// a missing required column (naming the closest header cell that no spec claimed, or listing the
// header) or for a name that matches two columns.
std::vector<std::optional<std::size_t>> ResolveColumns(const CsvTable& table, const std::vector<ColumnSpec>& specs);

// The unit of a column from its header, "Gyroscope X (deg/s)" → kDegreesPerSecond, parsed by
// `parse` (e.g. ParseAngularRateUnit). Throws BadInput naming the header cell when the header has no
// unit in parentheses or one that `parse` does not know; `allowed` lists the accepted spellings.
template <typename Unit>
Unit HeaderUnit(const CsvTable& table, std::size_t column, std::optional<Unit> (*parse)(std::string_view),
                const std::string& allowed);

}  // namespace rockfit::io

#include "text/header_matching.hpp"

namespace rockfit::io {

template <typename Unit>
Unit HeaderUnit(const CsvTable& table, std::size_t column, std::optional<Unit> (*parse)(std::string_view),
                const std::string& allowed) {
  const HeaderParts parts = SplitHeaderUnit(table.header()[column]);
  if (const std::optional<Unit> unit = parse(parts.unit)) return *unit;
  ThrowBadInput({table.HeaderPosition(column), table.DescribeColumn(column),
                 parts.unit.empty() ? "no unit in parentheses or brackets" : "the unit '" + parts.unit + "'",
                 "one of " + allowed, "Write the unit at the end of the header cell, e.g. '" + parts.name + " (" +
                 allowed.substr(0, allowed.find(',')) + ")', or give it in the column map (name@unit)."});
}

}  // namespace rockfit::io
