// A 64-bit content hash (FNV-1a) for settings texts, record contents and journal checksums. It detects changes
// and torn writes; it is not a cryptographic hash.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace rockfit::io {

// FNV-1a over the bytes, continuing from `state` (the offset basis by default) so that parts can be chained.
std::uint64_t Fnv1a64(std::string_view bytes, std::uint64_t state = 14695981039346656037ull);
// The hash as 16 lower-case hex digits.
std::string HashHex(std::uint64_t hash);

}  // namespace rockfit::io
