// The hybrid simulator against closed forms and defining equations (docs/design.md §4, §12): the release time
// T(α), planar motion from (6), energy per segment, mirror symmetry, ΔE ≤ 0 within the bounds, Zeno switches
// that keep the angular momentum about the edge, events inside one step, overturning, and robustness.
#include "rockfit/core/simulator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "dop853.hpp"
#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/planar_rocking.hpp"
#include "rockfit/core/vertex_dynamics.hpp"
#include "simulation_cases.hpp"

namespace rockfit::core {
namespace {

constexpr double kG = kStandardGravity;
// docs/design.md §4 accuracy targets.
constexpr double kReleaseTimeTol_s = 1e-9;
constexpr double kPlanarTimeTol_s = 1e-8;
constexpr double kEnergyDriftTol = 1e-9;
// No vertex may end below the ground by more than this [m] (docs/design.md §12).
constexpr double kGroundTol_m = 1e-9;

using testing::Fig14Block;
using testing::Fig14Parameters;
using testing::WithinBoundsParameters;

// Heights of the four base vertices above the contact of `mode` (which is on the ground).
std::array<double, 4> VertexHeights(const Block& block, const Eigen::Quaterniond& q_WB, const Mode& mode) {
  const Eigen::Matrix3d R = q_WB.toRotationMatrix();
  const double ground = (R * block.p_BV_B(mode.contact.first)).z();
  std::array<double, 4> heights{};
  for (int k = 1; k <= 4; ++k) heights[k - 1] = (R * block.p_BV_B(k)).z() - ground;
  return heights;
}

double MinVertexHeight(const Block& block, const Trajectory& tr) {
  double lowest = 0.0;
  for (std::size_t i = 0; i < tr.t_s.size(); ++i) {
    if (tr.mode[i].kind != ModeKind::kEdge && tr.mode[i].kind != ModeKind::kVertex) continue;
    for (double z : VertexHeights(block, tr.q_WB[i], tr.mode[i])) lowest = std::min(lowest, z);
  }
  return lowest;
}

std::vector<ImpactRecord> OfKind(const Trajectory& tr, ImpactKind kind) {
  std::vector<ImpactRecord> out;
  for (const auto& r : tr.impacts) {
    if (r.kind == kind) out.push_back(r);
  }
  return out;
}

TEST(Simulator, FirstFacetImpactIsAtTheQuadratureTimeT) {
  const Block block = Fig14Block();
  const PlanarRocker rocker = PlanarRockerAboutEdge(block, 1, 2, kG);
  SimulationOptions options;
  options.stop = StopCondition::kTMax;
  for (double alpha = 0.02; alpha <= 0.24 + 1e-12; alpha += 0.02) {
    ModelParameters params = Fig14Parameters();
    params.alpha_rad = alpha;
    options.t_max_s = FallTime(rocker, alpha) + 1e-3;  // just past the first impact
    const Trajectory tr = Simulate(block, params, options);
    ASSERT_FALSE(tr.impacts.empty()) << "α = " << alpha;
    const ImpactRecord& first = tr.impacts.front();
    EXPECT_EQ(first.kind, ImpactKind::kFacet);
    EXPECT_NEAR(first.t_s, FallTime(rocker, alpha), kReleaseTimeTol_s) << "α = " << alpha;
    // The landing rate follows from energy.
    EXPECT_NEAR(first.w_minus_B.y(), LandingRate(rocker, alpha), 1e-9 * LandingRate(rocker, alpha)) << "α = " << alpha;
  }
}

TEST(Simulator, ReleaseFallsBackWithPositiveOmegaY) {
  // docs/design.md §2: on edge V1V2 with the +x side lifted (φy = −α), falling back turns with w_B = (0, +ω, 0).
  const Trajectory tr = Simulate(Fig14Block(), Fig14Parameters(), SimulationOptions{});
  ASSERT_GT(tr.t_s.size(), 10u);
  EXPECT_NEAR(tr.euler_zyx[0][1], -0.197, 1e-15);
  EXPECT_EQ(tr.w_B[0], Eigen::Vector3d::Zero());
  for (std::size_t i = 1; tr.t_s[i] < tr.impacts.front().t_s; ++i) {
    EXPECT_GT(tr.w_B[i].y(), 0.0);
    EXPECT_EQ(tr.w_B[i].x(), 0.0);
    EXPECT_EQ(tr.w_B[i].z(), 0.0);
    EXPECT_EQ(tr.mode[i].ToString(), "V1V2");
  }
}

TEST(Simulator, EnergyIsConservedWithinEverySegment) {
  const Block block = Fig14Block();
  for (const ModelParameters& params : {Fig14Parameters(), WithinBoundsParameters()}) {
    // Past phase 4 of the Fig. 14 case and past the first Zeno switch of the other.
    SimulationOptions options;
    options.stop = StopCondition::kTMax;
    options.t_max_s = 1.2;
    const Trajectory tr = Simulate(block, params, options);
    ASSERT_GT(tr.segments.size(), 3u);
    for (const SegmentDiagnostics& s : tr.segments) {
      EXPECT_LE(s.energy_drift_rel, kEnergyDriftTol) << s.mode.ToString() << " from t = " << s.t_begin_s;
    }
    // Independently of the simulator's own bookkeeping: the energy of the sampled states, ½ wᵀJ_P w + m g z_C
    // about the contact, is constant between impacts.
    double energy_begin = 0.0;
    std::size_t segment_start = 0;
    for (std::size_t i = 0; i < tr.t_s.size(); ++i) {
      const Mode& mode = tr.mode[i];
      if (mode.kind != ModeKind::kVertex && mode.kind != ModeKind::kEdge) continue;
      const Eigen::Vector3d p_P = mode.kind == ModeKind::kVertex
                                      ? block.p_BV_B(mode.contact.first)
                                      : 0.5 * (block.p_BV_B(mode.contact.first) + block.p_BV_B(mode.contact.second));
      const Eigen::Matrix3d J_P = InertiaAboutPoint(block, p_P);
      const Eigen::Vector3d c_W = tr.q_WB[i] * (block.p_BC_B() - p_P);
      const double energy = 0.5 * tr.w_B[i].dot(J_P * tr.w_B[i]) + block.mass() * kG * c_W.z();
      const bool new_segment = i == 0 || tr.mode[i - 1] != mode ||
                               std::any_of(tr.impacts.begin(), tr.impacts.end(), [&](const ImpactRecord& r) {
                                 return r.t_s > tr.t_s[i - 1] && r.t_s <= tr.t_s[i];
                               });
      if (new_segment) {
        energy_begin = energy;
        segment_start = i;
      }
      EXPECT_NEAR(energy / energy_begin - 1.0, 0.0, kEnergyDriftTol) << "sample " << i << " (segment from " << segment_start << ")";
    }
  }
}

// Planar AVRF (6) of Chatzis et al., written out here: r = (θ + mh² − mλb²)/(θ + mh² + mλb²).
double ChatzisAvrf(const Block& block, double lambda) {
  const double theta = block.inertia_C_B()(1, 1);
  const double m = block.mass();
  const double h2 = block.h() * block.h();
  const double b2 = block.b1() * block.b1();
  return (theta + m * h2 - m * lambda * b2) / (theta + m * h2 + m * lambda * b2);
}

TEST(Simulator, PlanarMotionFollowsTheAvrfAndTheQuadratureAtEveryReturn) {
  // λ_lat = 0: every facet impact maps ω⁻ to r·ω⁻ with r from (6) (λ = λ_lon), the block rocks about the
  // opposite edge to the amplitude α_n given by energy and returns after 2 T(α_n).
  const Block block = Fig14Block();
  ModelParameters params;
  params.alpha_rad = 0.2;
  params.lambda_lat = 0.0;
  params.lambda_lon = 0.5;
  const double r = ChatzisAvrf(block, params.lambda_lon);
  const PlanarRocker rocker = PlanarRockerAboutEdge(block, 1, 2, kG);

  // Expected facet-impact times, landing rates and amplitudes.
  std::vector<double> times{FallTime(rocker, params.alpha_rad)};
  std::vector<double> rates{LandingRate(rocker, params.alpha_rad)};
  std::vector<double> amplitudes;
  std::vector<double> apex_times;
  while (times.size() < 40) {
    const double rate_after = r * rates.back();
    const double amplitude = *AmplitudeFromLandingRate(rocker, rate_after);
    const double half = FallTime(rocker, amplitude);
    amplitudes.push_back(amplitude);
    apex_times.push_back(times.back() + half);
    times.push_back(times.back() + 2.0 * half);
    rates.push_back(rate_after);
  }

  SimulationOptions options;
  options.stop = StopCondition::kTMax;
  options.t_max_s = times.back() + 1e-6;
  options.sample_times_s = apex_times;
  const Trajectory tr = Simulate(block, params, options);
  ASSERT_EQ(tr.end_reason, EndReason::kTMax) << tr.message;
  const std::vector<ImpactRecord> facets = OfKind(tr, ImpactKind::kFacet);
  ASSERT_EQ(facets.size(), times.size());
  EXPECT_EQ(facets.size(), tr.impacts.size());  // nothing but facet impacts
  for (std::size_t n = 0; n < times.size(); ++n) {
    EXPECT_NEAR(facets[n].t_s, times[n], kPlanarTimeTol_s) << "facet impact " << n;
    EXPECT_NEAR(std::abs(facets[n].w_minus_B.y()), rates[n], 1e-9 * rates[n]) << "facet impact " << n;
    EXPECT_NEAR(std::abs(facets[n].w_plus_B.y()), r * rates[n], 1e-9 * rates[n]) << "facet impact " << n;
    EXPECT_EQ(facets[n].contact_after.ToString(), n % 2 == 0 ? "V3V4" : "V1V2");
  }
  // At the apex between two impacts the block is at rest, tilted by the amplitude.
  ASSERT_EQ(tr.t_s.size(), apex_times.size());
  for (std::size_t n = 0; n < apex_times.size(); ++n) {
    EXPECT_NEAR(std::abs(tr.euler_zyx[n][1]), amplitudes[n], 1e-9) << "apex " << n;
    EXPECT_NEAR(tr.w_B[n].norm(), 0.0, 1e-8) << "apex " << n;
  }
  // Planar: no rotation about x or z, ever.
  const Trajectory dense = Simulate(block, params, SimulationOptions{});
  for (std::size_t i = 0; i < dense.t_s.size(); ++i) {
    EXPECT_EQ(dense.w_B[i].x(), 0.0);
    EXPECT_EQ(dense.w_B[i].z(), 0.0);
    EXPECT_NEAR(dense.euler_zyx[i][0], 0.0, 1e-15);
    EXPECT_NEAR(dense.euler_zyx[i][2], 0.0, 1e-15);
  }
}

TEST(Simulator, PlanarMotionEndsInRest) {
  ModelParameters params;
  params.alpha_rad = 0.2;
  params.lambda_lat = 0.0;
  params.lambda_lon = 0.7;
  SimulationOptions options;
  options.stop = StopCondition::kRest;
  const Trajectory tr = Simulate(Fig14Block(), params, options);
  EXPECT_EQ(tr.end_reason, EndReason::kRest) << tr.message;
  ASSERT_FALSE(tr.impacts.empty());
  EXPECT_EQ(tr.impacts.back().kind, ImpactKind::kRest);
  EXPECT_LT(tr.t_end_s, options.t_max_s);
  // Facet impacts accumulate (Zeno) before the rest: the last interval is below zeno_dt, or the kinetic
  // energy left (the rest record's −ΔE) cannot lift the COM by rest_energy_height.
  const std::vector<ImpactRecord> facets = OfKind(tr, ImpactKind::kFacet);
  ASSERT_GE(facets.size(), 3u);
  const double last_interval = facets[facets.size() - 1].t_s - facets[facets.size() - 2].t_s;
  const double kinetic_left = -tr.impacts.back().delta_energy_J;
  const Block block = Fig14Block();
  EXPECT_TRUE(last_interval < options.zeno_dt_s ||
              kinetic_left < block.mass() * kG * options.rest_energy_height_m)
      << "last interval " << last_interval << " s, kinetic energy " << kinetic_left << " J";
  // With stop = t_max the block stays at rest until t_max.
  options.stop = StopCondition::kTMax;
  options.t_max_s = tr.t_end_s + 0.5;
  const Trajectory held = Simulate(Fig14Block(), params, options);
  EXPECT_EQ(held.end_reason, EndReason::kTMax);
  EXPECT_EQ(held.mode.back().kind, ModeKind::kRest);
  EXPECT_EQ(held.w_B.back(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(held.t_s.back(), options.t_max_s, 1.0 / options.rate_hz);
}

int Mirror(int vertex) {
  // y → −y swaps V1 ↔ V2 and V3 ↔ V4.
  static constexpr std::array<int, 5> kMirror = {0, 2, 1, 4, 3};
  return kMirror[vertex];
}

TEST(Simulator, MirrorSymmetryLambdaLatToMinusLambdaLatGivesYToMinusY) {
  const Block block = Fig14Block();
  ModelParameters plus = WithinBoundsParameters();
  ModelParameters minus = plus;
  minus.lambda_lat = -plus.lambda_lat;
  SimulationOptions options;
  options.stop = StopCondition::kTMax;
  options.t_max_s = 1.2;
  const Trajectory a = Simulate(block, plus, options);
  const Trajectory b = Simulate(block, minus, options);
  ASSERT_EQ(a.t_s.size(), b.t_s.size());
  ASSERT_EQ(a.impacts.size(), b.impacts.size());
  ASSERT_GT(OfKind(a, ImpactKind::kEdge).size(), 2u);
  // Under y → −y an angular velocity (axial vector) maps (x, y, z) → (−x, y, −z); so do (φx, φy, φz).
  constexpr double kMirrorTol = 1e-8;  // two runs with different round-off through many impacts
  for (std::size_t i = 0; i < a.t_s.size(); ++i) {
    EXPECT_NEAR(a.w_B[i].x(), -b.w_B[i].x(), kMirrorTol) << "t = " << a.t_s[i];
    EXPECT_NEAR(a.w_B[i].y(), b.w_B[i].y(), kMirrorTol) << "t = " << a.t_s[i];
    EXPECT_NEAR(a.w_B[i].z(), -b.w_B[i].z(), kMirrorTol) << "t = " << a.t_s[i];
    EXPECT_NEAR(a.euler_zyx[i][0], -b.euler_zyx[i][0], kMirrorTol);
    EXPECT_NEAR(a.euler_zyx[i][1], b.euler_zyx[i][1], kMirrorTol);
    EXPECT_NEAR(a.euler_zyx[i][2], -b.euler_zyx[i][2], kMirrorTol);
  }
  for (std::size_t n = 0; n < a.impacts.size(); ++n) {
    EXPECT_NEAR(a.impacts[n].t_s, b.impacts[n].t_s, kMirrorTol);
    EXPECT_EQ(a.impacts[n].kind, b.impacts[n].kind);
    const Contact& ca = a.impacts[n].contact_after;
    const Contact& cb = b.impacts[n].contact_after;
    if (ca.is_vertex()) {
      EXPECT_EQ(Mirror(ca.first), cb.first) << "impact " << n;
    } else if (ca.is_edge()) {
      EXPECT_EQ(Contact::Edge(Mirror(ca.first), Mirror(ca.second)), cb) << "impact " << n;
    }
  }
}

TEST(Simulator, ImpactsWithinTheBoundsNeverAddEnergy) {
  const Block block = Fig14Block();
  std::mt19937 rng(31337);
  std::uniform_real_distribution<double> unit(0.0, 1.0), signed_unit(-1.0, 1.0), tilt(0.05, 0.23);
  SimulationOptions options;
  options.stop = StopCondition::kTMax;
  options.t_max_s = 1.0;
  options.rate_hz = 50.0;
  std::vector<ModelParameters> cases{WithinBoundsParameters()};
  for (int i = 0; i < 5; ++i) {
    ModelParameters p;
    p.alpha_rad = tilt(rng);
    p.lambda = unit(rng);
    p.lambda_lat = signed_unit(rng);
    p.lambda_lon = unit(rng);
    cases.push_back(p);
  }
  for (const ModelParameters& p : cases) {
    const Trajectory tr = Simulate(block, p, options);
    ASSERT_NE(tr.end_reason, EndReason::kFailed) << tr.message;
    for (const ImpactRecord& r : tr.impacts) {
      const double scale = 0.5 * InertiaAboutPoint(block, block.p_BV_B(1)).norm() * r.w_minus_B.squaredNorm();
      EXPECT_LE(r.delta_energy_J, 1e-12 * scale) << ToString(r.kind) << " at t = " << r.t_s << " (λ = " << p.lambda
                                                 << ", λ_lat = " << p.lambda_lat << ", λ_lon = " << p.lambda_lon << ")";
    }
  }
}

TEST(Simulator, ZenoSwitchKeepsTheAngularMomentumAboutTheEdge) {
  const Block block = Fig14Block();
  SimulationOptions options;
  options.stop = StopCondition::kTMax;
  options.t_max_s = 0.8;  // the first Zeno switch of this case is at 0.78 s
  const Trajectory tr = Simulate(block, WithinBoundsParameters(), options);
  const std::vector<ImpactRecord> zenos = OfKind(tr, ImpactKind::kZeno);
  ASSERT_FALSE(zenos.empty()) << "the within-bounds case runs into a Zeno sequence";
  for (const ImpactRecord& z : zenos) {
    ASSERT_TRUE(z.contact_before.is_vertex());
    ASSERT_TRUE(z.contact_after.is_edge());
    // e·(J_a ω⁻) = J_e ψ̇ with e the edge direction and J_a the inertia about the pivot V_a.
    const Eigen::Vector3d e = (block.p_BV_B(z.contact_after.second) - block.p_BV_B(z.contact_after.first)).normalized();
    const Eigen::Matrix3d J_a = InertiaAboutPoint(block, block.p_BV_B(z.contact_before.first));
    EXPECT_NEAR(e.dot(J_a * z.w_minus_B), e.dot(J_a * z.w_plus_B), 1e-12 * (J_a * z.w_minus_B).norm());
    // After the switch the block turns about the edge only.
    EXPECT_NEAR((z.w_plus_B - z.w_plus_B.dot(e) * e).norm(), 0.0, 1e-14);
    EXPECT_LE(z.delta_energy_J, 0.0);
  }
  // The intervals of the edge impacts before the first switch shrink.
  const double t_zeno = zenos.front().t_s;
  std::vector<double> edge_times;
  for (const ImpactRecord& r : tr.impacts) {
    if (r.kind == ImpactKind::kEdge && r.t_s <= t_zeno) edge_times.push_back(r.t_s);
  }
  ASSERT_GE(edge_times.size(), 3u);
  const std::size_t n = edge_times.size();
  EXPECT_LT(edge_times[n - 1] - edge_times[n - 2], options.zeno_dt_s);
  EXPECT_LT(edge_times[n - 1] - edge_times[n - 2], edge_times[n - 2] - edge_times[n - 3]);
}

TEST(Simulator, EdgeContactAfterAnEdgeImpactContinuesAsEdgeRocking) {
  // λ far above (25) reverses the rocking at an edge impact; V_b then stays down and the block keeps edge
  // contact V_aV_b (docs/design.md §3), turning about the edge with the angular momentum about the edge line.
  const Block block = Fig14Block();
  ModelParameters params = WithinBoundsParameters();
  params.lambda = 40.0;
  SimulationOptions options;
  options.rate_hz = 1000.0;
  const Trajectory tr = Simulate(block, params, options);
  ASSERT_EQ(tr.end_reason, EndReason::kPhase4) << tr.message;
  ASSERT_GE(tr.impacts.size(), 2u);
  const ImpactRecord& edge = tr.impacts[1];
  EXPECT_EQ(edge.kind, ImpactKind::kEdge);
  ASSERT_TRUE(edge.contact_after.is_edge());
  const Eigen::Vector3d e = (block.p_BV_B(edge.contact_after.second) - block.p_BV_B(edge.contact_after.first)).normalized();
  EXPECT_NEAR((edge.w_plus_B - edge.w_plus_B.dot(e) * e).norm(), 0.0, 1e-14);
  EXPECT_LE(edge.delta_energy_J, 0.0);
  for (std::size_t i = 0; i < tr.t_s.size(); ++i) {
    if (tr.t_s[i] >= edge.t_s && tr.t_s[i] < tr.impacts[2].t_s) {
      EXPECT_EQ(tr.mode[i].contact, edge.contact_after);
      EXPECT_NEAR((tr.w_B[i] - tr.w_B[i].dot(e) * e).norm(), 0.0, 1e-14);
    }
  }
}

TEST(Simulator, NoVertexEverEndsBelowTheGround) {
  const Block block = Fig14Block();
  SimulationOptions options;
  options.stop = StopCondition::kTMax;
  options.t_max_s = 1.2;
  options.rate_hz = 1000.0;
  for (const ModelParameters& params : {Fig14Parameters(), WithinBoundsParameters()}) {
    const Trajectory tr = Simulate(block, params, options);
    EXPECT_GE(MinVertexHeight(block, tr), -kGroundTol_m);
  }
}

// Rocking about V3, tilted about the edge V3V4 and spinning so that V4, 1 µm above the ground, dips below it
// for about 0.8 ms and comes back: a lift-off-and-land inside one integrator step.
InitialState DippingState(const Block& block) {
  const double beta = 0.15;  // tilt about the edge V3V4 (the −x side lifted)
  Eigen::Quaterniond q(Eigen::AngleAxisd(beta, Eigen::Vector3d::UnitY()));
  const double lift = 1e-6 / (2.0 * block.b2());  // raise V4 by about 1 µm
  q = Eigen::Quaterniond(Eigen::AngleAxisd(-lift, q * Eigen::Vector3d::UnitX())) * q;
  InitialState s;
  s.contact = Contact::Vertex(3);
  s.q_WB = q;
  s.w_B = q.conjugate() * Eigen::Vector3d(0.1, -10.0, 10.0);
  return s;
}

TEST(Simulator, LiftOffAndLandingWithinOneStepIsNotMissed) {
  const Block block = Block::FromDensity(0.05, 0.04, 0.2, 2692.0);
  const InitialState start = DippingState(block);
  const VertexDynamics dynamics(block, 3, kG);
  const VertexDynamics::State y0 = VertexDynamics::MakeState(start.q_WB, start.w_B);

  // Reference: the first time V4 goes below the ground, from a fixed-step RK4 with 1 µs steps.
  double t_down = -1.0, t_up = -1.0;
  {
    VertexDynamics::State y = y0;
    const double dt = 1e-6;
    double z_prev = dynamics.PointHeight(y, block.p_BV_B(4));
    for (int i = 1; i < 5000 && t_up < 0.0; ++i) {
      VertexDynamics::State k1, k2, k3, k4;
      dynamics(0.0, y, k1);
      dynamics(0.0, y + 0.5 * dt * k1, k2);
      dynamics(0.0, y + 0.5 * dt * k2, k3);
      dynamics(0.0, y + dt * k3, k4);
      y += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      const double z = dynamics.PointHeight(y, block.p_BV_B(4));
      if (z < 0.0 && z_prev >= 0.0 && t_down < 0.0) t_down = (i - 1 + z_prev / (z_prev - z)) * dt;
      if (z >= 0.0 && z_prev < 0.0 && t_down >= 0.0) t_up = i * dt;
      z_prev = z;
    }
  }
  ASSERT_GT(t_down, 0.0);
  ASSERT_GT(t_up, t_down);

  SimulationOptions options;
  options.initial_state = start;
  options.rel_tol = 1e-6;
  options.abs_tol = 1e-8;
  options.max_step_s = 0.05;
  options.stop = StopCondition::kTMax;
  options.t_max_s = 0.01;
  // The case is real: with these tolerances the first integrator step spans the whole dip.
  {
    Dop853Options integrator_options;
    integrator_options.rel_tol = options.rel_tol;
    integrator_options.abs_tol = options.abs_tol;
    integrator_options.max_step = options.max_step_s;
    Dop853<7> integrator(integrator_options);
    integrator.Reset(dynamics, 0.0, y0);
    ASSERT_EQ(integrator.Step(dynamics, 1.0), StepStatus::kOk);
    ASSERT_GT(integrator.t(), t_up) << "the first step must jump over the dip for this test to mean something";
    EXPECT_GT(dynamics.PointHeight(integrator.y(), block.p_BV_B(4)), 0.0);
  }
  const Trajectory tr = Simulate(block, ModelParameters{}, options);
  ASSERT_FALSE(tr.impacts.empty());
  EXPECT_EQ(tr.impacts.front().kind, ImpactKind::kEdge);
  EXPECT_EQ(tr.impacts.front().contact_before.ToString(), "V3");
  EXPECT_NEAR(tr.impacts.front().t_s, t_down, 1e-7);
}

// Released about V1V2 (or given an outward push), the block passes the balance point θ_c and overturns.
TEST(Simulator, OverturningIsDetectedBeyondTheCriticalAngle) {
  const Block block = Fig14Block();
  const EdgeDynamics edge(block, 1, 2, kG);
  const double theta_c = edge.critical_angle_rad();
  ModelParameters params;
  params.alpha_rad = theta_c + 0.01;
  Trajectory tr = Simulate(block, params, SimulationOptions{});
  EXPECT_EQ(tr.end_reason, EndReason::kOverturned);
  EXPECT_EQ(tr.t_end_s, 0.0);
  params.alpha_rad = theta_c - 0.01;  // just inside: it falls back
  tr = Simulate(block, params, SimulationOptions{});
  EXPECT_EQ(tr.end_reason, EndReason::kPhase4);

  // Tilted by ψ0 and pushed outwards with ψ̇0: energy gives ψ̇(ψ)² = ψ̇0² − K[cos(θ_c − ψ0) − cos(θ_c − ψ)]...
  // with K = 2mgR/J; the time to reach θ_c is ∫ dψ/ψ̇ (Gauss–Legendre on a smooth integrand).
  const double psi0 = 0.1;
  const double K = 2.0 * block.mass() * kG * edge.arm_m() / edge.inertia_kg_m2();
  const double rate0 = 1.05 * std::sqrt(K * (1.0 - std::cos(theta_c - psi0)));
  const auto rate = [&](double psi) {
    return std::sqrt(rate0 * rate0 - K * (std::cos(theta_c - psi) - std::cos(theta_c - psi0)));
  };
  static constexpr std::array<double, 5> kNodes = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                                   0.9061798459386640};
  static constexpr std::array<double, 5> kWeights = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                                     0.4786286704993665, 0.2369268850561891};
  double t_over = 0.0;
  const int panels = 200;
  for (int p = 0; p < panels; ++p) {
    const double a = psi0 + (theta_c - psi0) * p / panels;
    const double half = 0.5 * (theta_c - psi0) / panels;
    for (int i = 0; i < 5; ++i) t_over += half * kWeights[i] / rate(a + half * (1.0 + kNodes[i]));
  }
  SimulationOptions options;
  InitialState s;
  s.contact = Contact::Edge(1, 2);
  s.q_WB = edge.Tilt(psi0);
  s.w_B = rate0 * edge.axis_B();
  options.initial_state = s;
  tr = Simulate(block, params, options);
  EXPECT_EQ(tr.end_reason, EndReason::kOverturned);
  EXPECT_NEAR(tr.t_end_s, t_over, 1e-9);
}

TEST(Simulator, LateralOverturningFromVertexRockingIsDetected) {
  // A strong lateral spin about V3 carries the COM out over the side edge V2V3.
  const Block block = Fig14Block();
  SimulationOptions options;
  InitialState s;
  s.contact = Contact::Vertex(3);
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  s.w_B = Eigen::Vector3d(-8.0, 0.0, 0.0);
  options.initial_state = s;
  const Trajectory tr = Simulate(block, ModelParameters{}, options);
  EXPECT_EQ(tr.end_reason, EndReason::kOverturned) << tr.message;
}

TEST(Simulator, RandomParameterSetsAlwaysEndWithAStatus) {
  const Block block = Fig14Block();
  std::mt19937 rng(2021);
  std::uniform_real_distribution<double> tilt(0.01, 0.3), lambda(-4.0, 6.0), lat(-8.0, 8.0), lon(-3.0, 5.0),
      tau(-0.02, 0.02);
  SimulationOptions options;
  options.stop = StopCondition::kRest;
  options.t_max_s = 1.5;
  options.rate_hz = 100.0;
  // A fixed τ_edge can sustain a spinning wobble with an impact every few tens of µs until t_max; this bound
  // ends such runs (as failed) quickly and keeps the test fast.
  options.max_impacts = 300;
  for (int i = 0; i < 24; ++i) {
    ModelParameters p;
    p.alpha_rad = tilt(rng);
    p.lambda = lambda(rng);
    p.lambda_lat = lat(rng);
    p.lambda_lon = lon(rng);
    p.tau_edge = i % 3 == 0 ? tau(rng) : 0.0;
    p.facet_tau_rule = i % 2 == 0 ? FacetTauRule::kNoSpin : FacetTauRule::kFixed;
    const Trajectory tr = Simulate(block, p, options);
    const std::string where = "case " + std::to_string(i) + ": " + ToString(tr.end_reason) + " " + tr.message;
    EXPECT_LE(tr.t_end_s, options.t_max_s) << where;
    EXPECT_TRUE(std::isfinite(tr.t_end_s)) << where;
    if (tr.end_reason == EndReason::kFailed) {
      EXPECT_FALSE(tr.message.empty()) << where;
      EXPECT_NE(tr.failure, FailureReason::kNone) << where;
    } else {
      EXPECT_EQ(tr.failure, FailureReason::kNone) << where;
    }
    for (std::size_t k = 0; k < tr.t_s.size(); ++k) {
      ASSERT_TRUE(tr.w_B[k].allFinite()) << where;
      ASSERT_TRUE(tr.q_WB[k].coeffs().allFinite()) << where;
      ASSERT_TRUE(tr.euler_zyx[k].allFinite()) << where;
      if (k > 0) {
        ASSERT_GT(tr.t_s[k], tr.t_s[k - 1]) << where;
      }
    }
    for (const ImpactRecord& r : tr.impacts) {
      ASSERT_TRUE(r.w_plus_B.allFinite() && std::isfinite(r.delta_energy_J)) << where;
    }
    EXPECT_GE(MinVertexHeight(block, tr), -kGroundTol_m) << where;
  }
}

TEST(Simulator, StopsAtPhase4OnTheFirstReleaseSideImpactAfterTheFirstFacetImpact) {
  const Trajectory tr = Simulate(Fig14Block(), Fig14Parameters(), SimulationOptions{});
  ASSERT_EQ(tr.end_reason, EndReason::kPhase4) << tr.message;
  ASSERT_GE(tr.impacts.size(), 2u);
  EXPECT_EQ(tr.impacts.front().kind, ImpactKind::kFacet);
  EXPECT_EQ(tr.impacts.front().contact_before.ToString(), "V1V2");
  const auto touches_release_side = [](const ImpactRecord& r) {
    const Contact& c = r.contact_after;
    return c.first == 1 || c.first == 2 || c.second == 1 || c.second == 2;
  };
  for (std::size_t n = 1; n + 1 < tr.impacts.size(); ++n) {
    EXPECT_FALSE(touches_release_side(tr.impacts[n])) << "impact " << n;
  }
  EXPECT_TRUE(touches_release_side(tr.impacts.back()));
  EXPECT_EQ(tr.t_end_s, tr.impacts.back().t_s);
  EXPECT_LE(tr.t_s.back(), tr.t_end_s);
}

TEST(Simulator, SampleAtAnImpactInstantIsThePostImpactValue) {
  const Block block = Fig14Block();
  const Trajectory first = Simulate(block, Fig14Parameters(), SimulationOptions{});
  ASSERT_GE(first.impacts.size(), 3u);
  const ImpactRecord& impact = first.impacts[2];
  SimulationOptions options;
  options.sample_times_s = {0.1, impact.t_s, impact.t_s + 0.01};
  const Trajectory tr = Simulate(block, Fig14Parameters(), options);
  ASSERT_EQ(tr.t_s.size(), 3u);
  EXPECT_NEAR((tr.w_B[1] - impact.w_plus_B).norm(), 0.0, 1e-12);
  EXPECT_EQ(tr.mode[1].contact, impact.contact_after);
}

TEST(Simulator, SamplesAreAtKOverRateAndTheCheapModeGivesTheSameAngularVelocity) {
  const Block block = Fig14Block();
  SimulationOptions options;
  options.rate_hz = 256.0;
  const Trajectory full = Simulate(block, Fig14Parameters(), options);
  for (std::size_t k = 0; k < full.t_s.size(); ++k) EXPECT_EQ(full.t_s[k], static_cast<double>(k) / 256.0);
  options.sample_attitude = false;
  const Trajectory cheap = Simulate(block, Fig14Parameters(), options);
  EXPECT_TRUE(cheap.q_WB.empty());
  EXPECT_TRUE(cheap.euler_zyx.empty());
  ASSERT_EQ(cheap.t_s.size(), full.t_s.size());
  for (std::size_t k = 0; k < full.t_s.size(); ++k) EXPECT_EQ(cheap.w_B[k], full.w_B[k]);
}

TEST(Simulator, SampleTimesBeforeTheReleaseGiveTheBlockHeldAtRest) {
  SimulationOptions options;
  options.sample_times_s = {-0.5, -0.01, 0.0, 0.05};
  const Trajectory tr = Simulate(Fig14Block(), Fig14Parameters(), options);
  ASSERT_EQ(tr.t_s.size(), 4u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(tr.w_B[k], Eigen::Vector3d::Zero());
    EXPECT_NEAR(tr.euler_zyx[k][1], -0.197, 1e-15);
  }
  EXPECT_GT(tr.w_B[3].y(), 0.0);
}

TEST(Simulator, ReleaseAboutAnotherEdgeUsesThatEdgesGeometry) {
  const Block block = Fig14Block();
  SimulationOptions options;
  options.release_edge_first = 2;
  options.release_edge_second = 3;
  ModelParameters params = WithinBoundsParameters();
  params.alpha_rad = 0.1;
  const Trajectory tr = Simulate(block, params, options);
  ASSERT_FALSE(tr.impacts.empty());
  EXPECT_EQ(tr.impacts.front().contact_before.ToString(), "V2V3");
  EXPECT_NEAR(tr.impacts.front().t_s, FallTime(PlanarRockerAboutEdge(block, 2, 3, kG), 0.1), kReleaseTimeTol_s);
  // V2V3 lies along +x at y = +b2: the −y side is lifted by a turn about −x, so falling back turns about +x.
  EXPECT_GT(tr.impacts.front().w_minus_B.x(), 0.0);
  EXPECT_NEAR(tr.impacts.front().w_minus_B.y(), 0.0, 1e-15);
}

TEST(Simulator, InvalidOptionsAndParametersAreRejectedWithAMessage) {
  const Block block = Fig14Block();
  SimulationOptions options;
  options.rate_hz = 0.0;
  EXPECT_THROW(Simulate(block, ModelParameters{}, options), InvalidArgument);
  options = SimulationOptions{};
  options.release_edge_second = 3;
  EXPECT_THROW(Simulate(block, ModelParameters{}, options), InvalidArgument);
  options = SimulationOptions{};
  options.sample_times_s = {0.2, 0.1};
  EXPECT_THROW(Simulate(block, ModelParameters{}, options), InvalidArgument);
  ModelParameters params;
  params.alpha_rad = -0.1;
  EXPECT_THROW(Simulate(block, params, SimulationOptions{}), InvalidArgument);
  params = ModelParameters{};
  params.lambda = std::nan("");
  EXPECT_THROW(Simulate(block, params, SimulationOptions{}), InvalidArgument);
  // An initial state with a vertex under the ground.
  options = SimulationOptions{};
  InitialState s;
  s.contact = Contact::Vertex(3);
  s.q_WB = Eigen::Quaterniond(Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitY()));
  options.initial_state = s;
  EXPECT_THROW(Simulate(block, ModelParameters{}, options), InvalidArgument);
}

TEST(Simulator, ImpactsThatKeepAddingEnergyEndAsFailedWithAMessage) {
  // λ < 0 makes edge impacts add energy (Sect. 4.8): the block spins up around its corners without bound.
  ModelParameters params;
  params.alpha_rad = 0.027;
  params.lambda = -2.042;
  params.lambda_lat = -6.516;
  params.lambda_lon = 3.136;
  params.facet_tau_rule = FacetTauRule::kFixed;
  SimulationOptions options;
  options.stop = StopCondition::kRest;
  const Trajectory tr = Simulate(Fig14Block(), params, options);
  EXPECT_EQ(tr.end_reason, EndReason::kFailed);
  EXPECT_EQ(tr.failure, FailureReason::kEnergyBlowUp) << ToString(tr.failure);
  EXPECT_NE(tr.message.find("energy"), std::string::npos) << tr.message;
  ASSERT_FALSE(tr.impacts.empty());
  EXPECT_GT(tr.impacts.back().delta_energy_J, 0.0);
}

TEST(Simulator, TooManyImpactsEndAsFailedWithAMessage) {
  SimulationOptions options;
  options.max_impacts = 3;
  options.stop = StopCondition::kRest;
  const Trajectory tr = Simulate(Fig14Block(), Fig14Parameters(), options);
  EXPECT_EQ(tr.end_reason, EndReason::kFailed);
  EXPECT_EQ(tr.failure, FailureReason::kMaxImpacts) << ToString(tr.failure);
  EXPECT_NE(tr.message.find("max_impacts"), std::string::npos) << tr.message;
  EXPECT_EQ(tr.impacts.size(), 3u);
}


// Every field of two trajectories but the wall time, compared exactly.
void ExpectSameTrajectory(const Trajectory& a, const Trajectory& b) {
  EXPECT_EQ(a.t_s, b.t_s);
  EXPECT_EQ(a.w_B, b.w_B);
  ASSERT_EQ(a.q_WB.size(), b.q_WB.size());
  for (std::size_t i = 0; i < a.q_WB.size(); ++i) EXPECT_EQ(a.q_WB[i].coeffs(), b.q_WB[i].coeffs()) << "sample " << i;
  EXPECT_EQ(a.euler_zyx, b.euler_zyx);
  EXPECT_EQ(a.mode, b.mode);
  ASSERT_EQ(a.impacts.size(), b.impacts.size());
  for (std::size_t i = 0; i < a.impacts.size(); ++i) {
    const ImpactRecord& p = a.impacts[i];
    const ImpactRecord& q = b.impacts[i];
    EXPECT_EQ(p.t_s, q.t_s) << "impact " << i;
    EXPECT_EQ(p.kind, q.kind) << "impact " << i;
    EXPECT_EQ(p.contact_before, q.contact_before) << "impact " << i;
    EXPECT_EQ(p.contact_after, q.contact_after) << "impact " << i;
    EXPECT_EQ(p.w_minus_B, q.w_minus_B) << "impact " << i;
    EXPECT_EQ(p.w_plus_B, q.w_plus_B) << "impact " << i;
    EXPECT_EQ(p.w_minus_W, q.w_minus_W) << "impact " << i;
    EXPECT_EQ(p.w_plus_W, q.w_plus_W) << "impact " << i;
    EXPECT_EQ(p.tau, q.tau) << "impact " << i;
    EXPECT_EQ(p.delta_energy_J, q.delta_energy_J) << "impact " << i;
    EXPECT_EQ(p.status, q.status) << "impact " << i;
  }
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].t_begin_s, b.segments[i].t_begin_s) << "segment " << i;
    EXPECT_EQ(a.segments[i].t_end_s, b.segments[i].t_end_s) << "segment " << i;
    EXPECT_EQ(a.segments[i].mode, b.segments[i].mode) << "segment " << i;
    EXPECT_EQ(a.segments[i].min_normal_force_N, b.segments[i].min_normal_force_N) << "segment " << i;
    EXPECT_EQ(a.segments[i].max_friction_ratio, b.segments[i].max_friction_ratio) << "segment " << i;
    EXPECT_EQ(a.segments[i].energy_drift_rel, b.segments[i].energy_drift_rel) << "segment " << i;
  }
  EXPECT_EQ(a.t_end_s, b.t_end_s);
  EXPECT_EQ(a.end_q_WB.coeffs(), b.end_q_WB.coeffs());
  EXPECT_EQ(a.end_w_B, b.end_w_B);
  EXPECT_EQ(a.end_reason, b.end_reason);
  EXPECT_EQ(a.failure, b.failure);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.max_discarded_rate_rad_s, b.max_discarded_rate_rad_s);
  EXPECT_EQ(a.num_steps, b.num_steps);
  EXPECT_EQ(a.num_evaluations, b.num_evaluations);
  EXPECT_EQ(a.num_guard_evaluations, b.num_guard_evaluations);
}

TEST(Simulator, SimulateIntoTheTrajectoryOfAnotherRunGivesSimulatesRunBitForBit) {
  // A fit reuses one trajectory's storage for thousands of runs: what an earlier run left in it (more samples,
  // more impacts, a failure message, a rest) must not show in the next.
  const Block block = Fig14Block();
  SimulationOptions failing;
  failing.max_impacts = 3;  // fails with a message
  SimulationOptions with_attitude;
  with_attitude.t_max_s = 2.0;
  SimulationOptions sampled;  // as a fit runs: given times, no attitudes, to t_max
  sampled.sample_attitude = false;
  sampled.stop = StopCondition::kTMax;
  for (int k = 0; k < 300; ++k) sampled.sample_times_s.push_back(k / 256.0);
  sampled.t_max_s = sampled.sample_times_s.back();
  ModelParameters planar = Fig14Parameters();
  planar.lambda_lat = 0.0;
  const std::pair<ModelParameters, SimulationOptions> runs[] = {
      {Fig14Parameters(), with_attitude}, {Fig14Parameters(), failing}, {WithinBoundsParameters(), sampled},
      {planar, with_attitude},            {Fig14Parameters(), sampled}, {planar, failing}};
  Trajectory reused;
  for (const auto& [params, options] : runs) {
    SimulateInto(block, params, options, &reused);
    ExpectSameTrajectory(reused, Simulate(block, params, options));
  }
}

}  // namespace
}  // namespace rockfit::core
