#include "rockfit/io/stochastic_ground_motion.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::io {
namespace {

TEST(StochasticGroundMotion, SameSeedSameRecordAndPeakIsThePga) {
  CloughPenzienOptions o;
  o.seed = 11;
  const std::vector<double> a = CloughPenzienRecord(o);
  EXPECT_EQ(a, CloughPenzienRecord(o));
  EXPECT_EQ(a.size(), 4001u);
  EXPECT_EQ(a.front(), 0.0);
  double peak = 0.0;
  for (double v : a) peak = std::max(peak, std::abs(v));
  EXPECT_NEAR(peak, o.pga_m_s2, 1e-12);
  o.seed = 12;
  EXPECT_NE(a, CloughPenzienRecord(o));
}

// Mean power of the stationary part in a band, from a long record by a plain DFT.
double BandPower(const std::vector<double>& a, double dt, double f_lo, double f_hi) {
  const std::size_t n = a.size();
  double power = 0.0;
  for (std::size_t k = 1; k < n / 2; ++k) {
    const double f = static_cast<double>(k) / (static_cast<double>(n) * dt);
    if (f < f_lo || f > f_hi) continue;
    std::complex<double> sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) sum += a[j] * std::polar(1.0, -2.0 * M_PI * static_cast<double>(k * j) / n);
    power += std::norm(sum);
  }
  return power;
}

TEST(StochasticGroundMotion, SpectrumFollowsTheCloughPenzienShape) {
  // A long stationary record (no decay): the band around ω_g carries far more power than the band below the
  // high-pass corner ω_f, as the filter's density (ratio ≈ 500 between 0.05 Hz and 2.5 Hz) says.
  CloughPenzienOptions o;
  o.duration_s = 80.0;
  o.dt_s = 0.02;
  o.t_rise_s = 0.01;
  o.t_strong_end_s = 80.0;
  o.seed = 3;
  const std::vector<double> a = CloughPenzienRecord(o);
  const double near_ground = BandPower(a, o.dt_s, 2.0, 3.0) / 1.0;
  const double below_corner = BandPower(a, o.dt_s, 0.0125, 0.1) / 0.0875;
  EXPECT_GT(near_ground, 50.0 * below_corner);
}

TEST(StochasticGroundMotion, RejectsBadOptions) {
  CloughPenzienOptions o;
  o.dt_s = 0.0;
  EXPECT_THROW(CloughPenzienRecord(o), InvalidArgument);
  o = CloughPenzienOptions{};
  o.t_strong_end_s = 1.0;
  EXPECT_THROW(CloughPenzienRecord(o), InvalidArgument);
  // The shared checks (core/checks.hpp) name the option and the value.
  o = CloughPenzienOptions{};
  o.omega_g_rad_s = -2.5;
  try {
    o.Validate();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "omega_g must be a positive finite number, got -2.5");
  }
  o = CloughPenzienOptions{};
  o.decay_per_s = -1.0;
  EXPECT_THROW(o.Validate(), InvalidArgument);
}

TEST(StochasticGroundMotion, ParametersThatWouldGiveAnUnstableOrTooShortRecordAreRefused) {
  for (auto change : {+[](CloughPenzienOptions& o) { o.omega_f_rad_s = 1000.0; },
                      +[](CloughPenzienOptions& o) { o.omega_g_rad_s = 1000.0; },
                      +[](CloughPenzienOptions& o) { o.zeta_g = 1e300; },
                      +[](CloughPenzienOptions& o) { o.dt_s = 100.0; },
                      +[](CloughPenzienOptions& o) { o.duration_s = 1e9; }}) {
    CloughPenzienOptions o;
    change(o);
    EXPECT_THROW(o.Validate(), InvalidArgument);
  }
  CloughPenzienOptions o;
  o.omega_g_rad_s = 1000.0;
  try {
    o.Validate();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("omega_g = 1000 rad/s"), std::string::npos) << e.what();
  }
  // At the edge of the stable region the record is finite.
  o = CloughPenzienOptions{};
  o.omega_g_rad_s = 2.0 / o.dt_s;
  o.zeta_g = 1.0;
  for (double v : CloughPenzienRecord(o)) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace rockfit::io
