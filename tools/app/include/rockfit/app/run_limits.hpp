// The largest studies and responses the commands accept, checked against the options before anything is
// allocated for them (docs/file-formats.md, "Limits"; the file limits are in rockfit/io/input_limits.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "rockfit/core/ground_motion.hpp"

namespace rockfit::app {

// Intensity levels of one fragility study: a curve needs a dozen; more only lengthens the tables.
inline constexpr std::size_t kMaxFragilityLevels = 1000;
// Samples of one fragility study (blocks × levels × --samples): each keeps its outcome (quake::SampleOutcome, about
// 160 bytes) in memory and in the journal, 0.3 GB at the limit with the journal read back; at ~1000 simulations/s
// per core it is hours of work.
inline constexpr std::int64_t kMaxFragilitySamples = 1'000'000;
// Records of one fragility study (--record and --synthetic-records): suites of ground motions have tens to
// hundreds.
inline constexpr std::size_t kMaxFragilityRecords = 10'000;
// Ground-motion samples held by one fragility study over all its records (24 bytes each: 0.5 GB; the threads
// share them).
inline constexpr std::size_t kMaxStudyRecordSamples = 20'000'000;
// Output samples of one simulated motion — a response ((record + --tail) × --rate), a simulation (--t-max ×
// --rate) or a synthetic recording (--duration × --rate): about 150 bytes each in memory, several hundred more
// when written as JSON or CSV text; 10⁶ are 83 minutes at 200 Hz, an hour at 256 Hz.
inline constexpr double kMaxTrajectorySamples = 1e6;

// The lines of `--help` that state these limits and those of the input files, with their memory cost.
std::string LimitsHelp();

// InvalidArgument naming `options` (e.g. "--t-max × --rate") when `seconds` × `rate_hz` samples would exceed
// kMaxTrajectorySamples; also when either is not a positive finite number (they are checked again where used).
void RequireTrajectorySamplesWithinLimit(double seconds, double rate_hz, const std::string& options);

// Throws before a response is simulated whose samples would exceed kMaxTrajectorySamples: when the record alone is
// too long, BadInput naming the record file `source` (InvalidArgument naming --synthetic-duration when the record
// is generated, `from_file` false); else InvalidArgument naming --tail and --rate. Also refuses a --tail or --rate
// that is negative or not finite.
void RequireResponseWithinLimit(const core::GroundMotion& ground, const std::string& source, bool from_file,
                                double tail_s, double rate_hz);

}  // namespace rockfit::app
