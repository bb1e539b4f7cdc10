#include "rockfit/fitting/trajectory_error.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {

void MeasuredSignal::Validate() const {
  if (t_s.size() != w_B.size()) {
    throw InvalidArgument(fmt::format("measured signal: {} times but {} angular velocities", t_s.size(), w_B.size()));
  }
  if (!excluded.empty() && excluded.size() != t_s.size()) {
    throw InvalidArgument(fmt::format("measured signal: {} times but {} exclusion marks", t_s.size(), excluded.size()));
  }
  if (!censored_axes.empty() && censored_axes.size() != t_s.size()) {
    throw InvalidArgument(
        fmt::format("measured signal: {} times but {} censoring marks", t_s.size(), censored_axes.size()));
  }
  if (t_s.size() < 2) {
    throw InvalidArgument(fmt::format("measured signal: need at least two samples, got {}", t_s.size()));
  }
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    if (!std::isfinite(t_s[k]) || !w_B[k].allFinite()) {
      throw InvalidArgument(fmt::format("measured signal: sample {} is not finite (t = {} s)", k, t_s[k]));
    }
    if (k > 0 && !(t_s[k] > t_s[k - 1])) {
      throw InvalidArgument(fmt::format("measured signal: time does not increase at sample {} ({} s after {} s)", k,
                                        t_s[k], t_s[k - 1]));
    }
  }
}

Eigen::Vector3d MeasuredSignal::Interpolate(double t) const {
  if (t <= t_s.front()) return w_B.front();
  if (t >= t_s.back()) return w_B.back();
  const auto upper = std::upper_bound(t_s.begin(), t_s.end(), t);  // first sample after t
  const std::size_t k = static_cast<std::size_t>(std::distance(t_s.begin(), upper));
  const double s = (t - t_s[k - 1]) / (t_s[k] - t_s[k - 1]);
  return (1.0 - s) * w_B[k - 1] + s * w_B[k];
}

bool BuildErrorNodes(const MeasuredSignal& signal, double t0_s, double t_end_s, ErrorNodes* nodes) {
  if (!(t0_s >= signal.t_s.front()) || !(t_end_s <= signal.t_s.back()) || !(t0_s < t_end_s)) return false;
  // Samples strictly inside (t0, t_end).
  const auto begin = std::upper_bound(signal.t_s.begin(), signal.t_s.end(), t0_s);
  const auto end = std::lower_bound(begin, signal.t_s.end(), t_end_s);
  const std::size_t first = static_cast<std::size_t>(std::distance(signal.t_s.begin(), begin));
  const std::size_t interior = static_cast<std::size_t>(std::distance(begin, end));
  const std::size_t n = interior + 2;

  nodes->first_sample = first;
  nodes->num_interior = interior;
  nodes->t_s.resize(n);
  nodes->t_after_release_s.resize(n);
  nodes->w_m_B.resize(n);
  nodes->weight_s.resize(n);

  nodes->t_s[0] = t0_s;
  nodes->w_m_B[0] = signal.Interpolate(t0_s);
  for (std::size_t i = 0; i < interior; ++i) {
    nodes->t_s[i + 1] = signal.t_s[first + i];
    nodes->w_m_B[i + 1] = signal.w_B[first + i];
  }
  nodes->t_s[n - 1] = t_end_s;
  nodes->w_m_B[n - 1] = signal.Interpolate(t_end_s);

  // Trapezoid weights: w_i = ((t_i − t_{i−1}) + (t_{i+1} − t_i)) / 2, halves at both ends (n ≥ 2). The end nodes
  // apart, so that the loop over the interior has no branch and vectorises.
  const std::vector<double>& t = nodes->t_s;
  nodes->weight_s[0] = 0.5 * (0.0 + (t[1] - t[0]));
  for (std::size_t i = 1; i + 1 < n; ++i) nodes->weight_s[i] = 0.5 * ((t[i] - t[i - 1]) + (t[i + 1] - t[i]));
  nodes->weight_s[n - 1] = 0.5 * ((t[n - 1] - t[n - 2]) + 0.0);
  for (std::size_t i = 0; i < n; ++i) nodes->t_after_release_s[i] = t[i] - t0_s;
  // Excluded samples: their nodes, and an end node interpolated from one, carry no weight.
  nodes->excluded_weight_s = 0.0;
  nodes->num_excluded = 0;
  nodes->censored_axes.assign(n, 0);
  nodes->num_censored = 0;
  // A sample with a censored axis keeps its weight and is marked instead (the end nodes, interpolated, never are).
  auto censored = [&](std::size_t k) { return signal.censored_at(k) != 0; };
  if (!signal.censored_axes.empty()) {
    for (std::size_t i = 0; i < interior; ++i) {
      nodes->censored_axes[i + 1] = signal.censored_at(first + i);
      if (nodes->censored_axes[i + 1] != 0) ++nodes->num_censored;
    }
  }
  if (!signal.excluded.empty()) {
    auto exclude = [&](std::size_t i) {
      nodes->excluded_weight_s += nodes->weight_s[i];
      nodes->weight_s[i] = 0.0;
      ++nodes->num_excluded;
    };
    // Node 0 interpolates samples first − 1 and first; the last node samples first + interior − 1 and
    // first + interior (t_end ≤ the last sample time).
    const std::size_t last_sample = signal.size() - 1;
    if (signal.is_excluded(first) || (first > 0 && signal.is_excluded(first - 1))) exclude(0);
    for (std::size_t i = 0; i < interior; ++i) {
      if (signal.is_excluded(first + i) && !censored(first + i)) exclude(i + 1);
    }
    const std::size_t after = std::min(first + interior, last_sample);
    if (signal.is_excluded(after) || (first + interior > 0 && signal.is_excluded(first + interior - 1))) exclude(n - 1);
  }
  return true;
}

std::uint8_t SatisfiedCensoredAxes(const ErrorNodes& nodes, std::size_t i, const Eigen::Vector3d& w_s_B) {
  const std::uint8_t axes = nodes.censored_axes.empty() ? 0 : nodes.censored_axes[i];
  std::uint8_t satisfied = 0;
  for (int a = 0; a < 3; ++a) {
    if ((axes & (1u << a)) == 0) continue;
    const double sense = nodes.w_m_B[i][a] >= 0.0 ? 1.0 : -1.0;
    // The model at or beyond the rail: consistent with "at least this fast".
    if (sense * (nodes.w_m_B[i][a] - w_s_B[a]) <= 0.0) satisfied = static_cast<std::uint8_t>(satisfied | (1u << a));
  }
  return satisfied;
}

std::size_t NumSatisfiedCensoredComponents(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B) {
  if (nodes.num_censored == 0) return 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes.weight_s[i] == 0.0) continue;
    const std::uint8_t satisfied = SatisfiedCensoredAxes(nodes, i, w_s_B[i]);
    for (int a = 0; a < 3; ++a) count += (satisfied >> a) & 1u;
  }
  return count;
}

Eigen::Vector3d NodeMisfit(const ErrorNodes& nodes, std::size_t i, const Eigen::Vector3d& w_s_B) {
  Eigen::Vector3d d = nodes.w_m_B[i] - w_s_B;
  const std::uint8_t satisfied = SatisfiedCensoredAxes(nodes, i, w_s_B);
  for (int a = 0; a < 3; ++a) {
    if ((satisfied & (1u << a)) != 0) d[a] = 0.0;
  }
  return d;
}

double TrajectoryError(const ErrorNodes& nodes, const std::vector<Eigen::Vector3d>& w_s_B) {
  double integral = 0.0;  // ∫ ‖ω_m − ω_s‖ dt [rad]
  const bool any_censored = !nodes.censored_axes.empty();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (any_censored && nodes.censored_axes[i] != 0) {
      integral += nodes.weight_s[i] * NodeMisfit(nodes, i, w_s_B[i]).norm();
    } else {
      // A plain measurement (every node of the usual trial): NodeMisfit's plain difference, without its tests.
      const Eigen::Vector3d d = nodes.w_m_B[i] - w_s_B[i];
      integral += nodes.weight_s[i] * d.norm();
    }
  }
  const double covered_s = nodes.weighted_duration_s();
  if (nodes.num_excluded == nodes.size() || !(covered_s > 0.0)) return std::numeric_limits<double>::infinity();
  return integral / covered_s;  // (28)
}

}  // namespace rockfit::fitting
