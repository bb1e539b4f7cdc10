// Overturning without impact of a slender rigid block under a one-sine acceleration pulse a_p·sin(ω_p t),
// 0 ≤ t ≤ 2π/ω_p, in closed form: the linearised rocking equation (Housner 1963), whose solution under such a
// pulse Zhang & Makris (2001) use for the overturning "without impact" of their pulse study. Independent of
// the simulator: no integration, the solution is explicit.
//
// With φ the rotation about the pivot in units of α = θ_c, time in units of 1/p (p² = m g R / I_O) and
// a = a_p / (g α), the block uplifts at sin(r t_u) = 1/a (r = ω_p/p) and then, until it lands (φ = 0),
//
//   φ'' − φ = a sin(r t) − 1,        φ(t_u) = φ'(t_u) = 0,
//   φ(t) = A cosh(t − t_u) + B sinh(t − t_u) + 1 + C sin(r t),
//   C = −a / (1 + r²),   A = −1 − C sin(r t_u),   B = −C r cos(r t_u).
//
// Overturning is geometric, as in rockfit (the centre of mass passes over the pivot: φ reaches 1). During the
// pulse that is read off the solution; after it (T = 2π/r) the motion is free, φ'' = φ − 1, and reaches φ = 1
// iff the coefficient of e^t is positive: (φ(T) − 1) + φ'(T) > 0. The block overturns without landing iff φ
// reaches 1 before it returns to 0.
//
// A criterion that lets the block pass φ = 1 during the pulse and judges only the free motion after it (a block
// past θ_c can still be pulled back by the pulse's second half) gives a higher boundary:
// OverturnsAtPulseEndLinearised.
#pragma once

#include <cmath>

namespace rockfit::testing {

namespace one_sine_detail {

struct Solution {
  double t_u, t_end, A, B, c, r;
  double phi(double t) const { return A * std::cosh(t - t_u) + B * std::sinh(t - t_u) + 1.0 + c * std::sin(r * t); }
  double phi_dot(double t) const { return A * std::sinh(t - t_u) + B * std::cosh(t - t_u) + c * r * std::cos(r * t); }
  // Leaves for good after the pulse (free motion, linearised).
  bool LeavesAfterThePulse() const { return (phi(t_end) - 1.0) + phi_dot(t_end) > 0.0; }
};

inline Solution Solve(double r, double a) {
  Solution s;
  s.r = r;
  s.t_u = std::asin(1.0 / a) / r;
  s.t_end = 2.0 * M_PI / r;
  s.c = -a / (1.0 + r * r);
  s.A = -1.0 - s.c * std::sin(r * s.t_u);
  s.B = -s.c * r * std::cos(r * s.t_u);
  return s;
}

// φ on (t_u, T] sampled finely (φ is smooth; its extrema are not narrow against this step).
constexpr int kSamples = 20000;

}  // namespace one_sine_detail

// Whether the linearised block overturns (φ reaches 1) before it lands (φ returns to 0); r = ω_p/p,
// a = a_p/(g α).
inline bool OverturnsWithoutImpactLinearised(double r, double a) {
  if (!(a > 1.0)) return false;  // never uplifts
  const one_sine_detail::Solution s = one_sine_detail::Solve(r, a);
  for (int k = 1; k <= one_sine_detail::kSamples; ++k) {
    const double phi = s.phi(s.t_u + (s.t_end - s.t_u) * k / one_sine_detail::kSamples);
    if (phi >= 1.0) return true;
    if (phi <= 0.0) return false;
  }
  return s.LeavesAfterThePulse();
}

// The other criterion: no landing during the pulse, and the free motion after it leaves.
inline bool OverturnsAtPulseEndLinearised(double r, double a) {
  if (!(a > 1.0)) return false;
  const one_sine_detail::Solution s = one_sine_detail::Solve(r, a);
  for (int k = 1; k <= one_sine_detail::kSamples; ++k) {
    if (s.phi(s.t_u + (s.t_end - s.t_u) * k / one_sine_detail::kSamples) <= 0.0) return false;
  }
  return s.LeavesAfterThePulse();
}

}  // namespace rockfit::testing
