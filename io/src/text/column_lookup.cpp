#include "text/column_lookup.hpp"

#include "text/header_matching.hpp"

namespace rockfit::io {
namespace {

std::optional<std::size_t> FindExact(const CsvTable& table, const ColumnSpec& spec) {
  std::optional<std::size_t> found;
  for (std::size_t column = 0; column < table.column_count(); ++column) {
    const std::string header =
        spec.name_before_unit ? SplitHeaderUnit(table.header()[column]).name : table.header()[column];
    bool match = false;
    for (const std::string& name : spec.names) match = match || HeaderEquals(header, name);
    if (!match) continue;
    if (found) {
      ThrowBadInput({table.HeaderPosition(column), "", "a second column named '" + table.header()[column] + "' (" +
                     table.DescribeColumn(*found) + " has the same name)",
                     "each column name once", "Rename or delete one of the two columns."});
    }
    found = column;
  }
  return found;
}

std::string ListHeader(const CsvTable& table) {
  std::string text;
  for (std::size_t column = 0; column < table.column_count(); ++column) {
    text += (column == 0 ? "'" : ", '") + table.header()[column] + "'";
  }
  return text;
}

}  // namespace

std::vector<std::optional<std::size_t>> ResolveColumns(const CsvTable& table, const std::vector<ColumnSpec>& specs) {
  std::vector<std::optional<std::size_t>> columns;
  std::vector<bool> claimed(table.column_count(), false);
  for (const ColumnSpec& spec : specs) {
    columns.push_back(FindExact(table, spec));
    if (columns.back()) claimed[*columns.back()] = true;
  }
  for (std::size_t k = 0; k < specs.size(); ++k) {
    if (columns[k] || !specs[k].required) continue;
    const ColumnSpec& spec = specs[k];
    std::vector<std::string> unclaimed;
    std::vector<std::size_t> unclaimed_column;
    for (std::size_t column = 0; column < table.column_count(); ++column) {
      if (claimed[column]) continue;
      unclaimed.push_back(spec.name_before_unit ? SplitHeaderUnit(table.header()[column]).name
                                                : table.header()[column]);
      unclaimed_column.push_back(column);
    }
    const std::string shown = spec.display.empty() ? spec.names.front() : spec.display;
    const std::string wanted = "a column '" + shown + "' (" + spec.meaning + ")";
    if (const auto suggestion = ClosestHeader(unclaimed, spec.names)) {
      const std::size_t column = unclaimed_column[suggestion->index];
      ThrowBadInput({table.HeaderPosition(column), "", "the header '" + table.header()[column] + "'", wanted,
                     "If this is that column, rename its header to '" + shown + "'."});
    }
    ThrowBadInput({{table.name(), table.header_line()}, "", "the header " + ListHeader(table), wanted,
                   "Add the column, or check that this is the right file."});
  }
  return columns;
}

}  // namespace rockfit::io
