// The small grammars of option values that the program and Python share: lists, finite numbers, vectors and
// pivot edges. Enumerated values (facet-τ rules, formats, …) have their ToString/FromString pairs beside their
// enums in the libraries.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/facet_impact.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::app {

// "a,b,c" → {"a", "b", "c"} (empty cells kept; an empty text gives no cell).
std::vector<std::string> SplitList(const std::string& text, char separator = ',');
// The finite number that is the whole of `cell`, or none.
std::optional<double> ParseFinite(const std::string& cell);

// Parses "X,Y,Z" into a vector; throws InvalidArgument naming `option` on failure.
Eigen::Vector3d ParseVector3(const std::string& text, const std::string& option);

// --pivot-edge "I,J" with I, J cyclic neighbours → b of the pivot edge V_{b−1}V_b (either order names the same
// edge). Throws InvalidArgument listing the allowed pairs.
int ParsePivotEdge(const std::string& text);

// --facet-tau / facet_tau: core::FromString's names ("no-spin", "fixed", also "zero"); InvalidArgument otherwise.
core::FacetTauRule ParseFacetTauRule(const std::string& text);
// --overturn / overturn: "support" or "side"; InvalidArgument otherwise.
core::OverturnRule ParseOverturnRule(const std::string& text);

}  // namespace rockfit::app
