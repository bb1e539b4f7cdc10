#include "rockfit/io/peak_finding.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {

void PeakOptions::Validate() const {
  if (!std::isfinite(min_prominence) || min_prominence < 0.0) {
    throw InvalidArgument("peak min_prominence must be a finite number ≥ 0, got " + std::to_string(min_prominence));
  }
}

namespace {

// Local maxima; a plateau of equal samples that is higher than both neighbours counts once, at its middle.
std::vector<std::size_t> LocalMaxima(const std::vector<double>& x) {
  std::vector<std::size_t> maxima;
  const std::size_t n = x.size();
  std::size_t i = 1;
  while (i + 1 < n) {
    if (x[i - 1] < x[i]) {
      std::size_t ahead = i + 1;
      while (ahead + 1 < n && x[ahead] == x[i]) ++ahead;  // skip a flat top
      if (x[ahead] < x[i]) {
        maxima.push_back((i + ahead - 1) / 2);
        i = ahead;
        continue;
      }
    }
    ++i;
  }
  return maxima;
}

// For every sample i: the minimum of x over (j, i], where j is the last earlier sample higher than x[i]
// (or the start of the signal). Monotone stack of (value, minimum of its own interval), O(n).
std::vector<double> LeftBaseMinima(const std::vector<double>& x) {
  struct Entry {
    double value;
    double interval_min;
  };
  std::vector<Entry> stack;
  std::vector<double> base(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    double m = x[i];
    while (!stack.empty() && stack.back().value <= x[i]) {
      m = std::min(m, stack.back().interval_min);
      stack.pop_back();
    }
    base[i] = m;
    stack.push_back({x[i], m});
  }
  return base;
}

}  // namespace

std::vector<double> PeakProminences(const std::vector<double>& signal, const std::vector<std::size_t>& maxima) {
  const std::vector<double> left = LeftBaseMinima(signal);
  std::vector<double> reversed(signal.rbegin(), signal.rend());
  const std::vector<double> right_reversed = LeftBaseMinima(reversed);
  std::vector<double> prominences;
  prominences.reserve(maxima.size());
  const std::size_t n = signal.size();
  for (std::size_t k : maxima) {
    const double higher_base = std::max(left[k], right_reversed[n - 1 - k]);
    prominences.push_back(signal[k] - higher_base);
  }
  return prominences;
}

std::vector<Peak> FindPeaks(const std::vector<double>& signal, const PeakOptions& options) {
  options.Validate();
  for (std::size_t i = 0; i < signal.size(); ++i) {
    if (!std::isfinite(signal[i])) {
      throw InvalidArgument("FindPeaks: sample " + std::to_string(i) + " is not a finite number");
    }
  }
  const std::vector<std::size_t> maxima = LocalMaxima(signal);
  const std::vector<double> prominences = PeakProminences(signal, maxima);

  std::vector<Peak> candidates;
  for (std::size_t j = 0; j < maxima.size(); ++j) {
    if (prominences[j] >= options.min_prominence) candidates.push_back({maxima[j], signal[maxima[j]], prominences[j]});
  }
  if (options.min_separation_samples <= 1 || candidates.size() < 2) return candidates;

  // Keep peaks in order of decreasing height; drop every lower peak closer than the separation.
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return candidates[a].value > candidates[b].value; });
  std::vector<bool> removed(candidates.size(), false);
  const std::size_t distance = options.min_separation_samples;
  for (std::size_t j : order) {
    if (removed[j]) continue;
    for (std::size_t left = j; left-- > 0 && candidates[j].index - candidates[left].index < distance;) removed[left] = true;
    for (std::size_t right = j + 1; right < candidates.size() && candidates[right].index - candidates[j].index < distance;
         ++right) {
      removed[right] = true;
    }
  }
  std::vector<Peak> kept;
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    if (!removed[j]) kept.push_back(candidates[j]);
  }
  return kept;
}

RefinedPeak RefinePeakParabolic(const std::vector<double>& signal, std::size_t index) {
  if (index >= signal.size()) throw InvalidArgument("RefinePeakParabolic: index outside the signal");
  RefinedPeak refined{0.0, signal[index]};
  if (index == 0 || index + 1 >= signal.size()) return refined;
  const double y_prev = signal[index - 1];
  const double y_here = signal[index];
  const double y_next = signal[index + 1];
  const double curvature = y_prev - 2.0 * y_here + y_next;
  if (!(curvature < 0.0)) return refined;  // not a strict maximum: keep the sample
  const double offset = std::clamp(0.5 * (y_prev - y_next) / curvature, -0.5, 0.5);
  refined.offset_samples = offset;
  refined.value = y_here - 0.25 * (y_prev - y_next) * offset;
  return refined;
}

}  // namespace rockfit::io
