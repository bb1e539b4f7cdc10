// libFuzzer target: a ground-motion record (PEER AT2 or CSV), read as `rockfit respond --record FILE` reads it
// (ground_motion_target.hpp).
#include <cstddef>
#include <cstdint>

#include "ground_motion_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rockfit::fuzz::GroundMotion(rockfit::fuzz::AsText(data, size));
  return 0;
}
