// Fuzz target body: the campaign manifest (TOML), parsed from memory with io::ParseManifest as
// `rockfit summary MANIFEST` reads it, then every block turned into a core::Block and every trial's
// block looked up (as the commands do).
#pragma once
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "rockfit/io/manifest.hpp"

namespace rockfit::fuzz {

inline void Manifest(std::string_view input) {
  ExpectDocumentedOutcome([&] {
    const io::Manifest manifest = io::ParseManifest(input, "/nonexistent/manifest.toml");
    for (const auto& block : manifest.blocks) (void)block.ToBlock();
    for (const auto& trial : manifest.trials) {
      (void)manifest.FindBlock(trial.block_id);
      (void)manifest.FindTrial(trial.id);
    }
  });
}

}  // namespace rockfit::fuzz
