// Random parameter sets for the random-physics property tests (tests/core/random_physics_property_test.cpp,
// tests/fitting/random_evaluate_property_test.cpp): extreme geometries and masses, impact parameters far
// outside (25)/(27), tilts at and beyond the critical angle, tiny and huge tolerances. Fixed seeds.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

#include "build_type.hpp"
#include "rockfit/core/block.hpp"

namespace rockfit::testing {

// How many random parameter sets a property test draws: ROCKFIT_RANDOM_PHYSICS_RUNS when set (the documented
// full run uses 100000), else `optimised` in optimised builds and `sanitized` in Debug/sanitizer builds.
inline long RandomPhysicsRuns(long optimised, long sanitized) {
  if (const char* text = std::getenv("ROCKFIT_RANDOM_PHYSICS_RUNS")) return std::strtol(text, nullptr, 10);
  return kOptimisedBuild ? optimised : sanitized;
}

class RandomPhysics {
 public:
  explicit RandomPhysics(std::uint64_t seed) : rng_(seed) {}

  double Uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  // Log-uniform on [lo, hi], lo > 0.
  double LogUniform(double lo, double hi) { return std::exp(Uniform(std::log(lo), std::log(hi))); }
  int Integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool Chance(double p) { return Uniform(0.0, 1.0) < p; }
  double SignedLogUniform(double lo, double hi) { return (Chance(0.5) ? -1.0 : 1.0) * LogUniform(lo, hi); }

  // h from 5 mm to 2 m; b1/h and b2/h from 0.01 to 10; mass from 1e-3 to 1e4 kg.
  core::Block Block() {
    const double h = LogUniform(0.005, 2.0);
    return core::Block::FromMass(h * LogUniform(0.01, 10.0), h * LogUniform(0.01, 10.0), h, LogUniform(1e-3, 1e4));
  }

  // An impact parameter: mostly inside [−1, 1], often far outside (up to ±100), sometimes on the bounds.
  double ImpactParameter() {
    switch (Integer(0, 5)) {
      case 0:
        return Uniform(-1.0, 1.0);
      case 1:
        return Chance(0.5) ? 1.0 : -1.0;
      case 2:
        return Uniform(-3.0, 3.0);
      case 3:
        return SignedLogUniform(1.0, 100.0);
      case 4:
        return SignedLogUniform(1e-9, 1e-3);
      default:
        return 0.0;
    }
  }

  // A tilt relative to the critical angle θ_c: inside (0, θ_c), at θ_c to round-off, just beyond, far beyond.
  double Tilt(double critical_rad) {
    switch (Integer(0, 5)) {
      case 0:
        return critical_rad * Uniform(0.01, 1.0);
      case 1:
        return critical_rad * (1.0 - LogUniform(1e-14, 1e-3));
      case 2:
        return critical_rad;
      case 3:
        return critical_rad * (1.0 + LogUniform(1e-14, 1e-3));
      case 4:
        return critical_rad * Uniform(1.0, 3.0);
      default:
        return critical_rad * LogUniform(1e-8, 1e-2);
    }
  }

 private:
  std::mt19937_64 rng_;
};

}  // namespace rockfit::testing
