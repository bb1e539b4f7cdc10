// An independent reference for the simulator under ground motion: the planar rocking equation of a block on
// a table with horizontal acceleration a_x(t) (Housner 1963; Zhang & Makris 2001, eq. 1), integrated with
// GSL's rk8pd and its own event search, and the impact rule (6):
//   J θ̈ = s m [ −g R sin(θ_c − |θ|) + s a_x(t) R cos(θ_c − |θ|) ],   s = sign θ,   J = Θ_yy + m R²,
// θ > 0 rocking about the edge x = −b1 (lifted by a_x > 0), θ̇⁺ = r θ̇⁻ at θ = 0 with r of (6); the block
// leaves rest when a_x h > g b1 (θ > 0) or −a_x h > g b1 (θ < 0). Rest is done the textbook way: every impact
// is integrated, also those of a Zeno sequence, until |θ̇| after an impact falls below `rest_rate_rad_s`
// (1e-9 rad/s); the block then rests if the table cannot tip it at that instant, and otherwise rocks on from
// θ̇ = 0 on the side the table lifts. It overturns when |θ| reaches θ_c (or, when asked, π/2: it lies on its
// side). Nothing here uses rockfit's simulator.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

namespace rockfit::testing {

struct PlanarBaseRocking {
  double mass_kg = 1.0;
  double b_m = 0.05;    // half-width in the rocking plane
  double h_m = 0.2;     // COM height
  double theta_yy = 0.0;  // moment of inertia about the COM
  double gravity = 9.81;
  double lambda = 1.0;  // (6)
  double dt_record_s = 0.01;
  std::vector<double> a_x;  // record samples at k·dt, linear between, zero outside
  double rest_rate_rad_s = 1e-9;
  // Overturned when |θ| reaches this; 0: θ_c (the COM over the edge). π/2: the block lies on its side, the
  // equation going on past θ_c, where the table can still pull the block back.
  double overturn_tilt_rad = 0.0;

  double R() const { return std::hypot(b_m, h_m); }
  double ThetaC() const { return std::atan2(b_m, h_m); }
  double J() const { return theta_yy + mass_kg * R() * R(); }
  double Restitution() const {
    const double j0 = theta_yy + mass_kg * h_m * h_m;
    const double mb2 = mass_kg * b_m * b_m;
    return (j0 - lambda * mb2) / (j0 + lambda * mb2);
  }
  double Accel(double t) const {
    if (t < 0.0 || a_x.empty()) return 0.0;
    const double x = t / dt_record_s;
    const double last = static_cast<double>(a_x.size() - 1);
    if (x > last) return 0.0;
    const std::size_t k = std::min(static_cast<std::size_t>(x), a_x.size() - 2);
    const double u = x - static_cast<double>(k);
    return (1.0 - u) * a_x[k] + u * a_x[k + 1];
  }
};

struct PlanarResult {
  std::vector<double> uplift_times;  // from rest (a rest followed at once by rocking counts as neither)
  std::vector<double> impact_times;
  std::vector<double> rest_times;    // the impacts after which the block rests
  double peak_tilt = 0.0;  // largest |θ| at the output times
  std::vector<double> output_theta;  // θ at k·output_dt_s (until the end of the run)
  bool overturned = false;
  double t_overturn = 0.0;
};

namespace detail {

inline int PlanarRhs(double t, const double y[], double dydt[], void* raw) {
  const auto* m = static_cast<const PlanarBaseRocking*>(raw);
  const double s = y[0] > 0.0 ? 1.0 : (y[0] < 0.0 ? -1.0 : (y[1] >= 0.0 ? 1.0 : -1.0));
  const double psi = std::abs(y[0]);
  const double k = m->mass_kg * m->R() / m->J();
  dydt[0] = y[1];
  dydt[1] = s * k * (-m->gravity * std::sin(m->ThetaC() - psi) + s * m->Accel(t) * std::cos(m->ThetaC() - psi));
  return GSL_SUCCESS;
}

// Integrates from (t0, y0) to t1 (no breaks inside) with rk8pd at tight tolerances.
inline void Advance(const PlanarBaseRocking& m, double t0, const double y0[2], double t1, double y1[2]) {
  gsl_odeiv2_system system{PlanarRhs, nullptr, 2, const_cast<PlanarBaseRocking*>(&m)};
  gsl_odeiv2_driver* driver = gsl_odeiv2_driver_alloc_y_new(&system, gsl_odeiv2_step_rk8pd, 1e-5, 1e-14, 1e-14);
  double t = t0;
  y1[0] = y0[0];
  y1[1] = y0[1];
  if (t1 > t0) gsl_odeiv2_driver_apply(driver, &t, t1, y1);
  gsl_odeiv2_driver_free(driver);
}

}  // namespace detail

// Runs from flat rest at t = 0 to t_end, with chunks of `chunk_s` (and the record's sample times) as the
// steps of the event search; an event is bisected to 1e-13 s by re-integration from the chunk start.
inline PlanarResult SimulatePlanarBaseRocking(const PlanarBaseRocking& m, double t_end, double output_dt_s,
                                              double chunk_s = 1e-3) {
  gsl_set_error_handler_off();
  PlanarResult out;
  std::size_t next_output = 0;
  const auto output_time = [&](std::size_t k) { return static_cast<double>(k) * output_dt_s; };
  // Outputs up to time t in a state of rest.
  const auto rest_until = [&](double t_until) {
    while (output_time(next_output) < t_until && output_time(next_output) <= t_end) {
      out.output_theta.push_back(0.0);
      ++next_output;
    }
  };
  const double g_b = m.gravity * m.b_m;
  const auto margin = [&](double t, double side) { return side * m.Accel(t) * m.h_m - g_b; };
  double peak_accel = 0.0;
  for (double a : m.a_x) peak_accel = std::max(peak_accel, std::abs(a));
  double t = 0.0;
  double y[2] = {0.0, 0.0};
  bool resting = true;
  bool just_stopped = false;  // θ̇ vanished at an impact: rest, or rocking on from θ̇ = 0
  const double theta_over = m.overturn_tilt_rad > 0.0 ? m.overturn_tilt_rad : m.ThetaC();
  while (t < t_end) {
    if (resting) {
      // Next uplift: the margins are linear between record samples.
      double found = -1.0;
      double side = 0.0;
      for (double t0 = t; t0 < t_end && found < 0.0;) {
        const double t1 = std::min(t_end, (std::floor(t0 / m.dt_record_s + 1e-9) + 1.0) * m.dt_record_s);
        for (double sd : {1.0, -1.0}) {
          const double m0 = margin(t0, sd);
          const double m1 = margin(t1 - 1e-15 * t1, sd);
          if (m0 > 0.0) { found = t0; side = sd; break; }
          if (m1 > 0.0) {
            const double r = t0 + (t1 - t0) * (-m0) / (m1 - m0);
            if (found < 0.0 || r < found) { found = r; side = sd; }
          }
        }
        t0 = t1;
      }
      if (found < 0.0) {
        rest_until(t_end + output_dt_s);
        return out;
      }
      if (just_stopped && found == t) {
        out.rest_times.pop_back();  // the table tips the block at once: it never rested
      } else {
        rest_until(found);
        out.uplift_times.push_back(found);
      }
      just_stopped = false;
      t = found;
      y[0] = 0.0;
      y[1] = 0.0;
      resting = false;
      // Start on the lifted side: θ has the sign of `side` from here on.
      y[0] = side * 1e-300;
    }
    const double next_sample = (std::floor(t / m.dt_record_s + 1e-9) + 1.0) * m.dt_record_s;
    // A chunk must not hold two crossings of θ = 0 (an impact, the motion through θ = 0 on the wrong side's
    // equation, and a return): keep it below a quarter of the time |θ| and |θ̇| need to come back under the
    // largest angular acceleration the table can give.
    const double accel_bound = m.mass_kg * m.R() / m.J() * (m.gravity + peak_accel);
    const double return_s = (std::abs(y[1]) + std::sqrt(2.0 * accel_bound * std::abs(y[0]))) / accel_bound;
    const double t1 = std::min({t + std::min(chunk_s, std::max(0.25 * return_s, 1e-13)), next_sample, t_end,
                                output_time(next_output)});
    double y1[2];
    detail::Advance(m, t, y, t1, y1);
    const double side = y[0] >= 0.0 ? 1.0 : -1.0;
    const bool crossed = side * y1[0] < 0.0;
    const bool over = std::abs(y1[0]) >= theta_over;
    if (!crossed && !over) {
      if (t1 == output_time(next_output)) {
        out.output_theta.push_back(y1[0]);
        out.peak_tilt = std::max(out.peak_tilt, std::abs(y1[0]));
        ++next_output;
      }
      t = t1;
      y[0] = y1[0];
      y[1] = y1[1];
      continue;
    }
    // Bisect the first event in (t, t1].
    double lo = t, hi = t1;
    while (hi - lo > 1e-13) {
      const double mid = 0.5 * (lo + hi);
      double ym[2];
      detail::Advance(m, t, y, mid, ym);
      const bool event = over ? std::abs(ym[0]) >= theta_over : side * ym[0] < 0.0;
      (event ? hi : lo) = mid;
    }
    double ye[2];
    detail::Advance(m, t, y, hi, ye);
    if (over) {
      out.overturned = true;
      out.t_overturn = hi;
      return out;
    }
    out.impact_times.push_back(hi);
    const double rate = m.Restitution() * ye[1];
    t = hi;
    if (std::abs(rate) < m.rest_rate_rad_s) {
      out.rest_times.push_back(hi);
      resting = true;
      just_stopped = true;
      continue;
    }
    y[0] = -side * 1e-300;
    y[1] = rate;
  }
  return out;
}

}  // namespace rockfit::testing
