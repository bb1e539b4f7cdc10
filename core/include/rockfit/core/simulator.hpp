// The hybrid simulator of free 3D rocking (paper Sect. 4.1, Fig. 7; docs/design.md §4).
//
// Modes: Edge(i,j) (1 DOF about a base edge), Vertex(k) (3 DOF about a base vertex), Rest, and the
// terminal states Overturned and Failed. Impacts go through the maps of impact_maps.hpp. The decisions the
// specification leaves open (events, Zeno, rest, phase 4, failures, output) are in core/README.md, "Simulator".
//
//   rockfit::core::SimulationOptions options;               // stop at phase 4, 256 Hz output
//   const rockfit::core::Trajectory tr = rockfit::core::Simulate(block, params, options);
//   if (tr.end_reason == rockfit::core::EndReason::kFailed) { /* tr.message says why */ }
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rockfit/core/block.hpp"
#include "rockfit/core/ground_motion.hpp"
#include "rockfit/core/impact_maps.hpp"

namespace rockfit::core {

enum class ModeKind { kEdge, kVertex, kRest, kOverturned, kFailed };
const char* ToString(ModeKind kind);                      // "edge", "vertex", "rest", "overturned", "failed"
bool FromString(std::string_view text, ModeKind* value);  // the inverse of ToString

struct Mode {
  ModeKind kind = ModeKind::kEdge;
  Contact contact;  // the edge or vertex in contact (empty for Rest, Overturned, Failed)
  // "V1V2", "V3", "rest", "overturned", "failed".
  std::string ToString() const;
  bool operator==(const Mode& other) const { return kind == other.kind && contact == other.contact; }
  bool operator!=(const Mode& other) const { return !(*this == other); }
};

enum class StopCondition { kPhase4, kRest, kOverturned, kTMax };
// kLiftOff: under ground motion the table accelerates downward at least as fast as g; the block would leave
// the ground (free flight is not modelled), and the run ends at that instant.
enum class EndReason { kPhase4, kRest, kOverturned, kTMax, kFailed, kLiftOff };
const char* ToString(StopCondition stop);  // "phase4", "rest", "overturned", "t_max"
// Reads a stop condition's name back (command line, Python); false (and *stop unchanged) for any other text.
bool FromString(std::string_view text, StopCondition* stop);
const char* ToString(EndReason reason);    // "phase4", "rest", "overturned", "t_max", "failed", "lift_off"
bool FromString(std::string_view text, EndReason* value);  // the inverse of ToString

// When a run under ground motion has overturned (core/README.md, "Overturning under ground motion").
enum class OverturnRule {
  // "support": the COM passes over the support edge or vertex, as in free runs (docs/design.md §4).
  kComOverSupport,
  // "side": the motion goes on past the support, where the table may still pull the block back; the block has
  // overturned when it lies on a side (its z axis horizontal). This is the criterion of rocking spectra that
  // integrate the equation of motion through θ_c and judge overturning by where the block ends up.
  kFallsOnSide,
};
const char* ToString(OverturnRule rule);  // "support", "side"
bool FromString(std::string_view text, OverturnRule* rule);

// Initial conditions and impact parameters of one run (constant during the run).
struct ModelParameters {
  double alpha_rad = 0.2;    // release tilt (> 0; beyond the critical angle the block overturns at t = 0)
  // Release roll about the release edge's inward axis (rolled_release.hpp): 0 releases on the edge (the paper's
  // release); otherwise the block starts at rest on one corner of the edge, in a vertex phase.
  double release_roll_rad = 0.0;
  double lambda = 1.0;       // edge impacts (19)
  double tau_edge = 0.0;     // edge impacts [N·m·s]
  double lambda_lat = 0.0;   // facet impacts (21)
  double lambda_lon = 1.0;   // facet impacts (21)
  FacetTauRule facet_tau_rule = FacetTauRule::kNoSpin;  // kFixed means τ = 0 (the paper's Sect. 5)
  // Throws InvalidArgument for a non-finite value, a tilt α ≤ 0 or a roll |β| ≥ π/4 (α and β are checked only
  // for a release run).
  void Validate(bool check_alpha = true) const;
};

// Start from a given state instead of the release from rest. The contact is on the ground; for an edge,
// w_B must be along the edge and the attitude must have the edge on the ground (Simulate throws otherwise).
struct InitialState {
  Contact contact;                                      // vertex or edge in contact
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();
};

struct SimulationOptions {
  double rate_hz = 256.0;               // output samples at t_k = k / rate_hz after the release
  // If non-empty (ascending): sample at these times instead. Times before 0 get the initial state (the block
  // held before the release); times after the end of the run are not sampled (the trajectory is shorter).
  std::vector<double> sample_times_s;
  StopCondition stop = StopCondition::kPhase4;
  double t_max_s = 20.0;
  int release_edge_first = 1;           // release edge V_iV_j (default V1V2, +x side lifted)
  int release_edge_second = 2;
  // Edge impacts on one edge whose interval shrinks below this switch to edge rocking; facet impacts
  // whose interval shrinks below this end in Rest. Under ground motion facet impacts end only at an
  // accumulation point predicted less than this ahead, where the table keeps the block down.
  double zeno_dt_s = 1e-4;
  // Free rocking only: kinetic energy after a facet impact below m·g·this ends in Rest. Under ground motion
  // no energy threshold decides rest against rocking (docs/design.md §11a).
  double rest_energy_height_m = 1e-9;
  double gravity_m_s2 = kStandardGravity;
  double rel_tol = 1e-12;               // integrator relative tolerance
  double abs_tol = 1e-14;               // integrator absolute tolerance
  // Event location: crossings are polished to round-off; this bounds the location of a guard's extremum,
  // which only brackets a crossing (core/README.md, "Events").
  double event_time_tol_s = 1e-12;
  // Largest integrator step. Events inside a step are found from the guards' slopes at both ends (a dip
  // below zero and back is an interior minimum), which assumes at most one extremum of a vertex height per
  // step. In vertex rocking the steps are also kept below a turn of the body by kMaxTurnPerStep_rad (0.5 rad,
  // far from the π between two extrema of a height under rotation); edge rocking needs no bound (its guards
  // cannot dip and return).
  double max_step_s = 5e-2;
  std::size_t max_impacts = 100000;     // a run with more impacts ends as Failed
  // Under ground motion only: when the block has overturned. Free runs stop when the COM passes over the
  // support (past it a block on a still table only falls further).
  OverturnRule overturn = OverturnRule::kComOverSupport;
  bool sample_attitude = true;          // false: fill only t, w_B and mode (faster, for fitting)
  // Free runs: a swing about an edge that lands again is evaluated in closed form (landing time by an elliptic
  // integral, samples by Jacobi elliptic functions; docs/design.md §4, "Analytic edge phases") instead of being
  // integrated. false integrates it like every other phase (for checks). Runs under ground motion always integrate.
  bool analytic_edge_phases = true;
  std::optional<InitialState> initial_state;
  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

// What an entry of the impact log records. The string forms are used only at the edges (JSON, HDF5, CSV, text,
// Python).
enum class ImpactKind {
  kFacet,   // "facet": the facet impact map (the base lands flat)
  kEdge,    // "edge": the edge impact map (a side edge lands)
  kZeno,    // "zeno": switch to edge rocking after accumulating edge impacts
  kRest,    // "rest": the block stops on its base; contact_after is empty, ΔE = −the kinetic energy left
  kUplift,  // "uplift", under ground motion only: rest → rocking about contact_after, or edge → rocking about one
            // of its vertices when the other end's normal force vanishes; ω is continuous and ΔE = 0
};
const char* ToString(ImpactKind kind);
// Reads the string form back; false (and *kind unchanged) for any other text.
bool FromString(std::string_view text, ImpactKind* kind);

struct ImpactRecord {
  double t_s = 0.0;
  ImpactKind kind = ImpactKind::kFacet;
  Contact contact_before;
  Contact contact_after;
  Eigen::Vector3d w_minus_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_plus_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_minus_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_plus_W = Eigen::Vector3d::Zero();
  double tau = 0.0;             // [N·m·s], the τ the map used
  double delta_energy_J = 0.0;  // (26): kinetic energy after minus before
  ImpactStatus status = ImpactStatus::kOk;
};

struct SegmentDiagnostics {
  double t_begin_s = 0.0;
  double t_end_s = 0.0;
  Mode mode;
  double min_normal_force_N = 0.0;   // negative: the no-lift-off assumption failed
  double max_friction_ratio = 0.0;   // largest |F_t| / F_n needed for no slip
  double energy_drift_rel = 0.0;     // |E_end − E_begin| / E_begin, E = kinetic + m g z_C (z_C above ground)
};

// Why a run ended as EndReason::kFailed. For the two impact reasons the impact map's status (infeasible,
// ambiguous, singular; ok when ω⁺ came out non-finite) is that of the failing impact, the last entry of the
// impact log.
enum class FailureReason {
  kNone,            // "none": the run did not fail
  kEdgeImpact,      // "edge_impact": an edge impact map has no solution
  kFacetImpact,     // "facet_impact": a facet impact map has no solution
  kIntegratorStep,  // "integrator_step": the integrator's step size fell below round-off
  kImpactCascade,   // "impact_cascade": too many impacts at one instant without the contact resolving
  kMaxImpacts,      // "max_impacts": more impacts than SimulationOptions::max_impacts
  kEnergyBlowUp,    // "energy_blow_up": the kinetic energy after an impact grows without bound
};
const char* ToString(FailureReason reason);
bool FromString(std::string_view text, FailureReason* value);  // the inverse of ToString

// Samples (t_s, w_B, q_WB, euler_zyx, mode: one entry per sample time up to t_end_s), the impact log, one
// SegmentDiagnostics per continuous segment, and how the run ended.
struct Trajectory {
  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> w_B;
  std::vector<Eigen::Quaterniond> q_WB;    // empty when sample_attitude is false
  std::vector<Eigen::Vector3d> euler_zyx;  // (φz, φy, φx); empty when sample_attitude is false
  std::vector<Mode> mode;
  std::vector<ImpactRecord> impacts;
  std::vector<SegmentDiagnostics> segments;
  double t_end_s = 0.0;
  // The state at t_end_s, which usually falls between two samples (the attitude at which the block overturned,
  // for instance). Not written to files: the last sample and the impact log describe the end there.
  Eigen::Quaterniond end_q_WB = Eigen::Quaterniond::Identity();
  Eigen::Vector3d end_w_B = Eigen::Vector3d::Zero();
  EndReason end_reason = EndReason::kFailed;
  FailureReason failure = FailureReason::kNone;  // why a Failed run failed
  std::string message;                           // the same in words, with times and contacts
  // The largest |w_B| [rad/s] that a rest (or, under ground motion, a switch to rocking from zero relative
  // velocity) set to zero: a Zeno sequence's last post-impact rate, or what rest_energy_height ended.
  double max_discarded_rate_rad_s = 0.0;
  double wall_time_s = 0.0;  // of Simulate() itself
  long num_steps = 0;        // accepted integrator steps over all segments
  long num_evaluations = 0;  // right-hand-side evaluations over all segments
  long num_guard_evaluations = 0;  // guards evaluated on the dense output to locate events (integrated segments)

  // Every field as a default-constructed Trajectory has it, with the vectors' storage kept (for SimulateInto).
  void Clear();
};

// Throws InvalidArgument for invalid options, parameters or initial state; numerical trouble during the run
// is EndReason::kFailed with a message, never an exception or a NaN.
Trajectory Simulate(const Block& block, const ModelParameters& params, const SimulationOptions& options);
// The same run into *out (cleared first), whose vectors keep their storage from run to run: for callers that run
// many simulations one after another, such as a fit (~6,000 runs). The trajectory is that of Simulate(), bit for bit.
void SimulateInto(const Block& block, const ModelParameters& params, const SimulationOptions& options,
                  Trajectory* out);

// How a run under ground motion starts: flat at rest on the table (the usual case), or as the free run does
// (the release at α on the release edge, or options.initial_state).
enum class GroundStart { kFlatAtRest, kAsOptions };
const char* ToString(GroundStart start);                     // "flat", "tilted" (as respond --start)
bool FromString(std::string_view text, GroundStart* value);  // the inverse of ToString

// The same hybrid simulation in the frame of a table that moves with `ground` (ground_motion.hpp): the inertial
// force −m a_g acts at the COM, impacts act on velocities relative to the table, the flat block at rest starts
// to rock when the moment of gravity and inertial force about a base edge changes sign (ground_uplift.hpp),
// and a rest is not final: the block may uplift again. The run ends with `lift_off` when g + a_z ≤ 0. Use
// StopCondition::kTMax (run to t_max) or kRest/kOverturned (end at rest once no later uplift is possible
// before t_max). With a zero ground motion the motion is that of Simulate() above.
Trajectory Simulate(const Block& block, const ModelParameters& params, const SimulationOptions& options,
                    const GroundMotion& ground, GroundStart start);

}  // namespace rockfit::core
