#include "rockfit/io/stochastic_ground_motion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "rockfit/core/checks.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/io/synth_random.hpp"

namespace rockfit::io {
namespace {

// More samples than this are refused (a day at 1 kHz is below it).
constexpr double kMaxSamples = 1e8;

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
  if (duration_s / dt_s > kMaxSamples) throw InvalidArgument("duration/dt asks for more than 1e8 samples");
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
  if (peak > 0.0) {
    for (double& v : a) v *= o.pga_m_s2 / peak;
  }
  return a;
}

}  // namespace rockfit::io
