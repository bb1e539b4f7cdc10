// Whether the tests run in an optimised build. The sanitizer build of CI is a Debug build in which the hybrid
// simulator runs about 150 times slower; whole fits (thousands of simulations) are then too slow for a unit
// test suite. Tests that need them run in optimised builds only and say so when skipped; cheaper tests cover
// the same code under the sanitizers.
#pragma once

namespace rockfit::testing {

#ifdef NDEBUG
inline constexpr bool kOptimisedBuild = true;
#else
inline constexpr bool kOptimisedBuild = false;
#endif

// Whether AddressSanitizer instruments this build (CI's sanitizer build): its shadow memory and its quarantine of
// freed blocks (256 MB by default) make resident-memory bounds meaningless there.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizedBuild = true;
#else
inline constexpr bool kAddressSanitizedBuild = false;
#endif

}  // namespace rockfit::testing

// Skips the current test outside optimised builds.
#define ROCKFIT_REQUIRE_OPTIMISED_BUILD()                                                                   \
  do {                                                                                                      \
    if (!rockfit::testing::kOptimisedBuild) {                                                               \
      GTEST_SKIP() << "whole fits with the simulator run in optimised builds only (Debug/sanitizer builds " \
                      "simulate ~150x slower); the cheaper tests cover this code there";                   \
    }                                                                                                       \
  } while (0)
