// The Edge and Vertex modes under prescribed ground motion (core/README.md, "Ground motion"). Internal to the
// simulator; exposed for its tests.
//
// The equations are those of the free modes written in the ground frame, whose only extra force is the
// inertial force −m a_g(t) at the COM: with the effective field f_W(t) = −g e_z − a_g(t),
//   Vertex(k): J_P ẇ_B + w_B × J_P w_B = p_PC_B × m R_WBᵀ f_W(t),
//   Edge(i,j): J_e ψ̈ = m [f_z (d cos ψ − h sin ψ) − f_n (d sin ψ + h cos ψ)],  f_n = f_W·n_W, f_z = f_W·e_z,
// (n_W the horizontal unit vector from the edge towards the base centre). With a_g = 0 they are the free
// equations. The guards are the free modes' geometric guards; Edge mode adds one per end vertex V_i of the
// edge, which turns negative when V_i leaves the ground and the block rocks on about V_j. V_i leaves only when
// both contact modes agree: the edge's normal force on V_i (EndForces(), both ends pinned, no slip) is no
// longer positive, and the vertex motion about V_j alone lifts V_i (its vertical acceleration, minus, over g).
// The guard is the larger of the two, each made dimensionless (N_i/(m g), −a_i/g). Usually the force vanishes
// first: with both ends pinned V_i also carries a horizontal force that a vertex pivot cannot, so between the
// two instants neither mode is consistent under no slip, and the edge is kept until the vertex motion lifts
// V_i. On a slender block with a short edge the order can turn round: the horizontal inertial force yaws the
// block about a lone vertex (its yaw inertia is tiny), the vertex motion "lifts" V_i while the edge still
// loads it with about half the weight, and the vertex motion lands it again at once. Requiring both keeps the
// edge there. See core/README.md, "Ground motion".
// Integrator steps end at the record's sample times.
#pragma once

#include <algorithm>
#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "detail/contact_modes.hpp"
#include "rockfit/core/ground_motion.hpp"

namespace rockfit::core::detail {

// Longest step under table motion [s]: the table's acceleration can turn a tilt or a height around within a step
// whatever the body's rate, so steps stay as short as in free rocking before the turn bound (10 ms).
constexpr double kGroundStepBound_s = 1e-2;

class GroundVertexMode {
 public:
  static constexpr int kStateSize = VertexMode::kStateSize;
  static constexpr int kNumGuards = VertexMode::kNumGuards;
  static constexpr bool kEulerFromQuaternion = VertexMode::kEulerFromQuaternion;
  static constexpr bool kGuardsNeedStepBound = true;
  static constexpr int kAngularVelocityFirst = VertexMode::kAngularVelocityFirst;
  using State = VertexMode::State;

  // falls_on_side: OverturnRule::kFallsOnSide (the over guards become SideLanding).
  GroundVertexMode(const Block& block, int vertex, double gravity_m_s2, const GroundMotion& ground,
                   bool falls_on_side = false);

  void operator()(double t, const State& y, State& dydt) const;
  GuardValue Guard(int index, double /*t*/, const State& y) const {
    if (falls_on_side_ && index >= VertexMode::kOverNext) return SideLanding(index, y);
    return free_.Guard(index, y);
  }
  // Every guard at once, as Guard gives each.
  std::array<GuardValue, kNumGuards> Guards(double t, const State& y) const {
    std::array<GuardValue, kNumGuards> g = free_.Guards(t, y);
    if (falls_on_side_) {
      for (int index = VertexMode::kOverNext; index < kNumGuards; ++index) g[index] = SideLanding(index, y);
    }
    return g;
  }
  // Under OverturnRule::kFallsOnSide, the block lies on a side when its z axis is horizontal: the first point
  // beyond the base to reach the ground is then the top vertex above the pivot, 2h·(up_B · e_z) above it (the
  // other top vertices are higher by the heights of their base vertices, which the touch-down guards keep
  // positive). kOverNext carries that height over 2h; kOverPrevious is held positive.
  GuardValue SideLanding(int index, const State& y) const;
  double StepLimit(double t, double t_limit) const { return std::min(t_limit, ground_->NextBreak(t)); }
  static double StepBound(const State& y) { return std::min(kGroundStepBound_s, VertexMode::StepBound(y)); }
  static bool IsTouchdown(int guard) { return VertexMode::IsTouchdown(guard); }
  int GuardVertex(int guard) const { return free_.GuardVertex(guard); }
  Eigen::Quaterniond Attitude(const State& y) const { return free_.Attitude(y); }
  Eigen::Quaterniond SampleAttitude(const State& y) const { return free_.SampleAttitude(y); }
  Eigen::Vector3d EulerZyx(const Eigen::Quaterniond& q_WB, const State& y) const { return free_.EulerZyx(q_WB, y); }
  Eigen::Vector3d AngularVelocity_B(const State& y) const { return free_.AngularVelocity_B(y); }
  double Energy(const State& y) const { return free_.Energy(y); }
  double KineticEnergy(const State& y) const { return free_.KineticEnergy(y); }
  // The ground's force on the block: F = m (a_C − f_W).
  ContactForce Force(double t, const State& y, const State& dydt) const;
  // Force's normal and tangential parts alone, bit for bit (F_W left zero): what the segment diagnostics read.
  ContactForce Load(double t, const State& y, const State& dydt) const;
  static void Project(State* y) { VertexMode::Project(y); }
  Mode mode() const { return free_.mode(); }
  int vertex() const { return free_.vertex(); }
  const VertexMode& free_mode() const { return free_; }

 private:
  Eigen::Vector3d Force_B(double t, const State& y, const State& dydt) const;  // F of Force, in B

  VertexMode free_;
  const GroundMotion* ground_;
  bool falls_on_side_;
  double mass_kg_;
  double gravity_m_s2_;
  Eigen::Vector3d p_PC_B_;
  Eigen::Matrix3d inertia_P_B_;
  Eigen::Matrix3d inertia_P_B_inverse_;
};

class GroundEdgeMode {
 public:
  // Time step of the central difference for the rate of the end-load guards [s]: far below the record step
  // and the rocking time scale (≥ 1 ms), far above round-off of t.
  static constexpr double kLoadRateStep_s = 1e-6;
  static constexpr int kStateSize = EdgeMode::kStateSize;
  static constexpr int kNumGuards = EdgeMode::kNumGuards + 2;
  static constexpr bool kEulerFromQuaternion = EdgeMode::kEulerFromQuaternion;
  // The table's acceleration makes the tilt's curvature change sign: steps stay bounded.
  static constexpr bool kGuardsNeedStepBound = true;
  using State = EdgeMode::State;
  enum GuardIndex { kFlat = EdgeMode::kFlat, kOver = EdgeMode::kOver, kLoadFirst = 2, kLoadSecond = 3 };

  // falls_on_side: OverturnRule::kFallsOnSide (the over guard becomes cos ψ: the block lies on a side at ψ = π/2).
  // lift_margin_g: the end-load guards are raised by this much [g], so that an end lifts only when both the
  // vertex motion's lift and the edge's pull exceed it (the simulator sets it after an end came straight back).
  GroundEdgeMode(const Block& block, int i, int j, const Eigen::Quaterniond& q_yaw, double gravity_m_s2,
                 const GroundMotion& ground, bool falls_on_side = false, double lift_margin_g = 0.0);
  // The same mode with another yaw of the flat attitude and lift margin (a mode built once serves every segment
  // about its edge).
  void SetYawAndLiftMargin(const Eigen::Quaterniond& q_yaw, double lift_margin_g);

  void operator()(double t, const State& y, State& dydt) const;
  // kLoadFirst/kLoadSecond: EndHold of V_i / V_j (positive while the edge holds it), with its rate by a
  // central difference over kLoadRateStep_s along the motion (no closed form).
  GuardValue Guard(int index, double t, const State& y) const;
  // Every guard at once, as Guard gives each (the two end loads share their forces at each of the three times).
  std::array<GuardValue, kNumGuards> Guards(double t, const State& y) const;
  double StepLimit(double t, double t_limit) const { return std::min(t_limit, ground_->NextBreak(t)); }
  static double StepBound(const State& /*y*/) { return kGroundStepBound_s; }
  static bool IsTouchdown(int guard) { return guard == kFlat; }
  Eigen::Quaterniond Attitude(const State& y) const { return free_.Attitude(y); }
  Eigen::Vector3d EulerZyx(const Eigen::Quaterniond& q_WB, const State& y) const { return free_.EulerZyx(q_WB, y); }
  Eigen::Vector3d AngularVelocity_B(const State& y) const { return free_.AngularVelocity_B(y); }
  double Energy(const State& y) const { return free_.Energy(y); }
  double KineticEnergy(const State& y) const { return free_.KineticEnergy(y); }
  ContactForce Force(double t, const State& y, const State& dydt) const;
  ContactForce Load(double t, const State& y, const State& dydt) const { return Force(t, y, dydt); }
  // Normal forces on the two end vertices V_i, V_j [N] with both pinned (their sum is Force(...).normal_N).
  std::array<double, 2> EndForces(double t, const State& y) const;
  // Vertical acceleration [m/s²] of end vertex `end` (0: V_i, 1: V_j) in Vertex mode about the other end.
  double LiftAcceleration(int end, double t, const State& y) const;
  // The end-load guard's value: max(N_end/(m g), −LiftAcceleration/g) + lift_margin_g (see the header).
  double EndHold(int end, double t, const State& y) const;
  static void Project(State* /*y*/) {}
  Mode mode() const { return free_.mode(); }
  int first() const { return free_.first(); }
  int second() const { return free_.second(); }
  const EdgeMode& free_mode() const { return free_; }

 private:
  Eigen::Vector3d Field_B(double t, double psi) const;  // R_WBᵀ f_W(t)
  // EndHold of `end` given EndForces(t, y).
  double EndHoldWith(int end, double t, const State& y, const std::array<double, 2>& end_forces_N) const;
  // EndHold of both ends.
  std::array<double, 2> EndHolds(double t, const State& y) const;

  EdgeMode free_;
  const GroundMotion* ground_;
  double lift_margin_g_ = 0.0;
  bool falls_on_side_;
  double mass_kg_;
  double gravity_m_s2_;
  double d_m_;
  double h_m_;
  double torque_scale_;  // m / J_e
  double half_length_m_;
  Eigen::Vector3d inward_W_;
  Eigen::Vector3d p_PC_B_;
  Eigen::Vector3d edge_dir_B_;  // unit, from V_i to V_j
  Eigen::Matrix3d inertia_P_B_;
  GroundVertexMode about_first_;   // rocking about V_i
  GroundVertexMode about_second_;  // rocking about V_j
  Eigen::Vector3d first_to_second_B_;
};

}  // namespace rockfit::core::detail
