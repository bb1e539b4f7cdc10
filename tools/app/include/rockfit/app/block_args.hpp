// The block of a command: geometry from --b1 --b2 --h with --density or --mass, or a block of a campaign manifest
// (--manifest FILE --block ID). The program declares the options (tools/src/cli_common.cpp); Python fills the
// struct from keyword arguments.
#pragma once

#include <optional>
#include <string>

#include "rockfit/core/block.hpp"

namespace rockfit::app {

struct BlockArgs {
  std::optional<double> b1_m;
  std::optional<double> b2_m;
  std::optional<double> h_m;
  std::optional<double> density_kg_m3;
  std::optional<double> mass_kg;
  std::string manifest_path;
  std::string block_id;
};

// Throws InvalidArgument naming the missing or conflicting option, BadInput for a bad manifest or block id.
core::Block MakeBlock(const BlockArgs& args);
// True when any block option was given.
bool HasBlockOptions(const BlockArgs& args);
// The block when any block option was given (then as MakeBlock), else none.
std::optional<core::Block> MakeOptionalBlock(const BlockArgs& args);

}  // namespace rockfit::app
