// The closed-form swing about an edge: its landing time against the quadrature T(α), its states against an
// independent fixed-step integration of J_e ψ̈ = −m g R sin(θ_c − ψ), its load against EdgeDynamics::Force, and the
// simulator's free runs with closed-form swings against the same runs integrated.
#include "rockfit/core/conservative_edge_phase.hpp"

#include <cmath>
#include <random>

#include <gsl/gsl_sf_elljac.h>
#include <gtest/gtest.h>

#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/planar_rocking.hpp"
#include "rockfit/core/simulator.hpp"
#include "simulation_cases.hpp"

namespace rockfit::core {
namespace {

// Round-off of a time of ~0.1–0.5 s computed by a few dozen flops and one Carlson R_F [s].
constexpr double kTimeTol_s = 1e-14;
// Round-off of a tilt [rad] and a rate [rad/s] from one Jacobi evaluation.
constexpr double kTiltTol_rad = 1e-13;
constexpr double kRateTol_rad_s = 1e-12;

EdgeDynamics Fig14Edge() { return EdgeDynamics(testing::Fig14Block(), 1, 2, kStandardGravity); }

// ψ(t) by classical RK4 with a fixed step of 1e-5 s (global error ~1e-17·t for these frequencies).
EdgeDynamics::State IntegrateRk4(const EdgeDynamics& edge, EdgeDynamics::State y, double t_end_s) {
  constexpr double kStep_s = 1e-5;
  const int steps = static_cast<int>(std::ceil(t_end_s / kStep_s));
  const double h = t_end_s / steps;
  EdgeDynamics::State k1, k2, k3, k4;
  for (int i = 0; i < steps; ++i) {
    edge(0.0, y, k1);
    edge(0.0, y + 0.5 * h * k1, k2);
    edge(0.0, y + 0.5 * h * k2, k3);
    edge(0.0, y + h * k3, k4);
    y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return y;
}

std::optional<ConservativeEdgePhase> Swing(const EdgeDynamics& edge, double psi0, double psi_dot0) {
  return ConservativeEdgePhase::Make(edge.swing_constant_1_s2(), edge.critical_angle_rad(), psi0, psi_dot0);
}

TEST(ConservativeEdgePhase, ReleaseLandsAtTheQuadratureTimeT) {
  const EdgeDynamics edge = Fig14Edge();
  const PlanarRocker rocker = PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2);
  for (const double alpha : {0.01, 0.05, 0.1, 0.197, 0.23, 0.24}) {
    const auto swing = Swing(edge, alpha, 0.0);
    ASSERT_TRUE(swing.has_value()) << alpha;
    EXPECT_NEAR(swing->time_to_flat_s(), FallTime(rocker, alpha), kTimeTol_s) << alpha;
    EXPECT_NEAR(swing->AtFlat()[1], -LandingRate(rocker, alpha), kRateTol_rad_s) << alpha;
    EXPECT_NEAR(swing->apex_tilt_rad(), alpha, kTiltTol_rad) << alpha;
  }
}

TEST(ConservativeEdgePhase, SwingFromTheGroundTakesTwiceTheFallTimeOfItsApex) {
  const EdgeDynamics edge = Fig14Edge();
  const PlanarRocker rocker = PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2);
  const double overturn_rate = LandingRate(rocker, edge.critical_angle_rad());
  for (const double fraction : {0.01, 0.2, 0.6, 0.99}) {
    const double rate = fraction * overturn_rate;
    const auto swing = Swing(edge, 0.0, rate);
    ASSERT_TRUE(swing.has_value()) << rate;
    const double apex = *AmplitudeFromLandingRate(rocker, rate);
    EXPECT_NEAR(swing->apex_tilt_rad(), apex, kTiltTol_rad) << rate;
    EXPECT_NEAR(swing->time_to_flat_s(), 2.0 * FallTime(rocker, apex), 2.0 * kTimeTol_s) << rate;
    EXPECT_EQ(swing->AtFlat()[1], -rate);  // energy: it lands as fast as it left
  }
}

TEST(ConservativeEdgePhase, StatesAgreeWithAnIndependentIntegration) {
  const EdgeDynamics edge = Fig14Edge();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> tilt(0.0, 0.15);
  const PlanarRocker rocker = PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2);
  const double overturn_rate = LandingRate(rocker, edge.critical_angle_rad());
  std::uniform_real_distribution<double> rate(-0.6 * overturn_rate, 0.6 * overturn_rate);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const EdgeDynamics::State y0(tilt(rng), rate(rng));
    const auto swing = Swing(edge, y0[0], y0[1]);
    if (!swing) continue;
    const double t = fraction(rng) * swing->time_to_flat_s();
    const EdgeDynamics::State exact = swing->At(t);
    const EdgeDynamics::State integrated = IntegrateRk4(edge, y0, t);
    EXPECT_NEAR(exact[0], integrated[0], 1e-11) << "trial " << trial;
    EXPECT_NEAR(exact[1], integrated[1], 1e-10) << "trial " << trial;
    // At the landing time the integrated tilt is zero and the rate is the landing rate.
    const EdgeDynamics::State landed = IntegrateRk4(edge, y0, swing->time_to_flat_s());
    EXPECT_NEAR(landed[0], 0.0, 1e-11) << "trial " << trial;
    EXPECT_NEAR(landed[1], swing->AtFlat()[1], 1e-10) << "trial " << trial;
    ++checked;
  }
  EXPECT_GE(checked, 15);
}

TEST(ConservativeEdgePhase, StartStateAndApexAreReproduced) {
  const EdgeDynamics edge = Fig14Edge();
  for (const double rate : {-0.3, 0.0, 0.3}) {
    const auto swing = Swing(edge, 0.1, rate);
    ASSERT_TRUE(swing.has_value());
    EXPECT_NEAR(swing->At(0.0)[0], 0.1, kTiltTol_rad);
    EXPECT_NEAR(swing->At(0.0)[1], rate, kRateTol_rad_s);
    EXPECT_NEAR(swing->At(swing->apex_time_s())[1], 0.0, kRateTol_rad_s);
    EXPECT_NEAR(swing->At(swing->apex_time_s())[0], swing->apex_tilt_rad(), kTiltTol_rad);
    EXPECT_EQ(swing->apex_time_s() > 0.0, rate > 0.0);
  }
}

TEST(ConservativeEdgePhase, EvenSamplesByTheAdditionTheoremMatchExactEvaluations) {
  const EdgeDynamics edge = Fig14Edge();
  const auto swing = Swing(edge, 0.0, 0.5 * LandingRate(PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2), 0.245));
  ASSERT_TRUE(swing.has_value());
  const double dt = 1.0 / 256.0 / 7.0;  // many samples in one swing
  SwingSamples samples(*swing);
  int n = 0;
  for (double t = 0.3 * dt; t < swing->time_to_flat_s(); t = 0.3 * dt + (++n) * dt) {
    const EdgeDynamics::State stepped = swing->FromJacobi(samples.At(t));
    const EdgeDynamics::State exact = swing->At(t);
    EXPECT_NEAR(stepped[0], exact[0], kTiltTol_rad) << n;
    EXPECT_NEAR(stepped[1], exact[1], kRateTol_rad_s) << n;
  }
  EXPECT_GT(n, 2 * SwingSamples::kExactEvery);
}

// The Maclaurin series against GSL's Jacobi functions (descending Landen transformation) over |u| ≤ its bound, for
// swings from small to near-separatrix amplitudes (m from cos²(θ_c/2) to nearly 1: every m a swing can have).
TEST(ConservativeEdgePhase, JacobiSeriesAgreesWithTheLibraryToRoundOffBelowItsBound) {
  // A few units of round-off of values of order one.
  constexpr double kSeriesTol = 4e-16;
  const EdgeDynamics edge = Fig14Edge();
  const PlanarRocker rocker = PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2);
  const double overturn_rate = LandingRate(rocker, edge.critical_angle_rad());
  for (const double fraction : {1e-3, 0.3, 0.9, 0.999}) {
    const auto swing = Swing(edge, 0.0, fraction * overturn_rate);
    ASSERT_TRUE(swing.has_value()) << fraction;
    const double m = swing->parameter_m();
    for (int i = -20; i <= 20; ++i) {
      const double u = ConservativeEdgePhase::kSeriesMaxArg * i / 20.0;
      const JacobiTriple series = swing->JacobiSeries(u);
      JacobiTriple library;
      gsl_sf_elljac_e(u, m, &library.sn, &library.cn, &library.dn);
      EXPECT_NEAR(series.sn, library.sn, kSeriesTol) << fraction << " " << u;
      EXPECT_NEAR(series.cn, library.cn, kSeriesTol) << fraction << " " << u;
      EXPECT_NEAR(series.dn, library.dn, kSeriesTol) << fraction << " " << u;
    }
  }
}

// The start's triple comes from the state alone; it is the library's at u = −ω·(apex time) and gives back the state.
TEST(ConservativeEdgePhase, StartTripleFromTheStateIsTheLibrarysAtTheStart) {
  constexpr double kTripleTol = 1e-15;  // round-off of a few square roots and divisions of values of order one
  const EdgeDynamics edge = Fig14Edge();
  for (const double psi0 : {0.0, 0.02, 0.15}) {
    for (const double rate : {-0.4, 0.0, 0.4}) {
      const auto swing = Swing(edge, psi0, rate);
      if (!swing) continue;
      const JacobiTriple& start = swing->start_jacobi();
      JacobiTriple library;
      gsl_sf_elljac_e(-swing->omega_1_s() * swing->apex_time_s(), swing->parameter_m(), &library.sn, &library.cn,
                      &library.dn);
      EXPECT_NEAR(start.sn, library.sn, kTripleTol) << psi0 << " " << rate;
      EXPECT_NEAR(start.cn, library.cn, kTripleTol) << psi0 << " " << rate;
      EXPECT_NEAR(start.dn, library.dn, kTripleTol) << psi0 << " " << rate;
      EXPECT_NEAR(swing->TiltFromJacobi(start), psi0, kTiltTol_rad) << psi0 << " " << rate;
      EXPECT_NEAR(swing->RateFromJacobi(start), rate, kRateTol_rad_s) << psi0 << " " << rate;
    }
  }
}

TEST(ConservativeEdgePhase, UnevenSamplesAreEvaluatedExactly) {
  const EdgeDynamics edge = Fig14Edge();
  const auto swing = Swing(edge, 0.0, 0.5 * LandingRate(PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2), 0.245));
  ASSERT_TRUE(swing.has_value());
  SwingSamples samples(*swing);
  double t = 0.0;
  for (int n = 0; t < swing->time_to_flat_s(); ++n) {
    const EdgeDynamics::State got = swing->FromJacobi(samples.At(t));
    const EdgeDynamics::State exact = swing->At(t);
    EXPECT_NEAR(got[0], exact[0], kTiltTol_rad) << n;
    EXPECT_NEAR(got[1], exact[1], kRateTol_rad_s) << n;
    t += (n % 3 == 0) ? 1e-3 : 2.5e-3;  // spacings that change from sample to sample
  }
}

TEST(ConservativeEdgePhase, HalfTiltWithoutTrigonometryIsThatOfTheTilt) {
  const EdgeDynamics edge = Fig14Edge();
  const auto swing = Swing(edge, 0.05, 0.4);
  ASSERT_TRUE(swing.has_value());
  for (int i = 0; i <= 20; ++i) {
    const double t = swing->time_to_flat_s() * i / 20.0;
    const double psi = swing->At(t)[0];
    const Eigen::Vector2d half = swing->HalfTiltCosSinFromJacobi(swing->JacobiAt(t));
    EXPECT_NEAR(half[0], std::cos(0.5 * psi), 1e-15) << i;
    EXPECT_NEAR(half[1], std::sin(0.5 * psi), 1e-15) << i;
  }
}

TEST(ConservativeEdgePhase, UnboundedOrLandingStartsAreLeftToTheIntegrator) {
  const EdgeDynamics edge = Fig14Edge();
  const PlanarRocker rocker = PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2);
  const double over_rate = LandingRate(rocker, edge.critical_angle_rad()) * 1.001;
  EXPECT_FALSE(Swing(edge, 0.0, over_rate).has_value());                            // passes θ_c
  EXPECT_FALSE(Swing(edge, 0.0, -0.5).has_value());                                 // lands at once
  EXPECT_FALSE(Swing(edge, 0.0, 0.0).has_value());
  EXPECT_FALSE(Swing(edge, edge.critical_angle_rad(), 0.0).has_value());            // balanced on the edge
  EXPECT_FALSE(Swing(edge, edge.critical_angle_rad() - 1e-6, 0.0).has_value());     // at the separatrix
  EXPECT_TRUE(Swing(edge, edge.critical_angle_rad() - 1e-2, 0.0).has_value());
}

TEST(ConservativeEdgePhase, LoadPerMassIsTheContactForceOfEdgeDynamics) {
  const EdgeDynamics edge = Fig14Edge();
  const auto swing = Swing(edge, 0.0, 0.7 * LandingRate(PlanarRockerAboutEdge(testing::Fig14Block(), 1, 2), 0.245));
  ASSERT_TRUE(swing.has_value());
  for (int i = 0; i <= 10; ++i) {
    const double t = swing->time_to_flat_s() * i / 10.0;
    const EdgeDynamics::State y = swing->At(t);
    EdgeDynamics::State dydt;
    edge(0.0, y, dydt);
    const ContactForce force = edge.Force(y, dydt, Eigen::Quaterniond::Identity());
    const EdgeLoadPerMass load =
        swing->LoadPerMass(std::cos(edge.critical_angle_rad() - y[0]), edge.arm_m(), kStandardGravity);
    EXPECT_NEAR(edge.mass_kg() * load.normal_m_s2, force.normal_N, 1e-9 * force.normal_N) << i;
    EXPECT_NEAR(edge.mass_kg() * load.tangential_m_s2, force.tangential_N, 1e-9 * force.normal_N) << i;
  }
}

// The planar Housner case run to rest with closed-form swings and integrated: the same impacts at the same times and
// the same samples, to the integrator's accuracy.
TEST(ConservativeEdgePhase, SimulatorWithClosedFormSwingsMatchesTheIntegratedRun) {
  SimulationOptions options;
  options.stop = StopCondition::kRest;
  const Block block = testing::PlanarHousnerBlock();
  const ModelParameters params = testing::PlanarHousnerParameters();
  const Trajectory closed = Simulate(block, params, options);
  options.analytic_edge_phases = false;
  const Trajectory integrated = Simulate(block, params, options);
  ASSERT_EQ(closed.end_reason, EndReason::kRest);
  ASSERT_EQ(closed.impacts.size(), integrated.impacts.size());
  for (std::size_t i = 0; i < closed.impacts.size(); ++i) {
    EXPECT_EQ(closed.impacts[i].kind, integrated.impacts[i].kind) << i;
    EXPECT_NEAR(closed.impacts[i].t_s, integrated.impacts[i].t_s, 1e-9) << i;
    EXPECT_NEAR((closed.impacts[i].w_plus_B - integrated.impacts[i].w_plus_B).norm(), 0.0, 1e-8) << i;
  }
  ASSERT_EQ(closed.t_s.size(), integrated.t_s.size());
  for (std::size_t k = 0; k < closed.t_s.size(); ++k) {
    EXPECT_NEAR((closed.w_B[k] - integrated.w_B[k]).norm(), 0.0, 1e-8) << k;
    EXPECT_NEAR(closed.q_WB[k].angularDistance(integrated.q_WB[k]), 0.0, 1e-9) << k;
    EXPECT_EQ(closed.mode[k], integrated.mode[k]) << k;
  }
  EXPECT_EQ(closed.num_steps, 0);  // no phase needed the integrator
  EXPECT_EQ(closed.num_guard_evaluations, 0);  // nor the integrator's event search
  EXPECT_GT(integrated.num_guard_evaluations, 0);  // which located every impact of the integrated run
  for (const SegmentDiagnostics& s : closed.segments) EXPECT_LT(s.energy_drift_rel, 1e-13);
}

// Fig. 14 mixes vertex phases (integrated) with edge phases (closed form): same impacts, same phase-4 end.
TEST(ConservativeEdgePhase, Fig14RunWithClosedFormSwingsMatchesTheIntegratedRun) {
  SimulationOptions options;
  const Trajectory closed = Simulate(testing::Fig14Block(), testing::Fig14Parameters(), options);
  options.analytic_edge_phases = false;
  const Trajectory integrated = Simulate(testing::Fig14Block(), testing::Fig14Parameters(), options);
  ASSERT_EQ(closed.end_reason, integrated.end_reason);
  ASSERT_EQ(closed.impacts.size(), integrated.impacts.size());
  for (std::size_t i = 0; i < closed.impacts.size(); ++i) {
    EXPECT_NEAR(closed.impacts[i].t_s, integrated.impacts[i].t_s, 1e-9) << i;
  }
  ASSERT_EQ(closed.t_s.size(), integrated.t_s.size());
  for (std::size_t k = 0; k < closed.t_s.size(); ++k) {
    EXPECT_NEAR((closed.w_B[k] - integrated.w_B[k]).norm(), 0.0, 1e-7) << k;
  }
}

}  // namespace
}  // namespace rockfit::core
