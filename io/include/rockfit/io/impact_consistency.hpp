// Which candidate impacts really are instants where an Euler angle is zero (docs/design.md §6 drift correction).
//
// A peak of |ω_y| marks a landing on a base edge along x or on the whole base, where φ_y = 0 — but in
// three-dimensional rocking a block tilted about y that rolls from one vertex onto the neighbouring one (an
// edge impact of the edge along y) can make a smaller |ω_y| peak too, at φ_y far from zero. The gyro tells them
// apart without the drifting angle: between two instants where φ_y = 0 the integral of its rate φ̇_y is zero,
// while from a zero of φ_y to such a tilted instant it is the tilt. Starting from the candidate with the
// largest |ω| peak (the first landing after the release in a rocking test), the candidates are accepted in
// time order, forwards and backwards, when the integrated rate since the last accepted one has come back
// within `max_return_fraction` of the largest swing in between (plus `return_tolerance_rad` for the gyro
// bias). The same holds for φ_x with φ̇_x.
#pragma once

#include <cstddef>
#include <vector>

namespace rockfit::io {

struct ImpactConsistencyOptions {
  // The angle integrated from the gyro must come back to within this fraction of the swing in between.
  double max_return_fraction = 0.25;
  // ... plus this much [rad]: 3e-3 rad is a gyro bias of 0.01 rad/s (0.6 °/s) over 0.3 s between impacts.
  double return_tolerance_rad = 3e-3;
  void Validate() const;
};

// `candidate_times_s` ascending, `strength` (e.g. the |ω| peak) of each; `rate_rad_s` the Euler rate of the
// angle at the samples `t_s`. Returns the indices of the accepted candidates, ascending.
std::vector<std::size_t> ConsistentZeroInstants(const std::vector<double>& t_s, const std::vector<double>& rate_rad_s,
                                                const std::vector<double>& candidate_times_s,
                                                const std::vector<double>& strength,
                                                const ImpactConsistencyOptions& options);

}  // namespace rockfit::io
