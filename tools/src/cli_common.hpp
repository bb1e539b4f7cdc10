// Options and helpers shared by the subcommands: block geometry, exit codes, JSON output.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "rockfit/core/block.hpp"

namespace rockfit::tools {

// Exit codes of docs/design.md §9.
enum ExitCodes : int {
  kExitOk = 0,
  kExitUsage = 1,
  kExitBadInput = 2,
  kExitNumerical = 3,
  kExitCannotWrite = 4,
};

// Block geometry from --b1 --b2 --h with --density or --mass, or from --manifest FILE --block ID.
struct BlockArgs {
  std::optional<double> b1_m;
  std::optional<double> b2_m;
  std::optional<double> h_m;
  std::optional<double> density_kg_m3;
  std::optional<double> mass_kg;
  std::string manifest_path;
  std::string block_id;
};

void AddBlockOptions(CLI::App& app, BlockArgs& args);
// Throws InvalidArgument naming the missing or conflicting option, BadInput for a bad manifest or block id.
core::Block MakeBlock(const BlockArgs& args);
// True when any block option was given.
bool HasBlockOptions(const BlockArgs& args);
// The block when any block option was given (then as MakeBlock), else none.
std::optional<core::Block> MakeOptionalBlock(const BlockArgs& args);

// "a,b,c" → {"a", "b", "c"} (empty cells kept; an empty text gives no cell).
std::vector<std::string> SplitList(const std::string& text, char separator = ',');
// The finite number that is the whole of `cell`, or none.
std::optional<double> ParseFinite(const std::string& cell);

// Parses "X,Y,Z" into a vector; throws InvalidArgument naming `option` on failure.
Eigen::Vector3d ParseVector3(const std::string& text, const std::string& option);

// --pivot-edge "I,J" with I, J cyclic neighbours → b of the pivot edge V_{b−1}V_b (either order names the same
// edge). Throws InvalidArgument listing the allowed pairs.
int ParsePivotEdge(const std::string& text);

nlohmann::json ToJson(const Eigen::Vector3d& v);
// null for a missing value (JSON has no NaN or infinity): an empty optional, or a value that is not finite.
nlohmann::json OrNull(const std::optional<double>& value);
nlohmann::json OrNull(double value);
// Prints one JSON object on stdout (pretty, 2 spaces).
void PrintJson(const nlohmann::json& object);

}  // namespace rockfit::tools
