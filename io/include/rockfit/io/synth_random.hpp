// Seeded random numbers for synthetic recordings, reproducible bit for bit.
//
// std::normal_distribution is not specified exactly by the C++ standard (libstdc++ and libc++ give
// different numbers for the same engine), so the generator uses only what is: std::mt19937_64 seeded
// with one 64-bit integer. Uniforms take the top 53 bits of one engine output; normals come from the
// Box–Muller transform, both values of each pair used in order.
//
// Every random part of the measurement model draws from its own stream: the stream's engine seed is
// SplitMix64(seed + stream id). Switching one part on or off therefore never changes the numbers of another.
#pragma once

#include <cstdint>
#include <random>

namespace rockfit::io {

// Stream ids of the measurement model's random parts (part of the file format's reproducibility: never renumber).
enum class SynthStream : std::uint64_t {
  kGyroNoise = 1,
  kAccelNoise = 2,
  kMagNoise = 3,
  kDriftWalk = 4,
  kHousekeeping = 5,  // battery voltage and temperature packets
  kGroundMotion = 6,  // white noise of the stochastic ground-motion generator (stochastic_ground_motion.hpp)
  kFragilitySample = 7,  // the random inputs of one sample of a fragility study (fitting/quake/include/rockfit/quake/fragility_study.hpp)
};

// The SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mix used to derive stream seeds.
std::uint64_t SplitMix64(std::uint64_t x);

class SynthRandom {
 public:
  SynthRandom(std::uint64_t seed, SynthStream stream);

  // Uniform on (0, 1]: (top 53 bits + 1) · 2⁻⁵³.
  double Uniform();
  // Standard normal (mean 0, variance 1) by Box–Muller.
  double Normal();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace rockfit::io
