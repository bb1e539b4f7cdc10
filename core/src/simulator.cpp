// The hybrid simulator of free 3D rocking (docs/design.md §4, paper Sect. 4.1 and Fig. 7): continuous segments in
// the Edge and Vertex modes (detail/contact_modes.hpp, detail/hybrid_segment.hpp) joined by the impact maps
// of impact_maps.hpp, with Zeno handling, rest and overturning, and the stop conditions of Sect. 5.1.
#include "rockfit/core/simulator.hpp"

#include <array>
#include <chrono>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

#include "detail/analytic_edge_segment.hpp"
#include "detail/contact_modes.hpp"
#include "detail/ground_modes.hpp"
#include "detail/hybrid_segment.hpp"
#include "detail/lazy_slot.hpp"
#include "detail/mode_cache.hpp"
#include "detail/trajectory_sampler.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/ground_uplift.hpp"
#include "rockfit/core/rolled_release.hpp"

namespace rockfit::core {
namespace {

using detail::EdgeMode;
using detail::GroundEdgeMode;
using detail::GroundVertexMode;
using detail::RunSegment;
using detail::SegmentOutcome;
using detail::SegmentEnd;
using detail::SegmentSettings;
using detail::VertexMode;

// Impacts closer in time than this many event tolerances happen at one instant.
constexpr double kSameInstantFactor = 10.0;
// More impacts than this at one instant: the contact sequence does not resolve (the run fails).
constexpr int kMaxImpactsAtOneInstant = 16;
// Edge impacts on one edge closer than this many event tolerances switch to edge rocking even when their
// intervals are not (yet) shrinking: the event locator cannot separate them any further.
constexpr double kZenoFloorFactor = 100.0;
// Kinetic energy after an impact above this multiple of m·g·|p_VC| (the work to lift the COM by its whole
// distance from a base vertex) means impacts keep adding energy (e.g. λ < 0): the motion blows up.
constexpr double kBlowUpEnergyFactor = 1e3;
// A given initial state may have its base vertices below the ground by at most this [m].
constexpr double kInitialPenetrationTol_m = 1e-9;
// A given edge-contact attitude may differ from one with that edge on the ground by at most this angle [rad]
// (1e-9 rad lifts a vertex 1 m away by 1 nm, the same order as kInitialPenetrationTol_m).
constexpr double kInitialEdgeAttitudeTol_rad = 1e-9;
// A given edge-contact state may have an angular velocity off the edge axis of at most this [rad/s].
constexpr double kInitialOffAxisTol_rad_s = 1e-9;
// Under ground motion, an edge whose tilt is below this [rad] when one of its end vertices unloads counts as
// flat: all base vertices start their guards on the ground.
constexpr double kFlatTiltTol_rad = 1e-12;
// An end-vertex lift guard (an acceleration in units of g) below this in magnitude at the start of an Edge
// segment is zero.
constexpr double kLoadZeroTol = 1e-9;
// Under ground motion, an end vertex that left the edge and landed again at the same instant (the edge mode saw it
// unload, the vertex mode brought it straight down: both accelerations at round-off of zero) may lift again only
// when the lift and the pull both exceed this [g]; without it the two modes hand the vertex back and forth at
// one instant until the run fails.
constexpr double kReliftMargin_g = 1e-3;
// Under ground motion, a chatter of this many impacts within kMicroChatterSpan_s [s], with the block flat to within
// kMicroChatterTilt_rad and turning slower than kMicroChatterRate_rad_s, is motion below the resolution of the
// integration (hops of ~1e-10 s at 1e-9–1e-11 rad/s, where the table drives the block right at its threshold):
// its velocity is dropped and the contact decides (below kMaxImpactsAtOneInstant, which would fail the run).
constexpr int kMicroChatterImpacts = 12;
constexpr double kMicroChatterSpan_s = 1e-6;
constexpr double kMicroChatterTilt_rad = 1e-9;
constexpr double kMicroChatterRate_rad_s = 1e-6;
// Under ground motion, a facet impact that leaves |ω⁺| at or below this [rad/s] leaves the block without relative
// velocity: a numerical floor (a rocking amplitude of ~1e-19 rad at the table's accelerations), not a physical
// threshold (docs/design.md §11a).
constexpr double kRestRateFloor_rad_s = 1e-9;
// (27): the facet impact's resultant lies on the base for |λ_lat| ≤ this (and |λ_lon| ≤ this).
constexpr double kLateralBound = 1.0;

// The free mode of a segment's mode (the impact transitions work on the geometry alone).
const VertexMode& FreeMode(const VertexMode& mode) { return mode; }
const EdgeMode& FreeMode(const EdgeMode& mode) { return mode; }
const VertexMode& FreeMode(const GroundVertexMode& mode) { return mode.free_mode(); }
const EdgeMode& FreeMode(const GroundEdgeMode& mode) { return mode.free_mode(); }

std::string FormatTime(double t_s) {
  std::ostringstream out;
  out.precision(12);
  out << t_s << " s";
  return out.str();
}

// The state a run ends in, for the samples at its end time.
struct EndState {
  Mode mode;
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();
};

struct VertexStart {
  int vertex = 1;
  VertexDynamics::State y = VertexDynamics::State::Zero();
  std::array<bool, VertexMode::kNumGuards> on_surface{};
};

struct EdgeStart {
  Contact edge;
  Eigen::Quaterniond q_yaw = Eigen::Quaterniond::Identity();
  EdgeDynamics::State y = EdgeDynamics::State::Zero();
  double lift_margin_g = 0.0;  // GroundEdgeMode's lift margin for this segment
};

// The last few impact times of one kind, to recognise geometrically shrinking intervals.
class ImpactSequence {
 public:
  void Clear() { count_ = 0; }
  // Adds an impact on `contact`; a different contact starts a new sequence.
  void Add(double t_s, const Contact& contact) {
    if (count_ > 0 && contact != contact_) count_ = 0;
    contact_ = contact;
    for (std::size_t k = times_.size() - 1; k > 0; --k) times_[k] = times_[k - 1];
    times_[0] = t_s;
    ++count_;
  }
  // The last interval is shorter than `dt` and shorter than the one before.
  bool Shrinking(double dt) const {
    if (count_ < 3) return false;
    const double last = Interval(0);
    return last < dt && last < Interval(1);
  }
  bool LastIntervalBelow(double dt) const { return count_ >= 2 && Interval(0) < dt; }
  // Under ground motion a chattering block lands alternately from two edges (or vertices), and the table
  // pushes one side down harder than the other, so consecutive intervals alternate between short and long:
  // a shrinking pair of intervals says nothing. The sequence accumulates when both interleaved subsequences
  // shrink and the last three cycles (two impacts each) shrink by consistent ratios, as a geometric series
  // does (a sudden pair of quick impacts after slow ones is a change of motion, not an accumulation). With q
  // the ratio of the last cycle to the one before, the impacts still to come take (I0 + I1)·q/(1 − q).
  // Returns that time when it is below `dt`.
  std::optional<double> Accumulation(double dt) const {
    if (count_ < static_cast<int>(times_.size())) return std::nullopt;
    if (!(Interval(0) < Interval(2) && Interval(1) < Interval(3))) return std::nullopt;
    const double cycle = Interval(0) + Interval(1);
    const double q = cycle / (Interval(2) + Interval(3));
    const double q_before = (Interval(2) + Interval(3)) / (Interval(4) + Interval(5));
    if (!(q < 1.0 && q_before < 1.0)) return std::nullopt;  // also NaN from impacts at one instant
    if (!(q < kCycleRatioSpread * q_before && q_before < kCycleRatioSpread * q)) return std::nullopt;
    const double remaining = cycle * q / (1.0 - q);
    if (!(remaining < dt)) return std::nullopt;
    return remaining;
  }

 private:
  // Two consecutive cycle ratios of an accumulation differ by less than this factor (a ratio is the square of
  // the restitution of the two landings, which the table changes little within a cycle).
  static constexpr double kCycleRatioSpread = 2.0;
  double Interval(std::size_t k) const { return times_[k] - times_[k + 1]; }
  std::array<double, 7> times_{};
  Contact contact_;
  int count_ = 0;
};

// The times of the last kMicroChatterImpacts impacts of any kind.
class RecentTimes {
 public:
  void Add(double t_s) {
    times_[next_] = t_s;
    next_ = (next_ + 1) % times_.size();
    count_ = std::min(count_ + 1, times_.size());
  }
  // All of them lie within span_s.
  bool Within(double span_s) const {
    if (count_ < times_.size()) return false;
    const std::size_t newest = (next_ + times_.size() - 1) % times_.size();
    return times_[newest] - times_[next_] < span_s;  // next_ holds the oldest once the ring is full
  }

 private:
  std::array<double, kMicroChatterImpacts> times_{};
  std::size_t next_ = 0;
  std::size_t count_ = 0;
};

// The flat attitude with the heading of q_WB: the yaw about the vertical of its body x axis.
Eigen::Quaterniond FlatWithHeadingOf(const Eigen::Quaterniond& q_WB) {
  const Eigen::Matrix3d R_WB = q_WB.toRotationMatrix();
  return Eigen::Quaterniond(Eigen::AngleAxisd(std::atan2(R_WB(1, 0), R_WB(0, 0)), Eigen::Vector3d::UnitZ()));
}

// Kinetic energy of the flat block (attitude q_flat) right after an impact that leaves it on `contact` with
// body rate w_B: about the vertex, about the edge (the rate about it), or zero when the base stays down.
double KineticEnergyAfterLanding(detail::ModeCache& modes, const Contact& contact, const Eigen::Quaterniond& q_flat,
                                 const Eigen::Vector3d& w_B) {
  if (contact.is_vertex()) {
    return modes.VertexDynamicsOf(contact.first).KineticEnergy(VertexDynamics::MakeState(q_flat, w_B));
  }
  if (contact.is_edge()) {
    const EdgeDynamics& about_edge = modes.EdgeDynamicsOf(contact.first, contact.second);
    const double rate = about_edge.ProjectAngularVelocity(w_B, about_edge.p_BP_B());
    return about_edge.KineticEnergy(EdgeDynamics::State(0.0, rate));
  }
  return 0.0;
}

class HybridRun {
 public:
  // `ground` null: free rocking. Otherwise the run is in the frame of the moving table; `start_flat` starts it
  // flat at rest.
  HybridRun(const Block& block, const ModelParameters& params, const SimulationOptions& options, Trajectory* out,
            const GroundMotion* ground = nullptr, bool start_flat = false)
      : block_(block),
        params_(params),
        options_(options),
        gravity_(options.gravity_m_s2),
        out_(out),
        sampler_(options, options.t_max_s, out),
        modes_(block, options.gravity_m_s2, ground, options.overturn == OverturnRule::kFallsOnSide),
        ground_(ground),
        start_flat_(start_flat) {
    settings_.integrator.rel_tol = options.rel_tol;
    settings_.integrator.abs_tol = options.abs_tol;
    settings_.integrator.max_step = options.max_step_s;
    settings_.event_time_tol_s = options.event_time_tol_s;
    settings_.t_limit_s = options.t_max_s;
    release_ = {Block::WrapVertex(options.release_edge_first), Block::WrapVertex(options.release_edge_second)};
    if (ground_ != nullptr) {
      t_lift_off_ = LiftOffTime(*ground_, gravity_, 0.0, options.t_max_s);
      settings_.t_limit_s = std::min(options.t_max_s, t_lift_off_);
    }
  }

  void Run();

 private:
  enum class Next { kVertex, kEdge, kStopped };

  Next RunVertex();
  Next RunEdge();
  template <class ModeT>
  Next RunVertexIn(const ModeT& mode);
  template <class ModeT>
  Next RunEdgeIn(const ModeT& mode);
  // The transition at the end of an Edge segment of `mode` (integrated or in closed form).
  template <class ModeT>
  Next AfterEdgeSegment(const ModeT& mode, const SegmentOutcome<ModeT>& outcome);
  // Under ground motion: the end vertex `lifting` of the edge of `mode` unloads; rocking continues about the
  // other end vertex with the same ω.
  Next EdgeToVertex(const EdgeMode& mode, double t, const EdgeDynamics::State& y, int lifting);
  // Under ground motion: the flat block at rest from t on, until the next uplift (or the end of the run).
  Next RestOnTable(double t, const Eigen::Quaterniond& q_flat);
  // Under ground motion: the flat block starts to rock at `uplift` from zero relative velocity.
  Next StartRocking(const Uplift& uplift, const Eigen::Quaterniond& q_flat);
  // Under ground motion, after the facet impact `trigger` that left the block flat with w⁺ = trigger.w_plus_B:
  // rest, rocking on with w⁺, or rocking from zero relative velocity about the contact the table selects.
  Next AfterFacetImpactOnTable(double t, const Eigen::Quaterniond& q_flat, const ImpactRecord& trigger);
  // Under ground motion, the block flat (attitude q_flat) at t after the impact `trigger`, its remaining velocity
  // to be dropped: rest if the table keeps it down up to horizon_s ahead, rocking from zero relative velocity if
  // the table tips it at once; empty if the table tips it later within the horizon (the impacts go on).
  std::optional<Next> SettleOnTable(double t, const Eigen::Quaterniond& q_flat, const ImpactRecord& trigger,
                                    double horizon_s);
  // Under ground motion: the last kMicroChatterImpacts impacts came within kMicroChatterSpan_s with the block
  // flat and still to within kMicroChatterTilt_rad and kMicroChatterRate_rad_s (attitude q_WB, rate w_B after
  // the last): a motion below the resolution of the integration, whose velocity is zero for all purposes.
  bool MicroChatter(const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& w_B) const;
  bool lift_off_before_t_max() const { return t_lift_off_ <= options_.t_max_s; }
  Next AfterEdgeImpact(const VertexMode& mode, double t, const VertexDynamics::State& y, int landing);
  Next AfterFacetImpact(const EdgeMode& mode, double t, const EdgeDynamics::State& y);
  // Continues in `contact` (from an impact map) with attitude q_WB and w_B, a rotation about vertex `pivot`
  // (V_a of the map; for edge contact ω is projected onto the edge as a rotation about it). Vertices that were
  // on the ground before the impact (−1: all) start their guards at zero.
  Next Continue(const Contact& contact, double t, const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& w_B,
                int pivot, int vertex_off_ground_first, int vertex_off_ground_second);
  Next Rest(double t, const Eigen::Quaterniond& q_flat, const ImpactRecord& trigger);
  Next Stop(EndReason reason, double t, const EndState& state, std::string message = {});
  // Stop as Failed for `failure`, explained by `message`.
  Next Fail(FailureReason failure, double t, const EndState& state, std::string message);
  // The end of a segment of `mode` (rocking about `what`) that did not stop at a guard event: t_max or an
  // integrator failure; nullopt when it ended at an event.
  template <typename ModeT>
  std::optional<Next> StopUnlessEvent(const ModeT& mode, const SegmentOutcome<ModeT>& outcome);
  // Books an impact; false (and the run has failed) when impacts no longer advance time or the kinetic
  // energy after it, `kinetic_after_J`, shows that impacts keep adding energy without bound.
  bool BookImpact(const ImpactRecord& record, const EndState& state, double kinetic_after_J);
  void NoteDiscardedRate(const Eigen::Vector3d& w_B) {
    out_->max_discarded_rate_rad_s = std::max(out_->max_discarded_rate_rad_s, w_B.norm());
  }
  bool IsReleaseVertex(int k) const { return k == release_.first || k == release_.second; }
  EdgeStart MakeEdgeStart(const Contact& edge, const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& w_B,
                          const Eigen::Vector3d& p_BQ_B);
  template <class Outcome>
  void AddCounts(const Outcome& outcome) {
    out_->num_steps += outcome.num_steps;
    out_->num_evaluations += outcome.num_evaluations;
    out_->num_guard_evaluations += outcome.num_guard_evaluations;
    step_hint_s_ = outcome.next_step_hint_s;
  }

  const Block& block_;
  const ModelParameters& params_;
  const SimulationOptions& options_;
  double gravity_;
  Trajectory* out_;
  detail::TrajectorySampler sampler_;
  detail::ModeCache modes_;
  SegmentSettings settings_;
  RootPolisher polisher_;
  std::pair<int, int> release_;
  double step_hint_s_ = 0.0;
  bool facet_seen_ = false;
  ImpactSequence edge_impacts_;
  ImpactSequence facet_impacts_;
  double last_impact_t_ = -1.0;
  int impacts_at_instant_ = 0;
  VertexStart vertex_start_;
  EdgeStart edge_start_;
  double t_start_ = 0.0;
  const GroundMotion* ground_ = nullptr;
  bool start_flat_ = false;
  double t_lift_off_ = std::numeric_limits<double>::infinity();
  double end_lift_t_s_ = -std::numeric_limits<double>::infinity();  // the last Edge → Vertex switch
  RecentTimes recent_impacts_;  // of edge and facet impacts, under ground motion
  std::array<detail::LazySlot<FacetNoSpinOperators>, 4> facet_operators_;  // by pivot vertex b − 1, made when first needed
  // Free rocking, no-spin rule: the facet outcome of a unit rate about each ordered pre-impact edge (pivot b and the
  // other vertex before or after it) in each sense, made when first needed.
  std::array<detail::LazySlot<ImpactOutcome>, 16> facet_unit_outcomes_;
  // The edge map's operators for each ordered pair (pivot, landing), at EdgeOperatorSlot, made when first needed.
  std::array<detail::LazySlot<EdgeImpactOperators>, 8> edge_operators_;
  static int EdgeOperatorSlot(int pivot, int landing) {
    const int b = Block::WrapVertex(pivot);
    return 2 * (b - 1) + (Block::WrapVertex(b + 1) == Block::WrapVertex(landing) ? 0 : 1);
  }
};

EdgeStart HybridRun::MakeEdgeStart(const Contact& edge, const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& w_B,
                                   const Eigen::Vector3d& p_BQ_B) {
  EdgeStart start;
  start.edge = edge;
  const EdgeDynamics& dynamics = modes_.EdgeDynamicsOf(edge.first, edge.second);
  double psi = 0.0;
  dynamics.Decompose(q_WB, &start.q_yaw, &psi);
  // An edge on the ground with the base above it: ψ ≥ 0 up to the round-off of the event location.
  start.y = EdgeDynamics::State(std::max(psi, 0.0), dynamics.ProjectAngularVelocity(w_B, p_BQ_B));
  return start;
}

void HybridRun::Run() {
  Next next = Next::kEdge;
  if (ground_ != nullptr && start_flat_) {
    next = RestOnTable(0.0, Eigen::Quaterniond::Identity());
  } else if (options_.initial_state) {
    const InitialState& s = *options_.initial_state;
    if (s.contact.is_vertex()) {
      vertex_start_.vertex = s.contact.first;
      vertex_start_.y = VertexDynamics::MakeState(s.q_WB.normalized(), s.w_B);
      const VertexDynamics dynamics(block_, s.contact.first, gravity_);
      for (int k = 1; k <= 4; ++k) {
        if (dynamics.PointHeight(vertex_start_.y, block_.p_BV_B(k)) < -kInitialPenetrationTol_m) {
          throw InvalidArgument("the initial state pivots on V" + std::to_string(s.contact.first) + " but V" +
                                std::to_string(k) + " is below the ground");
        }
      }
      next = Next::kVertex;
    } else {
      const Contact edge = Contact::Edge(s.contact.first, s.contact.second);
      const EdgeDynamics dynamics(block_, edge.first, edge.second, gravity_);
      const Eigen::Vector3d off_axis = s.w_B - s.w_B.dot(dynamics.axis_B()) * dynamics.axis_B();
      if (off_axis.norm() > kInitialOffAxisTol_rad_s) {
        throw InvalidArgument("with edge contact " + edge.ToString() + " the initial w_B must be along the edge axis");
      }
      edge_start_ = MakeEdgeStart(edge, s.q_WB.normalized(), s.w_B, dynamics.p_BP_B());
      const Eigen::Quaterniond back = edge_start_.q_yaw * dynamics.Tilt(edge_start_.y[0]);
      if (back.angularDistance(s.q_WB.normalized()) > kInitialEdgeAttitudeTol_rad) {
        throw InvalidArgument("the initial attitude does not have edge " + edge.ToString() + " on the ground");
      }
      next = Next::kEdge;
    }
  } else if (params_.release_roll_rad != 0.0) {
    // Release from rest on a corner of the release edge, tilted by α and rolled by β (rolled_release.hpp).
    const RolledRelease rolled = MakeRolledRelease(block_, release_.first, release_.second, params_.alpha_rad,
                                                   params_.release_roll_rad);
    vertex_start_.vertex = rolled.pivot_vertex;
    vertex_start_.y = VertexDynamics::MakeState(rolled.q_WB, Eigen::Vector3d::Zero());
    next = Next::kVertex;
  } else {
    // Release from rest on the release edge, tilted by α (docs/design.md §2).
    edge_start_.edge = Contact::Edge(release_.first, release_.second);
    edge_start_.q_yaw = Eigen::Quaterniond::Identity();
    edge_start_.y = EdgeDynamics::State(params_.alpha_rad, 0.0);
  }
  while (next != Next::kStopped) {
    next = next == Next::kVertex ? RunVertex() : RunEdge();
  }
}

// What a mode rocks about, for messages.
std::string Pivot(const VertexMode& mode) { return "V" + std::to_string(mode.vertex()); }
std::string Pivot(const EdgeMode& mode) { return "edge " + mode.mode().ToString(); }
std::string Pivot(const GroundVertexMode& mode) { return Pivot(mode.free_mode()); }
std::string Pivot(const GroundEdgeMode& mode) { return Pivot(mode.free_mode()); }

template <typename ModeT>
std::optional<HybridRun::Next> HybridRun::StopUnlessEvent(const ModeT& mode, const SegmentOutcome<ModeT>& outcome) {
  if (outcome.end == SegmentEnd::kEvent) return std::nullopt;  // the usual case: no end state to build
  const EndState end{mode.mode(), mode.Attitude(outcome.y), mode.AngularVelocity_B(outcome.y)};
  switch (outcome.end) {
    case SegmentEnd::kTimeLimit:
      if (ground_ != nullptr && lift_off_before_t_max()) {
        return Stop(EndReason::kLiftOff, outcome.t_s, end,
                    "the table accelerates downward as fast as g at t = " + FormatTime(outcome.t_s) +
                        ": the block leaves the ground (free flight is not modelled)");
      }
      return Stop(EndReason::kTMax, outcome.t_s, end);
    case SegmentEnd::kStepFailure:
      return Fail(FailureReason::kIntegratorStep, outcome.t_s, end,
                  "the integrator could not continue rocking about " + Pivot(mode) + " at t = " + FormatTime(outcome.t_s) +
                      " (step size below round-off)");
    case SegmentEnd::kEvent:
      break;
  }
  return std::nullopt;
}

HybridRun::Next HybridRun::RunVertex() {
  if (ground_ != nullptr) {
    return RunVertexIn(modes_.GroundVertex(vertex_start_.vertex));
  }
  return RunVertexIn(modes_.Vertex(vertex_start_.vertex));
}

template <class ModeT>
HybridRun::Next HybridRun::RunVertexIn(const ModeT& mode) {
  out_->segments.emplace_back();
  const auto outcome = RunSegment(mode, t_start_, vertex_start_.y, vertex_start_.on_surface, settings_, step_hint_s_,
                                  polisher_, sampler_, &out_->segments.back());
  AddCounts(outcome);
  if (const auto stopped = StopUnlessEvent(mode, outcome)) return *stopped;
  if (!ModeT::IsTouchdown(outcome.guard)) {
    return Stop(EndReason::kOverturned, outcome.t_s,
                {mode.mode(), mode.Attitude(outcome.y), mode.AngularVelocity_B(outcome.y)});
  }
  return AfterEdgeImpact(FreeMode(mode), outcome.t_s, outcome.y, mode.GuardVertex(outcome.guard));
}

HybridRun::Next HybridRun::RunEdge() {
  const Contact& e = edge_start_.edge;
  if (ground_ != nullptr) {
    return RunEdgeIn(modes_.GroundEdge(e.first, e.second, edge_start_.q_yaw, edge_start_.lift_margin_g));
  }
  return RunEdgeIn(modes_.Edge(e.first, e.second, edge_start_.q_yaw));
}

template <class ModeT>
HybridRun::Next HybridRun::RunEdgeIn(const ModeT& mode) {
  out_->segments.emplace_back();
  // Under ground motion an end-lift guard that starts at or below zero (the segment began where it vanished, or
  // an impact or Zeno switch left the edge with the end barely lifting) counts as exactly zero: the end lifts
  // only if the guard then falls (its lift acceleration grows), never on the round-off of the event or on a
  // lift that is over within the first step (which would bring the vertex straight back: an endless loop).
  std::array<bool, ModeT::kNumGuards> on_surface{};
  for (int g = EdgeMode::kNumGuards; g < ModeT::kNumGuards; ++g) {
    on_surface[g] = mode.Guard(g, t_start_, edge_start_.y).value <= kLoadZeroTol;
  }
  if constexpr (std::is_same_v<ModeT, EdgeMode>) {
    // Free rocking: a swing that lands again needs no integrator.
    if (options_.analytic_edge_phases) {
      if (const auto outcome = detail::RunAnalyticEdgeSegment(mode, t_start_, edge_start_.y, settings_, step_hint_s_,
                                                              sampler_, &out_->segments.back())) {
        return AfterEdgeSegment(mode, *outcome);
      }
    }
  }
  return AfterEdgeSegment(mode, RunSegment(mode, t_start_, edge_start_.y, on_surface, settings_, step_hint_s_,
                                           polisher_, sampler_, &out_->segments.back()));
}

template <class ModeT>
HybridRun::Next HybridRun::AfterEdgeSegment(const ModeT& mode, const SegmentOutcome<ModeT>& outcome) {
  AddCounts(outcome);
  if (const auto stopped = StopUnlessEvent(mode, outcome)) return *stopped;
  if (outcome.guard >= EdgeMode::kNumGuards) {
    // Ground motion only: an end vertex of the edge unloads (GroundEdgeMode::kLoadFirst / kLoadSecond).
    const EdgeMode& free = FreeMode(mode);
    const int lifting = outcome.guard == EdgeMode::kNumGuards ? free.first() : free.second();
    return EdgeToVertex(free, outcome.t_s, outcome.y, lifting);
  }
  if (!ModeT::IsTouchdown(outcome.guard)) {
    return Stop(EndReason::kOverturned, outcome.t_s,
                {mode.mode(), mode.Attitude(outcome.y), mode.AngularVelocity_B(outcome.y)});
  }
  return AfterFacetImpact(FreeMode(mode), outcome.t_s, outcome.y);
}

HybridRun::Next HybridRun::EdgeToVertex(const EdgeMode& mode, double t, const EdgeDynamics::State& y, int lifting) {
  const int pivot = lifting == mode.first() ? mode.second() : mode.first();
  const Eigen::Quaterniond q_WB = mode.Attitude(y);
  const Eigen::Vector3d w_B = mode.AngularVelocity_B(y);
  ImpactRecord record;
  record.t_s = t;
  record.kind = ImpactKind::kUplift;
  record.contact_before = mode.mode().contact;
  record.contact_after = Contact::Vertex(pivot);
  record.w_minus_B = w_B;
  record.w_plus_B = w_B;
  record.w_minus_W = q_WB * w_B;
  record.w_plus_W = record.w_minus_W;
  Mode after_mode;
  after_mode.kind = ModeKind::kVertex;
  after_mode.contact = record.contact_after;
  const VertexDynamics& about_pivot = modes_.VertexDynamicsOf(pivot);
  if (!BookImpact(record, {after_mode, q_WB, w_B}, about_pivot.KineticEnergy(VertexDynamics::MakeState(q_WB, w_B)))) {
    return Next::kStopped;
  }
  edge_impacts_.Clear();
  end_lift_t_s_ = t;
  const bool flat = y[0] < kFlatTiltTol_rad;
  return Continue(record.contact_after, t, q_WB, w_B, pivot, flat ? -1 : lifting, flat ? -1 : 0);
}

HybridRun::Next HybridRun::RestOnTable(double t, const Eigen::Quaterniond& q_flat) {
  Mode rest_mode;
  rest_mode.kind = ModeKind::kRest;
  const EndState at_rest{rest_mode, q_flat, Eigen::Vector3d::Zero()};
  const double t_until = std::min(options_.t_max_s, t_lift_off_);
  const std::optional<Uplift> uplift = NextUplift(block_, *ground_, q_flat, gravity_, t, t_until);
  if (!uplift) {
    if (lift_off_before_t_max()) {
      return Stop(EndReason::kLiftOff, t_lift_off_, at_rest,
                  "the table accelerates downward as fast as g at t = " + FormatTime(t_lift_off_) +
                      ": the block leaves the ground (free flight is not modelled)");
    }
    if (options_.stop == StopCondition::kTMax) return Stop(EndReason::kTMax, options_.t_max_s, at_rest);
    // At rest for good: the run ends, but not before the record does (the samples show the table moving).
    return Stop(EndReason::kRest, std::max(t, std::min(ground_->t_end_s(), options_.t_max_s)), at_rest);
  }
  sampler_.EmitHeld(rest_mode, Eigen::Vector3d::Zero(), q_flat, uplift->t_s, false);
  ImpactRecord record;
  record.t_s = uplift->t_s;
  record.kind = ImpactKind::kUplift;
  record.contact_after = uplift->contact;
  out_->impacts.push_back(record);
  return StartRocking(*uplift, q_flat);
}

HybridRun::Next HybridRun::StartRocking(const Uplift& uplift, const Eigen::Quaterniond& q_flat) {
  edge_impacts_.Clear();
  facet_impacts_.Clear();
  t_start_ = uplift.t_s;
  if (uplift.contact.is_vertex()) {
    vertex_start_.vertex = uplift.contact.first;
    vertex_start_.y = VertexDynamics::MakeState(q_flat, Eigen::Vector3d::Zero());
    for (int g = 0; g < VertexMode::kNumGuards; ++g) vertex_start_.on_surface[g] = VertexMode::IsTouchdown(g);
    return Next::kVertex;
  }
  edge_start_.edge = uplift.contact;
  edge_start_.q_yaw = q_flat;
  edge_start_.y = EdgeDynamics::State::Zero();
  return Next::kEdge;
}

HybridRun::Next HybridRun::AfterFacetImpactOnTable(double t, const Eigen::Quaterniond& q_flat,
                                                   const ImpactRecord& trigger) {
  // Rest under a moving table is a contact condition (docs/design.md §11a): the block stops only where its
  // relative velocity vanishes — the map's ω⁺ = 0, |ω⁺| at the numerical floor, the accumulation point of a
  // Zeno sequence of facet impacts, or a micro-chatter below the integrator's resolution — and there rests only
  // if the moment of gravity and of −m·a_g keeps every base edge down. An impact that leaves the block rocking
  // is never cut short by an energy threshold.
  //
  // Impact parameters beyond the paper's bounds — a facet impact that adds energy (26), or a resultant beyond a
  // side edge of the base (|λ_lat| > 1, (27)), as fitted parameters often are — sustain chatters of sub-nanometre
  // hops that never accumulate (the map hands the block across its base to the opposite vertex at an ever-similar
  // rate), a motion the rigid model does not resolve. There, a facet impact that leaves less kinetic energy than
  // lifts the COM by rest_energy_height (the free-rocking threshold) drops its velocity and the contact decides
  // (docs/design.md §11a, "Parameters beyond the bounds"). Planar motion (λ_lat = 0) keeps the contact rule alone.
  const Contact& contact = trigger.contact_after;
  const bool stopped = !contact.is_vertex() && !contact.is_edge();
  const bool beyond_bounds = trigger.delta_energy_J > 0.0 || std::abs(params_.lambda_lat) > kLateralBound;
  const bool below_resolution =
      beyond_bounds && KineticEnergyAfterLanding(modes_, contact, q_flat, trigger.w_plus_B) <
                           block_.mass() * gravity_ * options_.rest_energy_height_m;
  double accumulates_in_s = 0.0;
  if (!stopped && !below_resolution && trigger.w_plus_B.norm() > kRestRateFloor_rad_s &&
      !MicroChatter(q_flat, trigger.w_plus_B)) {
    const std::optional<double> remaining = facet_impacts_.Accumulation(options_.zeno_dt_s);
    if (!remaining) return Continue(contact, t, q_flat, trigger.w_plus_B, contact.first, -1, -1);
    accumulates_in_s = *remaining;
  }
  if (const std::optional<Next> settled = SettleOnTable(t, q_flat, trigger, accumulates_in_s)) return *settled;
  // The table tips the block before the accumulation point: the impacts go on (they are the motion).
  return Continue(contact, t, q_flat, trigger.w_plus_B, contact.first, -1, -1);
}

std::optional<HybridRun::Next> HybridRun::SettleOnTable(double t, const Eigen::Quaterniond& q_flat,
                                                        const ImpactRecord& trigger, double horizon_s) {
  // The contact must hold from now to the accumulation point (horizon_s ahead).
  const double t_until = std::min({t + horizon_s, options_.t_max_s, t_lift_off_});
  const std::optional<Uplift> uplift = NextUplift(block_, *ground_, q_flat, gravity_, t, t_until);
  if (!uplift) return Rest(t, q_flat, trigger);
  if (uplift->t_s > t) return std::nullopt;
  // The table tips the block at this instant: it rocks on from zero relative velocity about the edge or vertex
  // the moment selects, logged as a switch of contact (kind zeno) that drops the velocity left.
  const Contact& contact = trigger.contact_after;
  ImpactRecord zeno;
  zeno.t_s = t;
  zeno.kind = ImpactKind::kZeno;
  zeno.contact_before = contact;
  zeno.contact_after = uplift->contact;
  zeno.w_minus_B = trigger.w_plus_B;
  zeno.w_minus_W = trigger.w_plus_W;
  zeno.delta_energy_J = -KineticEnergyAfterLanding(modes_, contact, q_flat, trigger.w_plus_B);
  out_->impacts.push_back(zeno);
  NoteDiscardedRate(trigger.w_plus_B);
  return StartRocking(*uplift, q_flat);
}

bool HybridRun::MicroChatter(const Eigen::Quaterniond& q_WB, const Eigen::Vector3d& w_B) const {
  if (!recent_impacts_.Within(kMicroChatterSpan_s)) return false;
  const Eigen::Matrix3d R_WB = q_WB.toRotationMatrix();
  const double sin_tilt = std::hypot(R_WB(0, 2), R_WB(1, 2));  // the body z axis off the vertical
  return sin_tilt <= kMicroChatterTilt_rad && w_B.norm() <= kMicroChatterRate_rad_s;
}

bool HybridRun::BookImpact(const ImpactRecord& record, const EndState& state, double kinetic_after_J) {
  out_->impacts.push_back(record);
  const double blow_up_J =
      kBlowUpEnergyFactor * block_.mass() * gravity_ * (block_.p_BC_B() - block_.p_BV_B(1)).norm();
  if (!(kinetic_after_J < blow_up_J)) {
    Fail(FailureReason::kEnergyBlowUp, record.t_s, state,
         "the kinetic energy grows without bound (" + std::to_string(kinetic_after_J) + " J after the " +
             ToString(record.kind) + " impact at t = " + FormatTime(record.t_s) +
             "): the impact parameters add energy at impacts (see delta_energy in the impact log)");
    return false;
  }
  const double same_instant = kSameInstantFactor * options_.event_time_tol_s;
  impacts_at_instant_ = (record.t_s - last_impact_t_ <= same_instant) ? impacts_at_instant_ + 1 : 1;
  last_impact_t_ = record.t_s;
  if (impacts_at_instant_ > kMaxImpactsAtOneInstant) {
    Fail(FailureReason::kImpactCascade, record.t_s, state,
         "more than " + std::to_string(kMaxImpactsAtOneInstant) + " impacts at t = " + FormatTime(record.t_s) +
             " without the contact resolving (last " + ToString(record.kind) + " impact " +
             record.contact_before.ToString() + " → " + record.contact_after.ToString() + ")");
    return false;
  }
  if (out_->impacts.size() >= options_.max_impacts) {
    Fail(FailureReason::kMaxImpacts, record.t_s, state,
         "more than max_impacts = " + std::to_string(options_.max_impacts) + " impacts by t = " + FormatTime(record.t_s));
    return false;
  }
  return true;
}

HybridRun::Next HybridRun::AfterEdgeImpact(const VertexMode& mode, double t, const VertexDynamics::State& y,
                                           int landing) {
  const int pivot = mode.vertex();
  const Eigen::Quaterniond q_WB = mode.Attitude(y);
  const Eigen::Matrix3d R_WB = q_WB.toRotationMatrix();
  const Eigen::Vector3d w_minus_B = mode.AngularVelocity_B(y);
  const EdgeImpactParameters edge_params{params_.lambda, params_.tau_edge};
  ImpactOutcome map;
  if (ground_ == nullptr) {
    // Free rocking: the map in B, its operators made once per ordered pair (pivot, landing) and run (the same
    // outcome to round-off). Under a table the map is built in W afresh, so that the response runs, whose chatter
    // amplifies round-off, stay bit for bit those of the full map.
    detail::LazySlot<EdgeImpactOperators>& operators = edge_operators_[EdgeOperatorSlot(pivot, landing)];
    if (!operators) operators = MakeEdgeImpactOperators(block_, pivot, landing, edge_params);
    map = EdgeImpact(*operators, R_WB, w_minus_B);
  } else {
    map = EdgeImpact(block_, R_WB, pivot, landing, R_WB * w_minus_B, edge_params);
  }
  const Eigen::Vector3d w_minus_W = map.w_minus_W;

  ImpactRecord record;
  record.t_s = t;
  record.kind = ImpactKind::kEdge;
  record.contact_before = Contact::Vertex(pivot);
  record.contact_after = map.contact_after;
  record.w_minus_B = w_minus_B;
  record.w_minus_W = w_minus_W;
  record.w_plus_W = map.w_plus_W;
  record.w_plus_B = ground_ == nullptr ? map.w_plus_B : Eigen::Vector3d(R_WB.transpose() * map.w_plus_W);
  record.tau = map.tau;
  record.delta_energy_J = map.delta_energy_J;
  record.status = map.status;
  const EndState before{mode.mode(), q_WB, w_minus_B};
  if (map.status != ImpactStatus::kOk || !map.w_plus_W.allFinite()) {
    out_->impacts.push_back(record);
    return Fail(FailureReason::kEdgeImpact, t, before,
                std::string("the edge impact on V") + std::to_string(pivot) + "V" + std::to_string(landing) +
                    " at t = " + FormatTime(t) + " has no solution (map status " + ToString(map.status) + ")");
  }
  if (map.contact_after.is_edge()) {
    // Edge contact V_aV_b after the impact: the block turns about the edge, with the angular momentum about the
    // edge line of the map's ω⁺ (a rotation about V_a). The log shows that motion and its energy change.
    const EdgeStart start = MakeEdgeStart(map.contact_after, q_WB, record.w_plus_B, block_.p_BV_B(landing));
    const EdgeDynamics& about_edge = modes_.EdgeDynamicsOf(map.contact_after.first, map.contact_after.second);
    record.w_plus_B = about_edge.AngularVelocity_B(start.y);
    record.w_plus_W = R_WB * record.w_plus_B;
    record.delta_energy_J = about_edge.KineticEnergy(start.y) - map.energy_before_J;
  }
  Mode after_mode;
  after_mode.kind = map.contact_after.is_edge() ? ModeKind::kEdge : ModeKind::kVertex;
  after_mode.contact = map.contact_after;
  const EndState after{after_mode, q_WB, record.w_plus_B};
  const VertexDynamics& about_landing = modes_.VertexDynamicsOf(landing);
  const double kinetic_after = about_landing.KineticEnergy(VertexDynamics::MakeState(q_WB, record.w_plus_B));
  if (!BookImpact(record, after, kinetic_after)) return Next::kStopped;
  // Under ground motion a chatter that lands on the base from alternate corners has edge impacts between its
  // facet impacts (facet → vertex → edge impacts → Zeno → edge → facet): the facet impacts of such a cycle
  // still accumulate, so the sequence goes on through them (docs/design.md §11a).
  if (ground_ == nullptr) facet_impacts_.Clear();
  edge_impacts_.Add(t, Contact::Edge(pivot, landing));
  if (ground_ != nullptr) recent_impacts_.Add(t);

  if (facet_seen_ && IsReleaseVertex(landing) && options_.stop == StopCondition::kPhase4) {
    return Stop(EndReason::kPhase4, t, after);
  }
  if (ground_ != nullptr && MicroChatter(q_WB, record.w_plus_B)) {
    if (const std::optional<Next> settled = SettleOnTable(t, FlatWithHeadingOf(q_WB), record, 0.0)) return *settled;
  }
  // Under ground motion the wobble between the two ends of an edge alternates short and long intervals (the
  // table lifts one end harder): where it accumulates, the interleaved test sees it (docs/design.md §11a).
  const bool zeno = map.contact_after.is_vertex() &&
                    (edge_impacts_.Shrinking(options_.zeno_dt_s) ||
                     edge_impacts_.LastIntervalBelow(kZenoFloorFactor * options_.event_time_tol_s) ||
                     (ground_ != nullptr && edge_impacts_.Accumulation(options_.zeno_dt_s)));
  if (zeno) {
    // Accumulating edge impacts on one edge: continue as rocking about that edge with the angular momentum
    // about the edge line of the post-impact rotation about V_a (docs/design.md §4).
    const Contact edge = Contact::Edge(pivot, landing);
    const int a = map.contact_after.first;
    edge_start_ = MakeEdgeStart(edge, q_WB, record.w_plus_B, block_.p_BV_B(a));
    const EdgeDynamics& next_mode = modes_.EdgeDynamicsOf(edge.first, edge.second);
    ImpactRecord switch_record;
    switch_record.t_s = t;
    switch_record.kind = ImpactKind::kZeno;
    switch_record.contact_before = map.contact_after;
    switch_record.contact_after = edge;
    switch_record.w_minus_B = record.w_plus_B;
    switch_record.w_minus_W = record.w_plus_W;
    switch_record.w_plus_B = next_mode.AngularVelocity_B(edge_start_.y);
    switch_record.w_plus_W = R_WB * switch_record.w_plus_B;
    const VertexDynamics& about_a = modes_.VertexDynamicsOf(a);
    switch_record.delta_energy_J = next_mode.KineticEnergy(edge_start_.y) -
                                   about_a.KineticEnergy(VertexDynamics::MakeState(q_WB, record.w_plus_B));
    out_->impacts.push_back(switch_record);
    edge_impacts_.Clear();
    t_start_ = t;
    return Next::kEdge;
  }
  const Next next = Continue(map.contact_after, t, q_WB, record.w_plus_B, landing, pivot, 0);
  if (ground_ != nullptr && map.contact_after.is_edge() &&
      t - end_lift_t_s_ <= kSameInstantFactor * options_.event_time_tol_s) {
    edge_start_.lift_margin_g = kReliftMargin_g;  // the end that just lifted came straight back
  }
  return next;
}

HybridRun::Next HybridRun::AfterFacetImpact(const EdgeMode& mode, double t, const EdgeDynamics::State& y) {
  // The base is flat at the impact: the attitude is the yaw alone.
  const Eigen::Quaterniond q_flat = mode.q_yaw();
  const Eigen::Matrix3d R_WB = q_flat.toRotationMatrix();
  const Eigen::Vector3d w_minus_B = mode.AngularVelocity_B(y);
  FacetImpactParameters facet;
  facet.lambda_lat = params_.lambda_lat;
  facet.lambda_lon = params_.lambda_lon;
  facet.tau_rule = params_.facet_tau_rule;
  facet.tau = 0.0;
  // The pre-impact edge is V_{b−1}V_b in the cyclic order of Contact::Edge.
  const int pivot_b = mode.second();
  ImpactOutcome map;
  if (facet.tau_rule == FacetTauRule::kNoSpin) {
    // The no-spin map is linear in ω⁻: its candidates' operators are computed once per pivot edge and run.
    detail::LazySlot<FacetNoSpinOperators>& operators = facet_operators_[Block::WrapVertex(pivot_b) - 1];
    if (!operators) operators = MakeFacetNoSpinOperators(block_, pivot_b, facet);
    const double rate = y[1];  // ω⁻ = ψ̇ · a_B: a multiple of the edge axis
    if (ground_ == nullptr && std::isfinite(rate) && rate != 0.0) {
      // Free rocking: the outcome for the unit rate in this sense, once per edge and sense, scaled by |ψ̇|
      // (ScaledFacetOutcome). Under a table the map is evaluated afresh, so that the response runs, whose chatter
      // amplifies round-off, stay bit for bit those of the full map.
      const int sense = rate > 0.0 ? 1 : 0;
      const bool other_before = Block::WrapVertex(mode.first()) == Block::WrapVertex(pivot_b - 1);
      const int edge_slot = 2 * (Block::WrapVertex(pivot_b) - 1) + (other_before ? 0 : 1);
      detail::LazySlot<ImpactOutcome>& unit = facet_unit_outcomes_[2 * edge_slot + sense];
      if (!unit) unit = FacetImpact(block_, *operators, (sense == 1 ? 1.0 : -1.0) * mode.dynamics().axis_B(), facet);
      map = ScaledFacetOutcome(*unit, std::abs(rate));
    } else {
      map = FacetImpact(block_, *operators, w_minus_B, facet);
    }
  } else {
    map = FacetImpact(block_, pivot_b, w_minus_B, facet);
  }

  ImpactRecord record;
  record.t_s = t;
  record.kind = ImpactKind::kFacet;
  record.contact_before = mode.mode().contact;
  record.contact_after = map.contact_after;
  record.w_minus_B = w_minus_B;
  record.w_minus_W = R_WB * w_minus_B;
  record.w_plus_B = map.w_plus_B;
  record.w_plus_W = R_WB * map.w_plus_B;
  record.tau = map.tau;
  record.delta_energy_J = map.delta_energy_J;
  record.status = map.status;
  const EndState before{mode.mode(), q_flat, w_minus_B};
  if (map.status != ImpactStatus::kOk || !map.w_plus_B.allFinite()) {
    out_->impacts.push_back(record);
    return Fail(FailureReason::kFacetImpact, t, before,
                "the facet impact after rocking about " + mode.mode().ToString() + " at t = " + FormatTime(t) +
                    " has no solution (map status " + ToString(map.status) + ")");
  }
  Mode after_mode;
  after_mode.kind = map.contact_after.is_edge()     ? ModeKind::kEdge
                    : map.contact_after.is_vertex() ? ModeKind::kVertex
                                                    : ModeKind::kRest;  // ω⁺ = 0: the base stays down
  after_mode.contact = map.contact_after;
  const EndState after{after_mode, q_flat, map.w_plus_B};
  // Kinetic energy after the impact (zero when the base stays down).
  const double kinetic_after = KineticEnergyAfterLanding(modes_, map.contact_after, q_flat, map.w_plus_B);
  if (!BookImpact(record, after, kinetic_after)) return Next::kStopped;
  edge_impacts_.Clear();
  facet_impacts_.Add(t, Contact{});
  if (ground_ != nullptr) recent_impacts_.Add(t);

  // The vertices that land are those off the pre-impact edge.
  bool release_side_lands = false;
  for (int k = 1; k <= 4; ++k) {
    if (k != mode.first() && k != mode.second() && IsReleaseVertex(k)) release_side_lands = true;
  }
  if (facet_seen_ && release_side_lands && options_.stop == StopCondition::kPhase4) {
    return Stop(EndReason::kPhase4, t, after);
  }
  facet_seen_ = true;

  if (ground_ != nullptr) return AfterFacetImpactOnTable(t, q_flat, record);
  // Free rocking: rest when the kinetic energy cannot lift the COM by rest_energy_height, or facet impacts
  // accumulate (docs/design.md §4).
  const double rest_energy = block_.mass() * gravity_ * options_.rest_energy_height_m;
  const bool stays_down = !map.contact_after.is_vertex() && !map.contact_after.is_edge();
  if (stays_down || kinetic_after < rest_energy || facet_impacts_.Shrinking(options_.zeno_dt_s)) {
    return Rest(t, q_flat, record);
  }
  // All base vertices are on the ground at a facet impact.
  return Continue(map.contact_after, t, q_flat, map.w_plus_B, map.contact_after.first, -1, -1);
}

HybridRun::Next HybridRun::Continue(const Contact& contact, double t, const Eigen::Quaterniond& q_WB,
                                    const Eigen::Vector3d& w_B, int pivot, int vertex_off_ground_first,
                                    int vertex_off_ground_second) {
  t_start_ = t;
  if (contact.is_vertex()) {
    vertex_start_.vertex = contact.first;
    vertex_start_.y = VertexDynamics::MakeState(q_WB, w_B);
    // Guards of vertices that were on the ground just before start at zero (−1: all of them).
    const VertexMode& next_mode = modes_.Vertex(contact.first);
    for (int g = 0; g < VertexMode::kNumGuards; ++g) {
      bool on_ground = false;
      if (VertexMode::IsTouchdown(g)) {
        const int k = next_mode.GuardVertex(g);
        on_ground = vertex_off_ground_first == -1 || k == vertex_off_ground_first || k == vertex_off_ground_second;
      }
      vertex_start_.on_surface[g] = on_ground;
    }
    return Next::kVertex;
  }
  // Edge contact after the impact: rotation about the edge, as the map's rotation about V_a projected onto it.
  edge_start_ = MakeEdgeStart(contact, q_WB, w_B, block_.p_BV_B(pivot));
  return Next::kEdge;
}

HybridRun::Next HybridRun::Rest(double t, const Eigen::Quaterniond& q_flat, const ImpactRecord& trigger) {
  ImpactRecord rest;
  rest.t_s = t;
  rest.kind = ImpactKind::kRest;
  rest.contact_before = trigger.contact_after;
  rest.contact_after = Contact{};
  rest.w_minus_B = trigger.w_plus_B;
  rest.w_minus_W = trigger.w_plus_W;
  const double kinetic = KineticEnergyAfterLanding(modes_, trigger.contact_after, q_flat, trigger.w_plus_B);
  rest.delta_energy_J = -kinetic;
  out_->impacts.push_back(rest);
  NoteDiscardedRate(trigger.w_plus_B);
  if (ground_ != nullptr) return RestOnTable(t, q_flat);
  Mode rest_mode;
  rest_mode.kind = ModeKind::kRest;
  const EndState at_rest{rest_mode, q_flat, Eigen::Vector3d::Zero()};
  if (options_.stop == StopCondition::kTMax) {
    // The block stays at rest: fill the samples up to t_max.
    return Stop(EndReason::kTMax, options_.t_max_s, at_rest);
  }
  return Stop(EndReason::kRest, t, at_rest);
}

HybridRun::Next HybridRun::Stop(EndReason reason, double t, const EndState& state, std::string message) {
  sampler_.EmitHeld(state.mode, state.w_B, state.q_WB, t, true);
  out_->t_end_s = t;
  out_->end_q_WB = state.q_WB;
  out_->end_w_B = state.w_B;
  out_->end_reason = reason;
  out_->message = std::move(message);
  return Next::kStopped;
}

HybridRun::Next HybridRun::Fail(FailureReason failure, double t, const EndState& state, std::string message) {
  out_->failure = failure;
  return Stop(EndReason::kFailed, t, state, std::move(message));
}

}  // namespace

void Trajectory::Clear() {
  // Take the vectors out, reset every other field to its default, and put the emptied vectors back.
  std::vector<double> kept_t_s = std::move(t_s);
  std::vector<Eigen::Vector3d> kept_w_B = std::move(w_B);
  std::vector<Eigen::Quaterniond> kept_q_WB = std::move(q_WB);
  std::vector<Eigen::Vector3d> kept_euler_zyx = std::move(euler_zyx);
  std::vector<Mode> kept_mode = std::move(mode);
  std::vector<ImpactRecord> kept_impacts = std::move(impacts);
  std::vector<SegmentDiagnostics> kept_segments = std::move(segments);
  std::string kept_message = std::move(message);
  *this = Trajectory();
  kept_t_s.clear();
  kept_w_B.clear();
  kept_q_WB.clear();
  kept_euler_zyx.clear();
  kept_mode.clear();
  kept_impacts.clear();
  kept_segments.clear();
  kept_message.clear();
  t_s = std::move(kept_t_s);
  w_B = std::move(kept_w_B);
  q_WB = std::move(kept_q_WB);
  euler_zyx = std::move(kept_euler_zyx);
  mode = std::move(kept_mode);
  impacts = std::move(kept_impacts);
  segments = std::move(kept_segments);
  message = std::move(kept_message);
}

void SimulateInto(const Block& block, const ModelParameters& params, const SimulationOptions& options,
                  Trajectory* out) {
  const auto wall_start = std::chrono::steady_clock::now();
  out->Clear();
  options.Validate();
  params.Validate(!options.initial_state.has_value());
  HybridRun run(block, params, options, out);
  run.Run();
  out->wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
}

Trajectory Simulate(const Block& block, const ModelParameters& params, const SimulationOptions& options) {
  Trajectory trajectory;
  SimulateInto(block, params, options, &trajectory);
  return trajectory;
}

Trajectory Simulate(const Block& block, const ModelParameters& params, const SimulationOptions& options,
                    const GroundMotion& ground, GroundStart start) {
  const auto wall_start = std::chrono::steady_clock::now();
  options.Validate();
  const bool flat = start == GroundStart::kFlatAtRest;
  params.Validate(!flat && !options.initial_state.has_value());
  if (options.stop == StopCondition::kPhase4) {
    throw InvalidArgument("a run under ground motion stops at t_max, at rest or when the block overturns, not at phase 4");
  }
  Trajectory trajectory;
  HybridRun run(block, params, options, &trajectory, &ground, flat);
  run.Run();
  trajectory.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return trajectory;
}

}  // namespace rockfit::core
