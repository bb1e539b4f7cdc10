// The largest inputs rockfit accepts, checked before anything is allocated for them (docs/file-formats.md,
// "Limits"). Each limit is far above any real recording or record; above it a damaged file, a device such as
// /dev/zero or a mistyped option would only fill the memory.
#pragma once

#include <cstddef>
#include <cstdint>

namespace rockfit::io {

// A recording's CSV file (x-IMU, x-IMU3, generic): 10⁷ rows of the x-IMU GUI are 600 MB. Reading holds the text
// and a table of cell positions, about 6 bytes of memory per byte of file.
inline constexpr std::uint64_t kMaxRecordingFileBytes = std::uint64_t{1} << 30;  // 1 GiB

// A ground-motion record (PEER AT2 or CSV): kMaxRecordSamples values in the PEER form are 150 MB.
inline constexpr std::uint64_t kMaxRecordFileBytes = std::uint64_t{256} << 20;  // 256 MiB

// Samples of one ground-motion component, read or generated: 10⁷ are 14 hours at 200 Hz (PEER records have
// 10⁴–10⁵); 80 MB as doubles, a few times that while a response runs on it.
inline constexpr std::size_t kMaxRecordSamples = 10'000'000;

// A manifest: 10⁵ trials are 10 MB; its parsed tree takes about 20 times the text.
inline constexpr std::uint64_t kMaxManifestFileBytes = std::uint64_t{16} << 20;  // 16 MiB

// [[blocks]] or [[trials]] entries of one manifest: `summary` and `batch` keep a few kB per trial (66 MB for 10⁴),
// 0.7 GB at the limit.
inline constexpr std::size_t kMaxManifestEntries = 100'000;

// Parts of one dotted TOML key or table name (`a.b.c` has 3): the TOML parser recurses once per part, and
// tens of thousands of parts overflow its stack. A manifest needs 2.
inline constexpr std::size_t kMaxManifestKeyParts = 64;

}  // namespace rockfit::io
