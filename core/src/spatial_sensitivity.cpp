#include "rockfit/core/spatial_sensitivity.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "dop853.hpp"
#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/impact_map_derivatives.hpp"
#include "rockfit/core/vertex_dynamics.hpp"

namespace rockfit::core {
namespace {

// Parameters whose derivatives are propagated: α, λ, λ_lat, λ_lon (slot p is SensitivityColumn p + 1).
constexpr int kNumPropagated = 4;
constexpr int kAlphaSlot = 0;
constexpr int kLambdaSlot = 1;
constexpr int kLambdaLatSlot = 2;
constexpr int kLambdaLonSlot = 3;
int ColumnOf(int slot) { return slot + 1; }

// Vertex phase: q_WB (4), w_B (3), and (δθ, δw) per parameter.
constexpr int kVertexStateSize = 7 + 6 * kNumPropagated;
using VertexState = Eigen::Matrix<double, kVertexStateSize, 1>;
// Edge phase: (ψ, ψ̇) and (δψ, δψ̇) per parameter.
constexpr int kEdgeStateSize = 2 + 2 * kNumPropagated;
using EdgeState = Eigen::Matrix<double, kEdgeStateSize, 1>;

int ThetaAt(int slot) { return 7 + 6 * slot; }
int RateAt(int slot) { return 10 + 6 * slot; }

// The motion about a vertex and its variational equations (spatial_sensitivity.hpp).
class VertexEquations {
 public:
  VertexEquations(const Block& block, int vertex, double gravity_m_s2)
      : dynamics_(block, vertex, gravity_m_s2),
        inertia_(dynamics_.inertia_P_B()),
        inertia_inverse_(inertia_.inverse()),
        weight_N_(block.mass() * gravity_m_s2) {}

  void operator()(double t, const VertexState& y, VertexState& dydt) const {
    const VertexDynamics::State s = y.head<7>();
    VertexDynamics::State ds;
    dynamics_(t, s, ds);
    dydt.head<7>() = ds;
    const Eigen::Vector3d up_B = VertexDynamics::UpInBody(s);
    const Eigen::Vector3d w_B = s.tail<3>();
    const Eigen::Vector3d L_B = inertia_ * w_B;
    const Eigen::Vector3d& c = dynamics_.p_PC_B();
    for (int p = 0; p < kNumPropagated; ++p) {
      const Eigen::Vector3d d_theta = y.segment<3>(ThetaAt(p));
      const Eigen::Vector3d d_w = y.segment<3>(RateAt(p));
      dydt.segment<3>(ThetaAt(p)) = d_w - w_B.cross(d_theta);
      dydt.segment<3>(RateAt(p)) =
          inertia_inverse_ * (-d_w.cross(L_B) - w_B.cross(inertia_ * d_w) - weight_N_ * c.cross(up_B.cross(d_theta)));
    }
  }
  // ẇ_B at attitude/rate state s.
  Eigen::Vector3d Acceleration(const VertexDynamics::State& s) const {
    VertexDynamics::State ds;
    dynamics_(0.0, s, ds);
    return ds.tail<3>();
  }
  static Eigen::Vector3d Rate(const VertexState& y) { return y.segment<3>(4); }
  Eigen::Vector3d TimeDerivative(const VertexState& y) const { return Acceleration(y.head<7>()); }
  static Eigen::Vector3d RateDerivative(const VertexState& y, int slot) { return y.segment<3>(RateAt(slot)); }

 private:
  VertexDynamics dynamics_;
  Eigen::Matrix3d inertia_;
  Eigen::Matrix3d inertia_inverse_;
  double weight_N_;
};

// The swing about an edge and its variational equation.
class EdgeEquations {
 public:
  EdgeEquations(const Block& block, const Contact& edge, double gravity_m_s2)
      : dynamics_(block, edge.first, edge.second, gravity_m_s2),
        half_K_1_s2_(0.5 * dynamics_.swing_constant_1_s2()),
        theta_c_rad_(dynamics_.critical_angle_rad()) {}

  void operator()(double /*t*/, const EdgeState& y, EdgeState& dydt) const {
    dydt[0] = y[1];
    dydt[1] = Acceleration(y[0]);
    const double stiffness = half_K_1_s2_ * std::cos(theta_c_rad_ - y[0]);
    for (int p = 0; p < kNumPropagated; ++p) {
      dydt[2 + 2 * p] = y[3 + 2 * p];
      dydt[3 + 2 * p] = stiffness * y[2 + 2 * p];
    }
  }
  double Acceleration(double psi_rad) const { return -half_K_1_s2_ * std::sin(theta_c_rad_ - psi_rad); }
  const EdgeDynamics& dynamics() const { return dynamics_; }
  Eigen::Vector3d Rate(const EdgeState& y) const { return y[1] * dynamics_.axis_B(); }
  Eigen::Vector3d TimeDerivative(const EdgeState& y) const { return Acceleration(y[0]) * dynamics_.axis_B(); }
  Eigen::Vector3d RateDerivative(const EdgeState& y, int slot) const { return y[3 + 2 * slot] * dynamics_.axis_B(); }

 private:
  EdgeDynamics dynamics_;
  double half_K_1_s2_;
  double theta_c_rad_;
};

// One pass over a run: the samples and their derivatives, filled phase by phase.
class SensitivityPass {
 public:
  SensitivityPass(const Trajectory& trajectory, const SpatialSensitivityOptions& options, double max_step_s,
                  SpatialSensitivitySummary* summary)
      : trajectory_(trajectory), options_(options), summary_(summary) {
    integrator_options_.rel_tol = options.rel_tol;
    integrator_options_.abs_tol = options.abs_tol;
    integrator_options_.max_step = max_step_s;
    k_ = static_cast<std::size_t>(std::lower_bound(trajectory.t_s.begin(), trajectory.t_s.end(), 0.0) -
                                  trajectory.t_s.begin());
  }

  // ω agrees with `reference` to the tolerance; records the disagreement.
  bool Agrees(const Eigen::Vector3d& w_B, const Eigen::Vector3d& reference) {
    const double disagreement = (w_B - reference).norm();
    summary_->max_disagreement_rad_s = std::max(summary_->max_disagreement_rad_s, disagreement);
    return disagreement <= options_.agreement_tol_rad_s * (1.0 + reference.norm());
  }

  // Integrates a phase from (t_start, y) to t_stop and fills the samples in [t_start, t_stop) (or up to t_stop
  // inclusive for the last phase); *y ends at t_stop. Empty on success, otherwise why not.
  template <int N, class Equations>
  std::string Integrate(const Equations& equations, double t_start_s, double t_stop_s, bool last,
                        Eigen::Matrix<double, N, 1>* y) {
    auto in_phase = [&](double t) { return t < t_stop_s || (last && t <= t_stop_s); };
    auto sample = [&](const Eigen::Matrix<double, N, 1>& y_sample) -> std::string {
      const Eigen::Vector3d w_B = equations.Rate(y_sample);
      if (!Agrees(w_B, trajectory_.w_B[k_])) {
        return fmt::format("the phase computed here differs from the simulator's sample at t = {} s by {} rad/s",
                           trajectory_.t_s[k_], (w_B - trajectory_.w_B[k_]).norm());
      }
      SampleSensitivity& d = summary_->dw_B[k_];
      d.col(static_cast<int>(SensitivityColumn::kTime)) = equations.TimeDerivative(y_sample);
      for (int p = 0; p < kNumPropagated; ++p) d.col(ColumnOf(p)) = equations.RateDerivative(y_sample, p);
      ++k_;
      return {};
    };
    const std::size_t n = trajectory_.t_s.size();
    if (!(t_stop_s > t_start_s)) {
      // A phase of no duration (two events at one instant): only a last phase can own a sample, at its start.
      while (last && k_ < n && trajectory_.t_s[k_] <= t_start_s) {
        if (std::string error = sample(*y); !error.empty()) return error;
      }
      return {};
    }
    Dop853<N> integrator(integrator_options_);
    integrator.Reset(equations, t_start_s, *y);
    Eigen::Matrix<double, N, 1> y_sample;
    while (integrator.t() < t_stop_s) {
      if (integrator.Step(equations, t_stop_s) != StepStatus::kOk) {
        return fmt::format("the variational equations could not be integrated at t = {} s", integrator.t());
      }
      bool dense = false;
      while (k_ < n && trajectory_.t_s[k_] <= integrator.t() && in_phase(trajectory_.t_s[k_])) {
        if (!dense) {
          integrator.PrepareDense(equations);
          dense = true;
        }
        integrator.Interpolate(trajectory_.t_s[k_], &y_sample);
        if (std::string error = sample(y_sample); !error.empty()) return error;
      }
    }
    *y = integrator.y();
    return {};
  }

  // The samples after a rest: ω = 0 (checked) and no derivative.
  std::string AtRest() {
    for (; k_ < trajectory_.t_s.size(); ++k_) {
      if (!Agrees(Eigen::Vector3d::Zero(), trajectory_.w_B[k_])) {
        return fmt::format("the simulator's sample at t = {} s is not at rest", trajectory_.t_s[k_]);
      }
    }
    return {};
  }

 private:
  const Trajectory& trajectory_;
  const SpatialSensitivityOptions& options_;
  SpatialSensitivitySummary* summary_;
  Dop853Options integrator_options_;
  std::size_t k_ = 0;
};

SpatialSensitivitySummary NotAvailable(std::string reason) {
  SpatialSensitivitySummary summary;
  summary.reason = std::move(reason);
  return summary;
}

// ∂ω⁺/∂p of a map for parameter slot p.
Eigen::Vector3d ParameterDerivative(const ImpactMapDerivatives& d, int slot) {
  switch (slot) {
    case kLambdaSlot: return d.dw_plus_dlambda;
    case kLambdaLatSlot: return d.dw_plus_dlambda_lat;
    case kLambdaLonSlot: return d.dw_plus_dlambda_lon;
    default: return Eigen::Vector3d::Zero();
  }
}

// The other vertex of an edge contact.
int OtherVertex(const Contact& edge, int vertex) {
  return Block::WrapVertex(edge.first) == Block::WrapVertex(vertex) ? edge.second : edge.first;
}

}  // namespace

void SpatialSensitivityOptions::Validate() const {
  auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0)) {
      throw InvalidArgument(fmt::format("spatial sensitivities: {} must be a positive finite number, got {}", name, v));
    }
  };
  positive(rel_tol, "rel_tol");
  positive(abs_tol, "abs_tol");
  positive(agreement_tol_rad_s, "agreement_tol_rad_s");
}

SpatialSensitivitySummary SpatialSampleSensitivities(const Block& block, const ModelParameters& params,
                                                     const SimulationOptions& options, const Trajectory& trajectory,
                                                     const SpatialSensitivityOptions& sensitivity_options) {
  sensitivity_options.Validate();
  if (options.initial_state) return NotAvailable("the run starts from an initial state, not from the release");
  // A rolled release starts about a corner, not the edge this pass starts from (rolled_release.hpp).
  if (params.release_roll_rad != 0.0) return NotAvailable("the release is rolled: its first phase is not tracked");
  if (trajectory.end_reason == EndReason::kFailed || trajectory.end_reason == EndReason::kOverturned) {
    return NotAvailable(fmt::format("the run ended as {}", ToString(trajectory.end_reason)));
  }
  if (trajectory.w_B.size() != trajectory.t_s.size()) return NotAvailable("the trajectory has no samples of w_B");
  if (params.facet_tau_rule != FacetTauRule::kNoSpin) {
    return NotAvailable("the facet map's derivatives are for the no-spin rule only");
  }

  SpatialSensitivitySummary summary;
  summary.dw_B.assign(trajectory.t_s.size(), SampleSensitivity::Zero());
  SensitivityPass pass(trajectory, sensitivity_options, options.max_step_s, &summary);
  const double g = options.gravity_m_s2;
  const EdgeImpactParameters edge_params{params.lambda, params.tau_edge};
  FacetImpactParameters facet_params;
  facet_params.lambda_lat = params.lambda_lat;
  facet_params.lambda_lon = params.lambda_lon;

  // The phase in progress: about an edge (edge_y) or a vertex (vertex_y).
  bool about_edge = true;
  Contact contact = Contact::Edge(options.release_edge_first, options.release_edge_second);
  EdgeState edge_y = EdgeState::Zero();
  edge_y[0] = params.alpha_rad;
  edge_y[2 + 2 * kAlphaSlot] = 1.0;  // ∂ψ/∂α at the release
  VertexState vertex_y = VertexState::Zero();
  double t_start_s = 0.0;
  bool rests = false;
  const std::vector<ImpactRecord>& impacts = trajectory.impacts;

  for (std::size_t i = 0;; ++i) {
    const bool last = i >= impacts.size();
    const double t_stop_s = last ? trajectory.t_end_s : impacts[i].t_s;
    std::string error;
    if (about_edge) {
      ++summary.edge_phases;
      error = pass.Integrate<kEdgeStateSize>(EdgeEquations(block, contact, g), t_start_s, t_stop_s, last, &edge_y);
    } else {
      ++summary.vertex_phases;
      error = pass.Integrate<kVertexStateSize>(VertexEquations(block, contact.first, g), t_start_s, t_stop_s, last,
                                               &vertex_y);
    }
    if (!error.empty()) return NotAvailable(error);
    if (last) break;

    const ImpactRecord& impact = impacts[i];
    const double T = impact.t_s;
    if (impact.kind == ImpactKind::kRest) {
      rests = true;
      break;
    }
    const bool rest_follows = i + 1 < impacts.size() && impacts[i + 1].kind == ImpactKind::kRest;
    if (impact.kind == ImpactKind::kFacet && about_edge) {
      if (rest_follows || (!impact.contact_after.is_vertex() && !impact.contact_after.is_edge())) {
        rests = true;  // the block stays on its base from T on: ω = 0 and no derivative
        break;
      }
      if (!impact.contact_after.is_vertex()) {
        return NotAvailable(fmt::format("the facet impact at t = {} s leaves contact {}: the derivatives of an "
                                        "impact that keeps two vertices down are not given", T,
                                        impact.contact_after.ToString()));
      }
      // (18)+(21)+(24) at the landing ψ = 0: dT = −δψ/ψ̇⁻, and the attitude along the moved event is flat (its
      // change Dθ = (δψ + ψ̇⁻ dT) a vanishes).
      const EdgeEquations before(block, contact, g);
      const Eigen::Vector3d& axis_B = before.dynamics().axis_B();
      const double rate_minus = edge_y[1];
      if (!pass.Agrees(rate_minus * axis_B, impact.w_minus_B) || !(rate_minus != 0.0)) {
        return NotAvailable(fmt::format("the swing computed here does not land as logged at t = {} s", T));
      }
      const ImpactMapDerivatives map =
          FacetImpactDerivatives(block, contact.second, impact.contact_after.first, impact.w_minus_B, facet_params);
      if (!map.ok || !pass.Agrees(map.w_plus_B, impact.w_plus_B)) {
        return NotAvailable(fmt::format("the facet map for V{} does not give the logged rate at t = {} s",
                                        impact.contact_after.first, T));
      }
      const double acceleration_minus = before.Acceleration(edge_y[0]);
      const VertexEquations after(block, impact.contact_after.first, g);
      vertex_y.setZero();
      vertex_y.head<7>() = VertexDynamics::MakeState(Eigen::Quaterniond::Identity(), impact.w_plus_B);
      const Eigen::Vector3d acceleration_plus = after.Acceleration(vertex_y.head<7>());
      for (int p = 0; p < kNumPropagated; ++p) {
        const double dT = -edge_y[2 + 2 * p] / rate_minus;
        const Eigen::Vector3d D_w_minus = (edge_y[3 + 2 * p] + acceleration_minus * dT) * axis_B;
        const Eigen::Vector3d D_w_plus = map.dw_plus_dw_minus * D_w_minus + ParameterDerivative(map, p);
        vertex_y.segment<3>(ThetaAt(p)) = -impact.w_plus_B * dT;
        vertex_y.segment<3>(RateAt(p)) = D_w_plus - acceleration_plus * dT;
      }
      about_edge = false;
      contact = impact.contact_after;
    } else if (impact.kind == ImpactKind::kEdge && !about_edge) {
      if (rest_follows) {
        rests = true;
        break;
      }
      // Accumulating edge impacts switch to rocking about the edge at once (a Zeno record at the same instant):
      // the same transition as an edge impact that leaves edge contact, from the map's rotation about V_a.
      const bool zeno = i + 1 < impacts.size() && impacts[i + 1].kind == ImpactKind::kZeno;
      const int pivot = contact.first;
      const int landing = impact.contact_after.is_vertex() ? impact.contact_after.first
                                                           : OtherVertex(impact.contact_after, pivot);
      const VertexEquations before(block, pivot, g);
      const VertexDynamics::State s = vertex_y.head<7>();
      const Eigen::Vector3d up_B = VertexDynamics::UpInBody(s);
      const Eigen::Vector3d w_minus_B = impact.w_minus_B;
      if (!pass.Agrees(VertexEquations::Rate(vertex_y), w_minus_B)) {
        return NotAvailable(fmt::format("the phase computed here does not reach the logged impact at t = {} s", T));
      }
      // The guard: the height of V_landing above the ground, h = u·r; ∂h/∂δθ = r × u, ḣ = u·(w × r).
      const Eigen::Vector3d r_B = block.p_BV_B(landing) - block.p_BV_B(pivot);
      const Eigen::Vector3d height_gradient = r_B.cross(up_B);
      const double height_rate = up_B.dot(w_minus_B.cross(r_B));
      if (!(height_rate < 0.0)) {
        return NotAvailable(fmt::format("V{} does not fall onto the ground at t = {} s", landing, T));
      }
      const ImpactMapDerivatives map = EdgeImpactDerivatives(block, up_B, pivot, landing, w_minus_B, edge_params);
      if (!map.ok) return NotAvailable(fmt::format("the edge map at t = {} s is singular", T));
      const Eigen::Vector3d acceleration_minus = before.Acceleration(s);
      std::array<double, kNumPropagated> dT{};
      std::array<Eigen::Vector3d, kNumPropagated> D_theta, D_w_plus;
      for (int p = 0; p < kNumPropagated; ++p) {
        const Eigen::Vector3d d_theta = vertex_y.segment<3>(ThetaAt(p));
        dT[p] = -height_gradient.dot(d_theta) / height_rate;
        D_theta[p] = d_theta + w_minus_B * dT[p];
        const Eigen::Vector3d D_w_minus = vertex_y.segment<3>(RateAt(p)) + acceleration_minus * dT[p];
        D_w_plus[p] = map.dw_plus_dw_minus * D_w_minus + map.dw_plus_dtheta * D_theta[p] + ParameterDerivative(map, p);
      }
      if (impact.contact_after.is_vertex() && !zeno) {
        if (!pass.Agrees(map.w_plus_B, impact.w_plus_B)) {
          return NotAvailable(fmt::format("the edge map does not give the logged rate at t = {} s", T));
        }
        const VertexEquations after(block, landing, g);
        VertexState next = VertexState::Zero();
        next.head<4>() = vertex_y.head<4>();
        next.segment<3>(4) = impact.w_plus_B;
        const Eigen::Vector3d acceleration_plus = after.Acceleration(next.head<7>());
        for (int p = 0; p < kNumPropagated; ++p) {
          next.segment<3>(ThetaAt(p)) = D_theta[p] - impact.w_plus_B * dT[p];
          next.segment<3>(RateAt(p)) = D_w_plus[p] - acceleration_plus * dT[p];
        }
        vertex_y = next;
        contact = impact.contact_after;
      } else {
        // Edge contact: ψ̇ = a·(J_a ω⁺)/J_e, linear in ω⁺; ψ from the attitude; δψ = a·Dθ (Dθ keeps the edge on
        // the ground, so it is a turn about a plus a yaw).
        const ImpactRecord& to_edge = zeno ? impacts[i + 1] : impact;
        if (zeno && !pass.Agrees(map.w_plus_B, impact.w_plus_B)) {
          return NotAvailable(fmt::format("the edge map does not give the logged rate at t = {} s", T));
        }
        const EdgeEquations after(block, to_edge.contact_after, g);
        const EdgeDynamics& edge = after.dynamics();
        const Eigen::Vector3d p_a = block.p_BV_B(landing);
        Eigen::Vector3d projection;
        for (int j = 0; j < 3; ++j) projection[j] = edge.ProjectAngularVelocity(Eigen::Vector3d::Unit(j), p_a);
        const double rate_plus = projection.dot(map.w_plus_B);
        if (!pass.Agrees(rate_plus * edge.axis_B(), to_edge.w_plus_B)) {
          return NotAvailable(fmt::format("the rate about the edge after t = {} s is not the logged one", T));
        }
        Eigen::Quaterniond q_yaw;
        double psi = 0.0;
        edge.Decompose(VertexDynamics::Attitude(s), &q_yaw, &psi);
        EdgeState next = EdgeState::Zero();
        next[0] = std::max(psi, 0.0);
        next[1] = edge.axis_B().dot(to_edge.w_plus_B);
        const double acceleration_plus = after.Acceleration(next[0]);
        for (int p = 0; p < kNumPropagated; ++p) {
          next[2 + 2 * p] = edge.axis_B().dot(D_theta[p]) - next[1] * dT[p];
          next[3 + 2 * p] = projection.dot(D_w_plus[p]) - acceleration_plus * dT[p];
        }
        edge_y = next;
        about_edge = true;
        contact = to_edge.contact_after;
        if (zeno) ++i;  // the Zeno record is this transition
      }
    } else {
      return NotAvailable(fmt::format("a {} impact at t = {} s after rocking about {}: no derivatives through it",
                                      ToString(impact.kind), T, contact.ToString()));
    }
    t_start_s = T;
  }
  if (rests) {
    if (std::string error = pass.AtRest(); !error.empty()) return NotAvailable(error);
  }
  summary.available = true;
  return summary;
}

}  // namespace rockfit::core
