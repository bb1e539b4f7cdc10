// The simulator's per-run cache of contact modes (detail/mode_cache.hpp) and the guards evaluated all at once:
// a mode reused with another yaw or lift margin, and every guard from Guards(), must be bit for bit what a freshly
// built mode and its Guard() give, since the simulator's results may not change by their use.
#include "detail/mode_cache.hpp"

#include <array>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "detail/hybrid_segment.hpp"

namespace rockfit::core::detail {
namespace {

constexpr double kG = 9.81;

Block TestBlock() { return Block::FromDensity(0.05, 0.03, 0.2, 2692.0); }

GroundMotion TestGround() {
  // A few samples with all three components, so that both end loads of an edge and the field vary.
  std::vector<Eigen::Vector3d> a{{0.0, 0.0, 0.0}, {2.5, -1.0, 0.8}, {-3.0, 2.0, -1.5}, {1.0, 0.5, 0.3}};
  return GroundMotion::Uniform(0.02, a);
}

void ExpectSameGuard(const GuardValue& a, const GuardValue& b, int index) {
  EXPECT_EQ(a.value, b.value) << "guard " << index;
  EXPECT_EQ(a.rate, b.rate) << "guard " << index;
}

TEST(ModeCache, EdgeDynamicsDoNotDependOnTheOrderOfTheEdge) {
  const Block block = TestBlock();
  ModeCache modes(block, kG, nullptr, false);
  for (int i = 1; i <= 4; ++i) {
    const int j = Block::WrapVertex(i + 1);
    const EdgeDynamics fresh(block, j, i, kG);
    const EdgeDynamics& cached = modes.EdgeDynamicsOf(i, j);
    EXPECT_EQ(&cached, &modes.EdgeDynamicsOf(j, i)) << "one entry per edge";
    EXPECT_EQ(cached.axis_B(), fresh.axis_B());
    EXPECT_EQ(cached.inertia_kg_m2(), fresh.inertia_kg_m2());
    EXPECT_EQ(cached.swing_constant_1_s2(), fresh.swing_constant_1_s2());
    EXPECT_EQ(cached.critical_angle_rad(), fresh.critical_angle_rad());
  }
}

TEST(ModeCache, AnEdgeModeReusedWithAnotherYawIsTheFreshlyBuiltMode) {
  const Block block = TestBlock();
  ModeCache modes(block, kG, nullptr, false);
  const EdgeMode::State y(0.07, -0.4);
  // The first yaw is pure and the edge axis a body axis (Euler angles without conversion); the others are not.
  for (const double yaw_rad : {0.0, 0.6, -2.1, 0.0}) {
    const Eigen::Quaterniond q_yaw(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
    for (int i = 1; i <= 4; ++i) {
      const int j = Block::WrapVertex(i + 1);
      for (const auto& [a, b] : {std::pair{i, j}, std::pair{j, i}}) {
        const EdgeMode fresh(block, a, b, q_yaw, kG);
        const EdgeMode& reused = modes.Edge(a, b, q_yaw);
        EXPECT_EQ(reused.first(), fresh.first());
        EXPECT_EQ(reused.second(), fresh.second());
        EXPECT_EQ(reused.Attitude(y).coeffs(), fresh.Attitude(y).coeffs());
        const Eigen::Quaterniond q_WB = fresh.Attitude(y);
        EXPECT_EQ(reused.EulerZyx(q_WB, y), fresh.EulerZyx(q_WB, y)) << "yaw " << yaw_rad << ", V" << a << "V" << b;
      }
    }
  }
}

TEST(ModeCache, AGroundEdgeModeReusedWithAnotherYawAndMarginGivesTheFreshGuardsAndRates) {
  const Block block = TestBlock();
  const GroundMotion ground = TestGround();
  ModeCache modes(block, kG, &ground, false);
  const GroundEdgeMode::State y(0.03, 0.2);
  for (const double yaw_rad : {0.3, -1.2}) {
    for (const double margin_g : {0.0, 1e-3}) {
      const Eigen::Quaterniond q_yaw(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
      const GroundEdgeMode fresh(block, 2, 3, q_yaw, kG, ground, false, margin_g);
      const GroundEdgeMode& reused = modes.GroundEdge(2, 3, q_yaw, margin_g);
      for (const double t : {0.005, 0.031, 0.047}) {
        GroundEdgeMode::State d_fresh;
        GroundEdgeMode::State d_reused;
        fresh(t, y, d_fresh);
        reused(t, y, d_reused);
        EXPECT_EQ(d_reused, d_fresh);
        for (int g = 0; g < GroundEdgeMode::kNumGuards; ++g) ExpectSameGuard(reused.Guard(g, t, y), fresh.Guard(g, t, y), g);
      }
    }
  }
}

TEST(Guards, AllAtOnceAreEachGuardBitForBit) {
  const Block block = TestBlock();
  const GroundMotion ground = TestGround();
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.1, Eigen::Vector3d(0.2, 1.0, 0.3).normalized()));
  const VertexMode::State y_vertex = VertexDynamics::MakeState(q, Eigen::Vector3d(0.3, -1.0, 0.4));
  const EdgeMode::State y_edge(0.05, -0.3);
  for (int k = 1; k <= 4; ++k) {
    const VertexMode free(block, k, kG);
    const auto all = EvaluateGuards(free, 0.0, y_vertex);
    for (int g = 0; g < VertexMode::kNumGuards; ++g) ExpectSameGuard(all[g], free.Guard(g, 0.0, y_vertex), g);
    for (const bool falls_on_side : {false, true}) {
      const GroundVertexMode moving(block, k, kG, ground, falls_on_side);
      const auto all_moving = EvaluateGuards(moving, 0.033, y_vertex);
      for (int g = 0; g < GroundVertexMode::kNumGuards; ++g) {
        ExpectSameGuard(all_moving[g], moving.Guard(g, 0.033, y_vertex), g);
      }
    }
    for (const bool falls_on_side : {false, true}) {
      const GroundEdgeMode edge(block, k, Block::WrapVertex(k + 1), Eigen::Quaterniond::Identity(), kG, ground, falls_on_side, 0.0);
      const auto all_edge = EvaluateGuards(edge, 0.021, y_edge);
      for (int g = 0; g < GroundEdgeMode::kNumGuards; ++g) ExpectSameGuard(all_edge[g], edge.Guard(g, 0.021, y_edge), g);
    }
  }
}

}  // namespace
}  // namespace rockfit::core::detail
