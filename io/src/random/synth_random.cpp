#include "rockfit/io/synth_random.hpp"

#include <cmath>

namespace rockfit::io {
namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kTwoToMinus53 = 1.0 / 9007199254740992.0;  // 2⁻⁵³
}  // namespace

std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

SynthRandom::SynthRandom(std::uint64_t seed, SynthStream stream)
    : engine_(SplitMix64(seed + static_cast<std::uint64_t>(stream))) {}

double SynthRandom::Uniform() { return static_cast<double>((engine_() >> 11) + 1) * kTwoToMinus53; }

double SynthRandom::Normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = Uniform();  // (0, 1]: the logarithm is finite
  const double u2 = Uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = kTwoPi * u2;
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

}  // namespace rockfit::io
