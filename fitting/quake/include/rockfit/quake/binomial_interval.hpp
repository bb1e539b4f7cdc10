// Confidence intervals for a binomial proportion k/n, for the probabilities of a fragility study
// (fitting/quake/README.md, "The fragility study"): the Wilson score interval and the exact Clopper–Pearson interval.
#pragma once

#include <cstdint>

#include "rockfit/fitting/uncertainty.hpp"

namespace rockfit::quake {

// Two-sided intervals at `confidence` (0 < confidence < 1) for k successes in n trials (0 ≤ k ≤ n). With no
// trials the interval is [0, 1] (nothing is known). k = 0 gives a lower end of exactly 0, k = n an upper end of
// exactly 1. Throws InvalidArgument for k outside [0, n] or a confidence outside (0, 1).
fitting::Interval WilsonInterval(std::int64_t successes, std::int64_t trials, double confidence = 0.95);
// Exact: the ends are quantiles of Beta(k, n − k + 1) and Beta(k + 1, n − k); it covers p at least `confidence`.
fitting::Interval ClopperPearsonInterval(std::int64_t successes, std::int64_t trials, double confidence = 0.95);

}  // namespace rockfit::quake
