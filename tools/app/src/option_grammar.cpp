#include "rockfit/app/option_grammar.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "rockfit/core/block.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::app {

std::vector<std::string> SplitList(const std::string& text, char separator) {
  std::vector<std::string> cells;
  std::stringstream stream(text);
  std::string cell;
  while (std::getline(stream, cell, separator)) cells.push_back(cell);
  return cells;
}

std::optional<double> ParseFinite(const std::string& cell) {
  char* end = nullptr;
  const double value = std::strtod(cell.c_str(), &end);
  if (cell.empty() || end == cell.c_str() || *end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

Eigen::Vector3d ParseVector3(const std::string& text, const std::string& option) {
  std::vector<double> values;
  for (const std::string& cell : SplitList(text)) {
    const std::optional<double> value = ParseFinite(cell);
    if (!value) {
      throw InvalidArgument(option + " expects three finite numbers X,Y,Z separated by commas, got '" + text + "'");
    }
    values.push_back(*value);
  }
  if (values.size() != 3) {
    throw InvalidArgument(option + " expects three numbers X,Y,Z separated by commas, got '" + text + "'");
  }
  return {values[0], values[1], values[2]};
}

// "I,J" with I, J cyclic neighbours → b of the pivot edge V_{b−1}V_b (either order names the same edge).
int ParsePivotEdge(const std::string& text) {
  const std::string allowed = "--pivot-edge expects two neighbouring base vertices I,J (1,2 2,3 3,4 or 4,1, in either order)";
  std::stringstream stream(text);
  std::string cell;
  std::vector<int> vertices;
  while (std::getline(stream, cell, ',')) {
    char* end = nullptr;
    const long value = std::strtol(cell.c_str(), &end, 10);
    if (cell.empty() || end == cell.c_str() || *end != '\0' || value < 1 || value > 4) {
      throw InvalidArgument(allowed + ", got '" + text + "'");
    }
    vertices.push_back(static_cast<int>(value));
  }
  if (vertices.size() != 2 || !core::Block::AreNeighbours(vertices[0], vertices[1])) {
    throw InvalidArgument(allowed + ", got '" + text + "'");
  }
  // In cyclic order the edge is V_{b−1}V_b: b is the vertex that follows the other one.
  return core::Block::WrapVertex(vertices[0] + 1) == vertices[1] ? vertices[1] : vertices[0];
}

core::FacetTauRule ParseFacetTauRule(const std::string& text) {
  core::FacetTauRule rule = core::FacetTauRule::kNoSpin;
  if (core::FromString(text, &rule)) return rule;
  throw InvalidArgument("the facet-τ rule (--facet-tau, facet_tau) is no-spin (τ from (24), the default) or fixed "
                        "(τ = 0, the paper's Sect. 5; also written zero), got '" + text + "'");
}

core::OverturnRule ParseOverturnRule(const std::string& text) {
  core::OverturnRule rule = core::OverturnRule::kComOverSupport;
  if (core::FromString(text, &rule)) return rule;
  throw InvalidArgument("the overturning rule (--overturn, overturn) is support (the COM passes over the support) or "
                        "side (the block lies on a side), got '" + text + "'");
}
}  // namespace rockfit::app
