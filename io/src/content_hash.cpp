#include "rockfit/io/content_hash.hpp"

#include <fmt/format.h>

namespace rockfit::io {

std::uint64_t Fnv1a64(std::string_view bytes, std::uint64_t state) {
  constexpr std::uint64_t kPrime = 1099511628211ull;
  for (unsigned char c : bytes) {
    state ^= c;
    state *= kPrime;
  }
  return state;
}

std::string HashHex(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

}  // namespace rockfit::io
