#include "rockfit/io/stochastic_ground_motion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/input_limits.hpp"
#include "rockfit/io/synth_random.hpp"

namespace rockfit::io {
namespace {

// Classical RK4 integrates a linear filter stably while every eigenvalue λ of it has |λ|·dt inside its stability
// region, which holds the half disc of radius 2.78 left of the imaginary axis; 2 keeps a margin (the records are
// then also smooth: at least π sample steps per period of the fastest mode).
constexpr double kMaxRk4StepTimesRate = 2.0;

// The largest |λ| [rad/s] of ẍ + 2ζω ẋ + ω² x = f: ω when underdamped, ω(ζ + √(ζ² − 1)) otherwise.
double FastestRate_rad_s(double omega_rad_s, double zeta) {
  if (zeta <= 1.0) return omega_rad_s;
  return omega_rad_s * (zeta + std::sqrt((zeta - 1.0) * (zeta + 1.0)));
}

void RequireStableStep(double omega_rad_s, double zeta, double dt_s, const char* omega_name, const char* zeta_name) {
  const double rate_rad_s = FastestRate_rad_s(omega_rad_s, zeta);
  if (!(rate_rad_s * dt_s <= kMaxRk4StepTimesRate)) {
    throw InvalidArgument(fmt::format(
        "{} = {} rad/s with {} = {} and a step dt = {} s: the filter's fastest rate {:.4g} rad/s times dt is {:.4g}, "
        "above {}, where the record's integration becomes unstable; lower {} or {}, or the step dt", omega_name,
        omega_rad_s, zeta_name, zeta, dt_s, rate_rad_s, rate_rad_s * dt_s, kMaxRk4StepTimesRate, omega_name,
        zeta_name));
  }
}

// State (x_g, ẋ_g, x_f, ẋ_f) of the two filters.
using FilterState = std::array<double, 4>;

struct Filters {
  double wg, zg, wf, zf;
  double SoilAcceleration(const FilterState& s) const { return -(2.0 * zg * wg * s[1] + wg * wg * s[0]); }
  double Output(const FilterState& s) const { return -SoilAcceleration(s) - 2.0 * zf * wf * s[3] - wf * wf * s[2]; }
  FilterState Rate(const FilterState& s, double w) const {
    return {s[1], -w - 2.0 * zg * wg * s[1] - wg * wg * s[0], s[3], Output(s)};
  }
};

FilterState Add(const FilterState& s, const FilterState& k, double h) {
  return {s[0] + h * k[0], s[1] + h * k[1], s[2] + h * k[2], s[3] + h * k[3]};
}

double Envelope(const CloughPenzienOptions& o, double t) {
  if (t < o.t_rise_s) return (t / o.t_rise_s) * (t / o.t_rise_s);
  if (t <= o.t_strong_end_s) return 1.0;
  return std::exp(-o.decay_per_s * (t - o.t_strong_end_s));
}

}  // namespace

void CloughPenzienOptions::Validate() const {
  RequirePositive(omega_g_rad_s, "omega_g");
  RequirePositive(zeta_g, "zeta_g");
  RequirePositive(omega_f_rad_s, "omega_f");
  RequirePositive(zeta_f, "zeta_f");
  RequirePositive(t_rise_s, "t_rise");
  RequirePositive(duration_s, "duration");
  RequirePositive(dt_s, "dt");
  RequirePositive(pga_m_s2, "pga");
  RequireNonNegative(decay_per_s, "decay");
  if (!(t_strong_end_s >= t_rise_s) || !std::isfinite(t_strong_end_s)) {
    throw InvalidArgument("the end of the strong phase t_2 must not come before the rise time t_1");
  }
  if (!(duration_s / dt_s <= static_cast<double>(kMaxRecordSamples - 1))) {
    throw InvalidArgument(fmt::format("duration {} s at a step dt = {} s asks for {:.4g} samples, more than the {} of "
                                      "the largest record (docs/file-formats.md, \"Limits\"); shorten the duration "
                                      "or raise dt", duration_s, dt_s, duration_s / dt_s + 1.0, kMaxRecordSamples));
  }
  if (!(duration_s >= dt_s)) {
    throw InvalidArgument(fmt::format("duration {} s is shorter than the step dt = {} s: a record needs at least two "
                                      "samples", duration_s, dt_s));
  }
  RequireStableStep(omega_g_rad_s, zeta_g, dt_s, "omega_g", "zeta_g");
  RequireStableStep(omega_f_rad_s, zeta_f, dt_s, "omega_f", "zeta_f");
}

std::vector<double> CloughPenzienRecord(const CloughPenzienOptions& o) {
  o.Validate();
  const auto n = static_cast<std::size_t>(std::llround(o.duration_s / o.dt_s)) + 1;
  const Filters f{o.omega_g_rad_s, o.zeta_g, o.omega_f_rad_s, o.zeta_f};
  SynthRandom random(o.seed, SynthStream::kGroundMotion);
  const double noise_scale = 1.0 / std::sqrt(o.dt_s);
  std::vector<double> a(n, 0.0);
  FilterState s{0.0, 0.0, 0.0, 0.0};
  const double h = o.dt_s;
  for (std::size_t k = 1; k < n; ++k) {
    const double w = noise_scale * random.Normal();
    const FilterState k1 = f.Rate(s, w);
    const FilterState k2 = f.Rate(Add(s, k1, 0.5 * h), w);
    const FilterState k3 = f.Rate(Add(s, k2, 0.5 * h), w);
    const FilterState k4 = f.Rate(Add(s, k3, h), w);
    for (int i = 0; i < 4; ++i) s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    a[k] = Envelope(o, static_cast<double>(k) * h) * f.Output(s);
  }
  double peak = 0.0;
  for (double v : a) peak = std::max(peak, std::abs(v));
  if (!std::isfinite(peak)) {
    throw NumericalFailure("the Clough–Penzien filters overflowed; choose milder parameters (smaller omega_g, "
                           "omega_f, zeta_g, zeta_f, or a smaller dt)");
  }
  if (peak > 0.0) {
    for (double& v : a) v *= o.pga_m_s2 / peak;
  }
  return a;
}

}  // namespace rockfit::io
