// libFuzzer target: the campaign manifest (TOML), parsed from memory with io::ParseManifest as
// `rockfit summary MANIFEST` reads it, then every block turned into a core::Block and every trial's
// block looked up (as the commands do).
#include <cstddef>
#include <cstdint>

#include "manifest_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::Manifest(rockfit::fuzz::AsText(data, size));
  return 0;
}
