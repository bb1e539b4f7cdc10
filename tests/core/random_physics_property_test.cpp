// Random physics: seeded loops over random parameter sets through both pieces of `impact` (edge (19)–(20) and
// facet (18)+(21)) and through `simulate`. Every run must end with a status (or InvalidArgument exactly when
// an input is outside what the function documents), return, and leave no NaN or inf in any output.
// The CI size is small (RandomPhysicsRuns); ROCKFIT_RANDOM_PHYSICS_RUNS=100000 gives the full run of the
// README's "Reliability" section.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "random_physics.hpp"
#include "rockfit/core/errors.hpp"
#include "rockfit/core/impact_maps.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::core {
namespace {

using testing::RandomPhysics;
using testing::RandomPhysicsRuns;

constexpr double kQuarterTurn_rad = 1.5707963267948966;

// A termination guard, not a speed requirement: a single run that needs longer than this is hung.
constexpr double kHangWallTime_s = 60.0;

Eigen::Vector3d RandomOmega(RandomPhysics& r) {
  return {r.SignedLogUniform(1e-6, 1e3), r.SignedLogUniform(1e-6, 1e3),
          r.Chance(0.3) ? 0.0 : r.SignedLogUniform(1e-6, 1e3)};
}

// Every number an impact outcome reports is finite; a non-ok outcome reports no post-impact state.
void ExpectFiniteOutcome(const ImpactOutcome& o, const std::string& what) {
  EXPECT_TRUE(o.w_plus_W.allFinite() && o.w_plus_B.allFinite() && o.w_minus_W.allFinite()) << what;
  EXPECT_TRUE(std::isfinite(o.tau) && std::isfinite(o.energy_before_J) && std::isfinite(o.energy_after_J) &&
              std::isfinite(o.delta_energy_J))
      << what;
  if (o.status != ImpactStatus::kOk) {
    EXPECT_TRUE(o.w_plus_W.isZero(0.0)) << what;
    EXPECT_EQ(o.energy_after_J, 0.0) << what;
  }
  for (const auto& c : o.candidates) EXPECT_TRUE(c.w_plus.allFinite() && std::isfinite(c.tau)) << what;
}

TEST(RandomPhysicsProperty, EdgeImpactsEndWithAStatusAndFiniteOutputsForExtremeParameters) {
  RandomPhysics r(20261125);
  const long runs = RandomPhysicsRuns(2000, 200);
  std::map<std::string, long> counts;
  for (long run = 0; run < runs; ++run) {
    const Block block = r.Block();
    const int pivot = r.Integer(1, 4);
    const bool neighbours = !r.Chance(0.05);
    const int landing = neighbours ? Block::WrapVertex(pivot + (r.Chance(0.5) ? 1 : -1)) : Block::WrapVertex(pivot + 2);
    const double critical = std::atan(std::max(block.b1(), block.b2()) / block.h());
    const double tilt = r.Chance(0.03) ? -r.LogUniform(1e-9, 1.0) : std::min(r.Tilt(critical), 2.0);
    const EdgeImpactParameters params{r.ImpactParameter(), r.Chance(0.5) ? 0.0 : r.SignedLogUniform(1e-12, 1e2)};
    const Eigen::Vector3d w_minus = RandomOmega(r);
    const std::string what = "run " + std::to_string(run) + ": b1 " + std::to_string(block.b1()) + " b2 " +
                             std::to_string(block.b2()) + " h " + std::to_string(block.h()) + " m " +
                             std::to_string(block.mass()) + " tilt " + std::to_string(tilt) + " λ " +
                             std::to_string(params.lambda);
    const bool valid = neighbours && tilt >= 0.0 && tilt <= kQuarterTurn_rad;
    try {
      const Eigen::Matrix3d R_WB = EdgeImpactAttitude(block, pivot, landing, tilt);
      const ImpactOutcome o = EdgeImpact(block, R_WB, pivot, landing, R_WB * w_minus, params);
      ASSERT_TRUE(valid) << what << ": accepted an input outside the documented range";
      ExpectFiniteOutcome(o, what);
      EXPECT_EQ(o.within_geometric_bounds, WithinEdgeBounds(params.lambda)) << what;
      for (double root : EdgeImpactSingularLambdas(block, R_WB, pivot, landing))
        EXPECT_TRUE(std::isfinite(root)) << what;
      ++counts[ToString(o.status)];
    } catch (const InvalidArgument&) {
      ASSERT_FALSE(valid) << what << ": refused a documented input";
      ++counts["refused"];
    }
  }
  long total = 0;
  for (const auto& [status, n] : counts) total += n;
  EXPECT_EQ(total, runs);
  EXPECT_GT(counts["ok"], runs / 4);
  RecordProperty("runs", std::to_string(runs));
  for (const auto& [status, n] : counts) std::printf("edge impact  %-10s %ld\n", status.c_str(), n);
}

TEST(RandomPhysicsProperty, FacetImpactsEndWithAStatusAndFiniteOutputsForExtremeParameters) {
  RandomPhysics r(20261126);
  const long runs = RandomPhysicsRuns(2000, 200);
  std::map<std::string, long> counts;
  for (long run = 0; run < runs; ++run) {
    const Block block = r.Block();
    const int pivot = r.Integer(-6, 9);  // taken cyclically
    FacetImpactParameters params;
    params.lambda_lat = r.ImpactParameter();
    params.lambda_lon = r.ImpactParameter();
    params.tau_rule = r.Chance(0.5) ? FacetTauRule::kNoSpin : FacetTauRule::kFixed;
    params.tau = r.Chance(0.5) ? 0.0 : r.SignedLogUniform(1e-12, 1e2);
    // Falling onto the facet (ω⁻ a positive multiple of r_b − r_{b−1}) or any other direction.
    const Eigen::Vector3d edge = block.p_BV_B(pivot) - block.p_BV_B(pivot - 1);
    const Eigen::Vector3d w_minus =
        r.Chance(0.7) ? Eigen::Vector3d(edge.normalized() * r.LogUniform(1e-6, 1e3)) : RandomOmega(r);
    const std::string what = "run " + std::to_string(run) + ": b1 " + std::to_string(block.b1()) + " b2 " +
                             std::to_string(block.b2()) + " h " + std::to_string(block.h()) + " λ_lat " +
                             std::to_string(params.lambda_lat) + " λ_lon " + std::to_string(params.lambda_lon);
    const ImpactOutcome o = FacetImpact(block, pivot, w_minus, params);  // every input here is documented
    ExpectFiniteOutcome(o, what);
    EXPECT_EQ(o.within_geometric_bounds, WithinFacetBounds(params.lambda_lat, params.lambda_lon)) << what;
    ++counts[ToString(o.status)];
  }
  EXPECT_GT(counts["ok"], runs / 4);
  for (const auto& [status, n] : counts) std::printf("facet impact %-10s %ld\n", status.c_str(), n);
}

// Every sample, impact and segment of a trajectory is finite; the run ends by t_max.
void ExpectFiniteTrajectory(const Trajectory& tr, const SimulationOptions& o, const std::string& what) {
  EXPECT_TRUE(std::isfinite(tr.t_end_s) && tr.t_end_s >= 0.0 && tr.t_end_s <= o.t_max_s * (1.0 + 1e-12)) << what;
  ASSERT_EQ(tr.w_B.size(), tr.t_s.size()) << what;
  for (std::size_t k = 0; k < tr.t_s.size(); ++k) {
    ASSERT_TRUE(std::isfinite(tr.t_s[k]) && tr.w_B[k].allFinite()) << what << " sample " << k;
    if (!tr.q_WB.empty()) {
      ASSERT_TRUE(tr.q_WB[k].coeffs().allFinite() && tr.euler_zyx[k].allFinite()) << what;
    }
  }
  for (const auto& i : tr.impacts) {
    ASSERT_TRUE(std::isfinite(i.t_s) && i.w_minus_B.allFinite() && i.w_plus_B.allFinite() && std::isfinite(i.tau) &&
                std::isfinite(i.delta_energy_J))
        << what;
  }
  for (const auto& s : tr.segments) {
    ASSERT_TRUE(std::isfinite(s.t_begin_s) && std::isfinite(s.t_end_s) && !std::isnan(s.min_normal_force_N) &&
                !std::isnan(s.max_friction_ratio) && !std::isnan(s.energy_drift_rel))
        << what;
  }
  if (tr.end_reason == EndReason::kFailed) {
    EXPECT_FALSE(tr.message.empty()) << what;
  }
}

TEST(RandomPhysicsProperty, SimulationsEndWithAReasonInBoundedTimeAndFiniteOutputs) {
  RandomPhysics r(20261127);
  const long runs = RandomPhysicsRuns(2000, 100);  // a simulation costs ~100 impact maps: fewer under the sanitizers
  std::map<std::string, long> counts;
  double slowest_s = 0.0;
  for (long run = 0; run < runs; ++run) {
    const Block block = r.Block();
    const double critical = std::atan(block.b1() / block.h());  // release about V1V2, the +x side lifted
    ModelParameters p;
    p.alpha_rad = r.Chance(0.02) ? (r.Chance(0.5) ? 0.0 : -0.1) : r.Tilt(critical);
    p.lambda = r.ImpactParameter();
    p.tau_edge = r.Chance(0.7) ? 0.0 : r.SignedLogUniform(1e-9, 1e-1) * block.mass() * block.h() * block.h();
    p.lambda_lat = r.ImpactParameter();
    p.lambda_lon = r.ImpactParameter();
    p.facet_tau_rule = r.Chance(0.5) ? FacetTauRule::kNoSpin : FacetTauRule::kFixed;
    SimulationOptions o;
    const StopCondition stops[] = {StopCondition::kPhase4, StopCondition::kRest, StopCondition::kOverturned,
                                   StopCondition::kTMax};
    o.stop = stops[r.Integer(0, 3)];
    o.t_max_s = r.LogUniform(0.05, 2.0);
    o.rate_hz = r.LogUniform(16.0, 1024.0);
    o.sample_attitude = r.Chance(0.5);
    o.rel_tol = r.Chance(0.03) ? r.LogUniform(1e-17, 1e-15) : r.LogUniform(1e-15, 0.5);  // tiny to huge
    o.abs_tol = r.LogUniform(1e-18, 1e-2);
    o.event_time_tol_s = r.Chance(0.03) ? 1e-2 : r.LogUniform(1e-15, 1e-3);
    o.max_step_s = r.LogUniform(1e-3, 1.0);
    o.zeno_dt_s = r.Chance(0.1) ? 0.0 : r.LogUniform(1e-8, 1e-2);
    o.rest_energy_height_m = r.Chance(0.1) ? 0.0 : r.LogUniform(1e-12, 1e-2);
    o.max_impacts = static_cast<std::size_t>(r.LogUniform(1.0, 1e4));
    const bool valid = p.alpha_rad > 0.0 && o.rel_tol >= 1e-15 && o.event_time_tol_s <= 1e-3;
    const std::string what = "run " + std::to_string(run) + ": b1 " + std::to_string(block.b1()) + " b2 " +
                             std::to_string(block.b2()) + " h " + std::to_string(block.h()) + " m " +
                             std::to_string(block.mass()) + " α/θc " + std::to_string(p.alpha_rad / critical) + " λ " +
                             std::to_string(p.lambda) + " λ_lat " + std::to_string(p.lambda_lat) + " λ_lon " +
                             std::to_string(p.lambda_lon) + " rel_tol " + std::to_string(o.rel_tol);
    try {
      const Trajectory tr = Simulate(block, p, o);
      ASSERT_TRUE(valid) << what << ": accepted an input outside the documented range";
      ExpectFiniteTrajectory(tr, o, what);
      EXPECT_LT(tr.wall_time_s, kHangWallTime_s) << what;
      slowest_s = std::max(slowest_s, tr.wall_time_s);
      if (p.alpha_rad > critical * (1.0 + 1e-6)) {
        // Beyond θ_c the block never comes back (paper Sect. 4.1): it overturns or the time runs out.
        EXPECT_TRUE(tr.impacts.empty()) << what;
        EXPECT_TRUE(tr.end_reason == EndReason::kOverturned || tr.end_reason == EndReason::kTMax) << what;
      }
      ++counts[ToString(tr.end_reason)];
    } catch (const InvalidArgument&) {
      ASSERT_FALSE(valid) << what << ": refused a documented input";
      ++counts["refused"];
    }
  }
  for (const auto& [reason, n] : counts) std::printf("simulate     %-10s %ld\n", reason.c_str(), n);
  std::printf("simulate     slowest run %.3f s of %ld\n", slowest_s, runs);
}

}  // namespace
}  // namespace rockfit::core
