#include "cli_common.hpp"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <vector>

#include "rockfit/core/errors.hpp"
#include "rockfit/io/manifest.hpp"

namespace rockfit::tools {

void AddBlockOptions(CLI::App& app, BlockArgs& args) {
  app.add_option("--b1", args.b1_m, "Block half-width along x (b1) [m]")->group("Block");
  app.add_option("--b2", args.b2_m, "Block half-depth along y (b2) [m]")->group("Block");
  app.add_option("--h", args.h_m, "Height of the centre of mass above the base (half the block height) [m]")
      ->group("Block");
  auto* density = app.add_option("--density", args.density_kg_m3, "Density [kg/m³] (granite: 2692)")->group("Block");
  auto* mass = app.add_option("--mass", args.mass_kg, "Total mass [kg]")->group("Block");
  density->excludes(mass);
  app.add_option("--manifest", args.manifest_path, "Campaign manifest (TOML) to take the block from")->group("Block");
  app.add_option("--block", args.block_id, "Block id in the manifest")->group("Block");
}

core::Block MakeBlock(const BlockArgs& args) {
  if (!args.manifest_path.empty() || !args.block_id.empty()) {
    if (args.manifest_path.empty() || args.block_id.empty()) {
      throw InvalidArgument("--manifest FILE and --block ID go together: give both to take the block from a manifest");
    }
    if (args.b1_m || args.b2_m || args.h_m || args.density_kg_m3 || args.mass_kg) {
      throw InvalidArgument("give the block either by --manifest/--block or by --b1 --b2 --h with --density or --mass, "
                            "not both");
    }
    return io::ReadManifest(args.manifest_path).FindBlock(args.block_id).ToBlock();  // BadInput: file, line, column
  }
  if (!args.b1_m || !args.b2_m || !args.h_m) {
    throw InvalidArgument("the block needs --b1, --b2 and --h (half-sizes in metres), or --manifest FILE --block ID");
  }
  if (args.density_kg_m3.has_value() == args.mass_kg.has_value()) {
    throw InvalidArgument("give exactly one of --density (kg/m³) or --mass (kg) for the block");
  }
  if (args.density_kg_m3) return core::Block::FromDensity(*args.b1_m, *args.b2_m, *args.h_m, *args.density_kg_m3);
  return core::Block::FromMass(*args.b1_m, *args.b2_m, *args.h_m, *args.mass_kg);
}

bool HasBlockOptions(const BlockArgs& args) {
  return args.b1_m || args.b2_m || args.h_m || args.density_kg_m3 || args.mass_kg || !args.manifest_path.empty() ||
         !args.block_id.empty();
}

std::optional<core::Block> MakeOptionalBlock(const BlockArgs& args) {
  if (!HasBlockOptions(args)) return std::nullopt;
  return MakeBlock(args);
}

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

nlohmann::json ToJson(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

nlohmann::json OrNull(const std::optional<double>& value) { return value ? OrNull(*value) : nlohmann::json(); }
nlohmann::json OrNull(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

void PrintJson(const nlohmann::json& object) { std::cout << object.dump(2) << std::endl; }

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

}  // namespace rockfit::tools
