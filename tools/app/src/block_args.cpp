#include "rockfit/app/block_args.hpp"

#include "rockfit/core/errors.hpp"
#include "rockfit/io/manifest.hpp"

namespace rockfit::app {

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

}  // namespace rockfit::app
