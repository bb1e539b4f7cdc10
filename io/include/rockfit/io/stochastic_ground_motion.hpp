// A stochastic ground-motion generator, so that samples and tests need no external records
// (io/README.md, "Stochastic ground motion").
//
// Model: Clough–Penzien filtered white noise (Kanai 1957, Tajimi 1960, Clough & Penzien 1975) times a
// deterministic envelope (Jennings, Housner & Tsai 1968). A white noise w(t) drives the Kanai–Tajimi soil
// filter (ω_g, ζ_g); its absolute acceleration drives the Clough–Penzien high-pass filter (ω_f, ζ_f), which
// removes the unbounded low-frequency content (the ground displacement stays bounded):
//   ẍ_g + 2ζ_g ω_g ẋ_g + ω_g² x_g = −w(t),   a_1 = −(2ζ_g ω_g ẋ_g + ω_g² x_g),
//   ẍ_f + 2ζ_f ω_f ẋ_f + ω_f² x_f = −a_1,     a_s(t) = ẍ_f,
// power spectral density S_0·(ω_g⁴ + 4ζ_g²ω_g²ω²)/((ω_g² − ω²)² + 4ζ_g²ω_g²ω²)·ω⁴/((ω_f² − ω²)² + 4ζ_f²ω_f²ω²).
// The record is a(t) = e(t)·a_s(t) with e = (t/t_1)² before t_1, 1 up to t_2, exp(−c(t − t_2)) after,
// scaled so that max|a| is the given PGA. w is held constant over each step (standard normal / √dt, from
// SynthRandom: the same seed gives the same record bit for bit on every platform); the filters are
// integrated with classical RK4 at the record step.
#pragma once

#include <cstdint>
#include <vector>

namespace rockfit::io {

struct CloughPenzienOptions {
  double omega_g_rad_s = 15.6;  // Kanai–Tajimi ground frequency (firm soil, ≈ 2.5 Hz)
  double zeta_g = 0.6;
  double omega_f_rad_s = 1.5;   // Clough–Penzien high-pass corner (≈ 0.24 Hz)
  double zeta_f = 0.6;
  double t_rise_s = 2.0;        // t_1
  double t_strong_end_s = 10.0; // t_2
  double decay_per_s = 0.35;    // c
  double duration_s = 20.0;
  double dt_s = 0.005;
  double pga_m_s2 = 2.94;       // 0.3 g
  std::uint64_t seed = 1;
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

// round(duration/dt) + 1 samples a(k·dt) [m/s²], the first zero.
std::vector<double> CloughPenzienRecord(const CloughPenzienOptions& options);

}  // namespace rockfit::io
