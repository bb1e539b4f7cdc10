// Local maxima of a sampled signal with a prominence threshold and a minimum separation, and the
// parabolic refinement of a peak between samples. Used for impact detection (peaks of |ω_y|, |ω_x|)
// and for the AVRF (peaks of the corrected |φ_y|), docs/design.md §6.
#pragma once

#include <cstddef>
#include <vector>

namespace rockfit::io {

struct PeakOptions {
  // A peak must rise at least this much above the higher of its two bases (the lowest points between it
  // and the nearest higher samples on either side, or the ends of the signal). Same unit as the signal.
  double min_prominence = 0.0;
  // Of two peaks closer than this many samples, only the higher is kept (ties: the earlier one).
  std::size_t min_separation_samples = 1;
  // Throws InvalidArgument for a negative or non-finite prominence.
  void Validate() const;
};

struct Peak {
  std::size_t index = 0;     // sample of the local maximum
  double value = 0.0;        // signal at that sample
  double prominence = 0.0;   // height above the higher base
};

// Local maxima of `signal` (a flat top counts once, at its middle sample; the first and last samples are
// never peaks), then those with prominence ≥ min_prominence, then the minimum separation by height.
// Returned in time order. The signal must be finite (InvalidArgument otherwise).
std::vector<Peak> FindPeaks(const std::vector<double>& signal, const PeakOptions& options);

// Prominence of every local maximum (same length as `maxima`), O(n) with a monotone stack.
std::vector<double> PeakProminences(const std::vector<double>& signal, const std::vector<std::size_t>& maxima);

// The vertex of the parabola through (k−1, k, k+1): the fractional offset in [−½, ½] samples from k and the
// value there. For a sampled smooth maximum this removes the O(Δt²) error of taking the sample itself.
struct RefinedPeak {
  double offset_samples = 0.0;
  double value = 0.0;
};
RefinedPeak RefinePeakParabolic(const std::vector<double>& signal, std::size_t index);

}  // namespace rockfit::io
