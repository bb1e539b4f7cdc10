// The continuous modes of the hybrid simulator with their event guards (docs/design.md §4). Internal to the
// simulator; exposed for its tests.
//
// Every guard is a scalar that is positive while the mode is valid and crosses zero downwards at its event:
//   Vertex(k): heights of V_{k+1} and V_{k−1} (touch-down: edge impact on V_kV_{k±1}), and the signed
//              horizontal distances of the COM from the vertical planes through V_k along the two base edges
//              at V_k (the COM leaves the base's footprint at the pivot: overturning).
//   Edge(i,j): the tilt ψ (the base lands flat: facet impact) and the distance of the COM from the vertical
//              plane of the edge (overturning).
// The opposite vertex V_{k+2} needs no guard: its height is the sum of those of V_{k±1}.
#pragma once

#include <array>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/attitude.hpp"
#include "rockfit/core/block.hpp"
#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/event_location.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/core/vertex_dynamics.hpp"

namespace rockfit::core::detail {

// Largest turn of the body in one integrator step of vertex rocking [rad]: far below the π between two extrema
// of a vertex height under a steady rotation, so that the event test's one-extremum assumption holds.
constexpr double kMaxTurnPerStep_rad = 0.5;

class VertexMode {
 public:
  static constexpr int kStateSize = VertexDynamics::kStateSize;
  static constexpr int kNumGuards = 4;
  // The sample's Euler angles come from its quaternion (the sampler's EulerZyxSequence), not from the state.
  static constexpr bool kEulerFromQuaternion = true;
  // A vertex height can fall below zero and rise again within one step: steps stay below max_step_s.
  static constexpr bool kGuardsNeedStepBound = true;
  // AngularVelocity_B(y) is the state's components [4, 7): a sample without attitude interpolates only those.
  static constexpr int kAngularVelocityFirst = 4;
  static_assert(kAngularVelocityFirst + 3 == kStateSize, "ω is the state's tail (VertexDynamics::AngularVelocity)");
  using State = VertexDynamics::State;
  enum GuardIndex { kTouchNext = 0, kTouchPrevious = 1, kOverNext = 2, kOverPrevious = 3 };

  VertexMode(const Block& block, int vertex, double gravity_m_s2);

  void operator()(double t, const State& y, State& dydt) const { dynamics_(t, y, dydt); }
  GuardValue Guard(int index, const State& y) const;
  // The interface of the segment runner (time-dependent guards, forces and step limits exist only under
  // ground motion, detail/ground_modes.hpp): here t is ignored and steps are limited by t_limit alone.
  GuardValue Guard(int index, double /*t*/, const State& y) const { return Guard(index, y); }
  // Every guard at once, as Guard gives each (the attitude's vertical and its rate computed once).
  std::array<GuardValue, kNumGuards> Guards(double t, const State& y) const;
  double StepLimit(double /*t*/, double t_limit) const { return t_limit; }
  // The longest step from state y: a turn of the body by at most kMaxTurnPerStep_rad, so that a vertex height
  // (A cos(turn) + C under a steady rotation) has at most one extremum per step.
  static double StepBound(const State& y);
  static bool IsTouchdown(int guard) { return guard == kTouchNext || guard == kTouchPrevious; }
  // The vertex that lands when `guard` fires (a neighbour of the pivot).
  int GuardVertex(int guard) const;

  Eigen::Quaterniond Attitude(const State& y) const { return VertexDynamics::Attitude(y); }
  // The attitude of an output sample (VertexDynamics::SampleAttitude: Attitude(y) to round-off, cheaper).
  Eigen::Quaterniond SampleAttitude(const State& y) const { return VertexDynamics::SampleAttitude(y); }
  // Euler angles (φz, φy, φx) of the sample attitude q_WB (canonical, from Attitude(y)).
  Eigen::Vector3d EulerZyx(const Eigen::Quaterniond& q_WB, const State& /*y*/) const {
    return EulerZyxFromUnitQuaternion(q_WB);
  }
  Eigen::Vector3d AngularVelocity_B(const State& y) const { return VertexDynamics::AngularVelocity(y); }
  double Energy(const State& y) const { return dynamics_.Energy(y); }
  double KineticEnergy(const State& y) const { return dynamics_.KineticEnergy(y); }
  ContactForce Force(const State& y, const State& dydt) const { return dynamics_.Force(y, dydt); }
  ContactForce Force(double /*t*/, const State& y, const State& dydt) const { return dynamics_.Force(y, dydt); }
  // The interface of the segment runner: Force's normal and tangential parts (F_W left zero), what its diagnostics read.
  ContactForce Load(double /*t*/, const State& y, const State& dydt) const { return dynamics_.Load(y, dydt); }
  // Renormalises the quaternion between steps.
  static void Project(State* y);
  Mode mode() const;
  int vertex() const { return vertex_; }
  const VertexDynamics& dynamics() const { return dynamics_; }

 private:
  int vertex_;
  VertexDynamics dynamics_;
  std::array<int, 2> neighbours_;            // V_{k+1}, V_{k−1}
  std::array<Eigen::Vector3d, 2> p_KN_B_;    // from the pivot to each neighbour
  std::array<Eigen::Vector3d, 2> edge_x_c_;  // σ·(p_KN × p_KC): overturn guard = up_B · this
};

class EdgeMode {
 public:
  static constexpr int kStateSize = EdgeDynamics::kStateSize;
  static constexpr int kNumGuards = 2;
  static constexpr bool kEulerFromQuaternion = false;  // EulerZyx reads them off the yaw and the tilt
  // Neither guard can cross zero and come back: below θ_c the tilt is concave in time (ψ̈ = −(mgR/J_e)
  // sin(θ_c − ψ) < 0, also for ψ < 0), so once it falls through zero it keeps falling, and beyond θ_c it is convex,
  // so once the COM passes over the edge it keeps going. A guard positive at both ends of a step is positive
  // inside it, whatever the step length, and steps need no bound (docs/design.md §4).
  static constexpr bool kGuardsNeedStepBound = false;
  using State = EdgeDynamics::State;
  enum GuardIndex { kFlat = 0, kOver = 1 };

  // Rotation about the base edge V_iV_j (neighbours) with the given yaw of the flat attitude.
  EdgeMode(const Block& block, int i, int j, const Eigen::Quaterniond& q_yaw, double gravity_m_s2);
  // The same rotation with another yaw of the flat attitude (the edge's dynamics do not depend on it, so a mode
  // built once serves every segment about its edge).
  void SetYaw(const Eigen::Quaterniond& q_yaw);

  void operator()(double t, const State& y, State& dydt) const { dynamics_(t, y, dydt); }
  GuardValue Guard(int index, const State& y) const;
  GuardValue Guard(int index, double /*t*/, const State& y) const { return Guard(index, y); }
  double StepLimit(double /*t*/, double t_limit) const { return t_limit; }
  static double StepBound(const State& /*y*/) { return std::numeric_limits<double>::infinity(); }
  static bool IsTouchdown(int guard) { return guard == kFlat; }

  Eigen::Quaterniond Attitude(const State& y) const { return q_yaw_ * dynamics_.Tilt(y[0]); }
  // Euler angles (φz, φy, φx) of the sample attitude: R_WB = Rz(yaw)·Rot(±e_y or ±e_x, ψ) is already in ZYX
  // form, (yaw, ±ψ, 0) or (yaw, 0, ±ψ), so no conversion is needed (a tenth of a planar run's time); the
  // general conversion of q_WB where the yaw or the edge axis is not of that form.
  Eigen::Vector3d EulerZyx(const Eigen::Quaterniond& q_WB, const State& y) const;
  Eigen::Vector3d AngularVelocity_B(const State& y) const { return dynamics_.AngularVelocity_B(y); }
  double Energy(const State& y) const { return dynamics_.Energy(y); }
  double KineticEnergy(const State& y) const { return dynamics_.KineticEnergy(y); }
  ContactForce Force(const State& y, const State& dydt) const { return dynamics_.Force(y, dydt, q_yaw_); }
  ContactForce Force(double /*t*/, const State& y, const State& dydt) const { return Force(y, dydt); }
  ContactForce Load(double t, const State& y, const State& dydt) const { return Force(t, y, dydt); }
  static void Project(State* /*y*/) {}
  Mode mode() const;
  int first() const { return first_; }
  int second() const { return second_; }
  const Eigen::Quaterniond& q_yaw() const { return q_yaw_; }
  const EdgeDynamics& dynamics() const { return dynamics_; }

 private:
  int first_;
  int second_;
  Eigen::Quaterniond q_yaw_;
  EdgeDynamics dynamics_;
  double yaw_rad_ = 0.0;  // the angle of q_yaw_ in (−π, π]
  int tilt_euler_index_ = -1;  // 1: the edge axis is ±e_y (ψ is ±φy), 2: ±e_x (±φx); −1: neither
  double tilt_euler_sign_ = 1.0;
};

}  // namespace rockfit::core::detail
