// The lognormal fragility curve P(IM) = Φ(ln(IM/θ)/β) fitted by maximum likelihood to binomial counts per
// intensity level (Baker 2015, "Efficient analytical fragility function fitting using dynamic structural analysis
// data"; fitting/quake/README.md, "The fragility study"). Standard errors come from the observed information (the inverse of
// the Hessian of −log L at the optimum), the median's by the delta method through ln θ.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rockfit/fitting/uncertainty.hpp"

namespace rockfit::quake {

struct LevelCount {
  double intensity = 0.0;     // > 0 (PGA in g, or a scale factor)
  std::int64_t trials = 0;    // samples with an outcome
  std::int64_t exceeded = 0;  // of them, those that reached the limit state (overturned, tilt exceeded)
};

enum class LognormalFitStatus {
  kOk,
  kNoExceedance,   // no sample reached the limit state: the median lies beyond the highest level
  kAllExceeded,    // every sample did: the median lies below the lowest level
  kSeparated,      // levels with 0 up to some intensity, at most one mixed level, then levels with all exceeded: the
                   // likelihood grows as β → 0 (a step); the median is the mixed level or between the two levels
  kTooFewLevels,   // fewer than two levels with samples
  kNotConverged,   // the optimiser did not converge or the information matrix is not positive definite
};
const char* ToString(LognormalFitStatus status);  // "ok", "no_exceedance", "all_exceeded", "separated", …

struct LognormalFragilityFit {
  LognormalFitStatus status = LognormalFitStatus::kTooFewLevels;
  std::string message;      // what the status means for this data, in words
  double median = 0.0;      // θ (same unit as the intensities); NaN unless ok or separated
  double beta = 0.0;        // β (dispersion of ln IM); 0 when separated; NaN unless ok or separated
  double median_std_error = 0.0;  // NaN unless ok
  double beta_std_error = 0.0;    // NaN unless ok
  fitting::Interval median_interval_95{};  // exp(ln θ ± 1.96·SE(ln θ)); for separated: the levels that bracket the step
  double correlation = 0.0;       // between ln θ and β at the optimum; NaN unless ok
  double log_likelihood = 0.0;    // at the optimum (for separated: its supremum, β → 0); NaN when there is none
  int iterations = 0;
};

// Levels with no trials are ignored. Never throws for data that give no estimate: the status says why.
// Throws InvalidArgument for a non-positive or non-finite intensity or counts with exceeded > trials.
LognormalFragilityFit FitLognormalFragility(const std::vector<LevelCount>& levels);

// Φ(ln(x/θ)/β): the fitted curve at intensity x (a step at θ when β = 0).
double LognormalFragility(double intensity, double median, double beta);

}  // namespace rockfit::quake
