#include "rockfit/core/planar_sensitivity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "dop853.hpp"
#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_avrf.hpp"

namespace rockfit::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Parameters whose derivatives are propagated through the swings: α and λ_lon.
constexpr int kNumPropagated = 2;
constexpr int kAlphaSlot = 0;
constexpr int kLambdaLonSlot = 1;
// (ψ, ψ̇) and (δψ, δψ̇) for each propagated parameter.
constexpr int kStateSize = 2 + 2 * kNumPropagated;
using State = Eigen::Matrix<double, kStateSize, 1>;

// One swing about a base edge: ψ̈ = −(K/2) sin(θ_c − ψ) and its variational equation
// δψ̈ = (K/2) cos(θ_c − ψ) δψ (edge_dynamics.hpp).
struct SwingEquations {
  double half_K_1_s2 = 0.0;
  double theta_c_rad = 0.0;
  double Acceleration(double psi_rad) const { return -half_K_1_s2 * std::sin(theta_c_rad - psi_rad); }
  double Stiffness(double psi_rad) const { return half_K_1_s2 * std::cos(theta_c_rad - psi_rad); }
  void operator()(double /*t*/, const State& y, State& dydt) const {
    dydt[0] = y[1];
    dydt[1] = Acceleration(y[0]);
    const double stiffness = Stiffness(y[0]);
    for (int p = 0; p < kNumPropagated; ++p) {
      dydt[2 + 2 * p] = y[3 + 2 * p];
      dydt[3 + 2 * p] = stiffness * y[2 + 2 * p];
    }
  }
};

PlanarSensitivitySummary NotAvailable(std::string reason) {
  PlanarSensitivitySummary summary;
  summary.reason = std::move(reason);
  return summary;
}

// The planar AVRF (6) of a facet impact after a swing about the edge with axis a_B, and ∂r/∂λ_lon.
void FacetAvrf(const Block& block, const Eigen::Vector3d& axis_B, double lambda_lon, double* r, double* dr_dlambda) {
  const PlanarBlock planar = std::abs(axis_B.y()) > std::abs(axis_B.x()) ? PlanarBlockAboutY(block) : PlanarBlockAboutX(block);
  const double j0 = planar.theta_kg_m2 + planar.mass_kg * planar.h_m * planar.h_m;
  const double mb2 = planar.mass_kg * planar.b_m * planar.b_m;
  *r = AvrfChatzis(planar, lambda_lon);  // (6)
  const double denominator = j0 + lambda_lon * mb2;
  *dr_dlambda = -2.0 * j0 * mb2 / (denominator * denominator);
}

}  // namespace

void PlanarSensitivityOptions::Validate() const {
  auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0)) {
      throw InvalidArgument(fmt::format("planar sensitivities: {} must be a positive finite number, got {}", name, v));
    }
  };
  positive(rel_tol, "rel_tol");
  positive(abs_tol, "abs_tol");
  positive(agreement_tol_rad_s, "agreement_tol_rad_s");
}

PlanarSensitivitySummary PlanarSampleSensitivities(const Block& block, const ModelParameters& params,
                                                   const SimulationOptions& options, const Trajectory& trajectory,
                                                   const PlanarSensitivityOptions& sensitivity_options) {
  sensitivity_options.Validate();
  if (params.lambda_lat != 0.0) return NotAvailable("lambda_lat is not 0: the run is not planar");
  if (options.initial_state) return NotAvailable("the run starts from an initial state, not from the release");
  if (params.release_roll_rad != 0.0) return NotAvailable("the release is rolled: the run is not planar");
  if (trajectory.end_reason == EndReason::kFailed || trajectory.end_reason == EndReason::kOverturned) {
    return NotAvailable(fmt::format("the run ended as {}", ToString(trajectory.end_reason)));
  }
  if (trajectory.w_B.size() != trajectory.t_s.size()) return NotAvailable("the trajectory has no samples of w_B");
  // The landings: facet impacts, the last possibly followed by the rest at the same instant.
  std::vector<const ImpactRecord*> landings;
  bool rests = false;
  for (const ImpactRecord& impact : trajectory.impacts) {
    if (impact.kind == ImpactKind::kFacet && !rests) {
      landings.push_back(&impact);
    } else if (impact.kind == ImpactKind::kRest && !rests) {
      rests = true;
    } else {
      return NotAvailable(fmt::format("a {} impact at t = {} s: the run is not planar", ToString(impact.kind), impact.t_s));
    }
  }

  PlanarSensitivitySummary summary;
  const std::size_t num_samples = trajectory.t_s.size();
  summary.dw_B.assign(num_samples, SampleSensitivity::Zero());
  for (SampleSensitivity& d : summary.dw_B) d.col(static_cast<int>(SensitivityColumn::kLambdaLat)).setConstant(kNaN);

  Dop853Options integrator_options;
  integrator_options.rel_tol = sensitivity_options.rel_tol;
  integrator_options.abs_tol = sensitivity_options.abs_tol;
  Dop853<kStateSize> integrator(integrator_options);

  // The swing in progress: its edge, its start time and the state (with its fixed-time derivatives) there.
  Contact edge = Contact::Edge(options.release_edge_first, options.release_edge_second);
  double t_start_s = 0.0;
  State y = State::Zero();
  y[0] = params.alpha_rad;
  y[2 + 2 * kAlphaSlot] = 1.0;  // ∂ψ/∂α at the release
  // Samples before the release hold the block at rest: ω = 0 and no derivative.
  std::size_t k = static_cast<std::size_t>(
      std::lower_bound(trajectory.t_s.begin(), trajectory.t_s.end(), 0.0) - trajectory.t_s.begin());
  const double t_run_end_s = trajectory.t_end_s;

  for (std::size_t swing = 0;; ++swing) {
    const EdgeDynamics dynamics(block, edge.first, edge.second, options.gravity_m_s2);
    const SwingEquations equations{0.5 * dynamics.swing_constant_1_s2(), dynamics.critical_angle_rad()};
    const Eigen::Vector3d& axis_B = dynamics.axis_B();
    const bool lands = swing < landings.size();
    const double t_stop_s = lands ? landings[swing]->t_s : t_run_end_s;
    ++summary.swings;
    integrator.Reset(equations, t_start_s, y);
    // Samples in [t_start, t_stop); the last swing of a run that does not land also takes a sample at its end.
    auto in_swing = [&](double t) { return t < t_stop_s || (!lands && t <= t_stop_s); };
    State y_sample;
    while (integrator.t() < t_stop_s) {
      if (integrator.Step(equations, t_stop_s) != StepStatus::kOk) {
        return NotAvailable(fmt::format("the variational equations could not be integrated at t = {} s", integrator.t()));
      }
      bool dense = false;
      while (k < num_samples && trajectory.t_s[k] <= integrator.t() && in_swing(trajectory.t_s[k])) {
        if (!dense) {
          integrator.PrepareDense(equations);
          dense = true;
        }
        integrator.Interpolate(trajectory.t_s[k], &y_sample);
        const Eigen::Vector3d w_B = y_sample[1] * axis_B;
        summary.max_disagreement_rad_s = std::max(summary.max_disagreement_rad_s, (w_B - trajectory.w_B[k]).norm());
        if ((w_B - trajectory.w_B[k]).norm() > sensitivity_options.agreement_tol_rad_s * (1.0 + w_B.norm())) {
          return NotAvailable(fmt::format("the swing computed here differs from the simulator's sample at t = {} s "
                                          "by {} rad/s: the run is not the planar motion described",
                                          trajectory.t_s[k], (w_B - trajectory.w_B[k]).norm()));
        }
        SampleSensitivity& d = summary.dw_B[k];
        d.col(static_cast<int>(SensitivityColumn::kTime)) = equations.Acceleration(y_sample[0]) * axis_B;
        d.col(static_cast<int>(SensitivityColumn::kAlpha)) = y_sample[3 + 2 * kAlphaSlot] * axis_B;
        d.col(static_cast<int>(SensitivityColumn::kLambdaLon)) = y_sample[3 + 2 * kLambdaLonSlot] * axis_B;
        ++k;
      }
    }
    if (!lands) break;

    // The landing ψ = 0 at T: the event moves by dT = −δψ/ψ̇⁻; the pre-impact rate along the moved event is
    // Dψ̇⁻ = δψ̇ + ψ̈⁻ dT.
    const State& y_minus = integrator.y();
    const double rate_minus = y_minus[1];
    if (!(rate_minus < 0.0)) {
      return NotAvailable(fmt::format("the swing does not fall at the landing at t = {} s", t_stop_s));
    }
    const double acceleration_minus = equations.Acceleration(0.0);
    std::array<double, kNumPropagated> dT{}, D_rate_minus{};
    for (int p = 0; p < kNumPropagated; ++p) {
      dT[p] = -y_minus[2 + 2 * p] / rate_minus;
      D_rate_minus[p] = y_minus[3 + 2 * p] + acceleration_minus * dT[p];
    }
    if (swing + 1 == landings.size() && rests) break;  // at rest after this landing: ω = 0 from here on

    const ImpactRecord& landing = *landings[swing];
    if (!landing.contact_after.is_edge()) {
      return NotAvailable(fmt::format("the facet impact at t = {} s leaves contact {}: the run is not planar",
                                      landing.t_s, landing.contact_after.ToString()));
    }
    double r = 0.0, dr_dlambda_lon = 0.0;
    FacetAvrf(block, axis_B, params.lambda_lon, &r, &dr_dlambda_lon);
    if (!(r > 0.0)) return NotAvailable(fmt::format("the facet AVRF r = {} is not positive", r));
    // (6): ω⁺ = r ω⁻ about the same body axis; the new edge's ψ̇⁺ is positive (the other side lifts).
    const EdgeDynamics next(block, landing.contact_after.first, landing.contact_after.second, options.gravity_m_s2);
    const double axis_sign = next.axis_B().dot(axis_B) > 0.0 ? 1.0 : -1.0;
    const double rate_plus = axis_sign * r * rate_minus;
    if (!(rate_plus > 0.0)) return NotAvailable(fmt::format("the swing after t = {} s does not lift", landing.t_s));
    const SwingEquations next_equations{0.5 * next.swing_constant_1_s2(), next.critical_angle_rad()};
    const double acceleration_plus = next_equations.Acceleration(0.0);
    State y_plus = State::Zero();
    y_plus[1] = rate_plus;
    for (int p = 0; p < kNumPropagated; ++p) {
      const double dr = p == kLambdaLonSlot ? dr_dlambda_lon : 0.0;
      const double D_rate_plus = axis_sign * (r * D_rate_minus[p] + dr * rate_minus);
      // The fixed-time derivative at T of the post-impact state (ψ⁺ = 0 along the moved event).
      y_plus[2 + 2 * p] = -rate_plus * dT[p];
      y_plus[3 + 2 * p] = D_rate_plus - acceleration_plus * dT[p];
    }
    edge = landing.contact_after;
    t_start_s = landing.t_s;
    y = y_plus;
    // A sample exactly at the landing belongs to the swing after it.
  }
  // Samples after the rest (or past the end) keep ω = 0 and no derivative; check that the simulator agrees.
  for (; k < num_samples; ++k) {
    summary.max_disagreement_rad_s = std::max(summary.max_disagreement_rad_s, trajectory.w_B[k].norm());
    if (trajectory.w_B[k].norm() > sensitivity_options.agreement_tol_rad_s) {
      return NotAvailable(fmt::format("the simulator's sample at t = {} s is not at rest", trajectory.t_s[k]));
    }
  }
  summary.available = true;
  return summary;
}

}  // namespace rockfit::core
