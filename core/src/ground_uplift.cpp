#include "rockfit/core/ground_uplift.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockfit::core {
namespace {

// The edge V_kV_{k+1} of index e = k − 1.
Contact EdgeOfIndex(int e) { return Contact::Edge(e + 1, e + 2); }

// Margins within this fraction of g·(b1 + b2)·1 m of zero vanish together (round-off of two roots of one instant).
constexpr double kSimultaneousRelTol = 1e-12;

Contact ContactAt(const std::array<double, 4>& margins, int first_edge, double zero) {
  // Edges e − 1 and e share V_{e+1}; edges e and e + 1 share V_{e+2}.
  const int previous = (first_edge + 3) % 4;
  const int next = (first_edge + 1) % 4;
  if (margins[previous] >= -zero && margins[previous] >= margins[next]) return Contact::Vertex(first_edge + 1);
  if (margins[next] >= -zero) return Contact::Vertex(first_edge + 2);
  return EdgeOfIndex(first_edge);
}

// Per base edge: the distance d of its midpoint from the base centre and the inward unit vector n_B.
struct EdgeLevers {
  std::array<double, 4> d_m{};
  std::array<Eigen::Vector3d, 4> inward_B{};
  explicit EdgeLevers(const Block& block) {
    for (int e = 0; e < 4; ++e) {
      const Eigen::Vector3d mid_B = 0.5 * (block.p_BV_B(e + 1) + block.p_BV_B(e + 2));
      d_m[e] = mid_B.norm();
      inward_B[e] = -mid_B / d_m[e];
    }
  }
};

std::array<double, 4> Margins(const EdgeLevers& levers, double h_m, const Eigen::Quaterniond& q_yaw,
                              double gravity_m_s2, const Eigen::Vector3d& a_W) {
  std::array<double, 4> margins{};
  const Eigen::Vector3d a_B = q_yaw.conjugate() * a_W;  // yaw only: a_B·n_B = a_W·n_W, a_B.z = a_W.z
  for (int e = 0; e < 4; ++e) {
    margins[e] = h_m * a_B.dot(levers.inward_B[e]) - levers.d_m[e] * (gravity_m_s2 + a_B.z());
  }
  return margins;
}

}  // namespace

std::array<double, 4> UpliftMargins(const Block& block, const Eigen::Quaterniond& q_yaw, double gravity_m_s2,
                                    const Eigen::Vector3d& a_W) {
  return Margins(EdgeLevers(block), block.h(), q_yaw, gravity_m_s2, a_W);
}

std::optional<Uplift> NextUplift(const Block& block, const GroundMotion& ground, const Eigen::Quaterniond& q_yaw,
                                 double gravity_m_s2, double t_from_s, double t_until_s) {
  if (!(t_until_s >= t_from_s)) return std::nullopt;
  const double zero = kSimultaneousRelTol * gravity_m_s2 * (block.b1() + block.b2());
  const EdgeLevers levers(block);  // once per search: the search visits every record sample
  const auto margins_at = [&](double t) {
    return Margins(levers, block.h(), q_yaw, gravity_m_s2, ground.Acceleration_W(t));
  };
  std::array<double, 4> m0 = margins_at(t_from_s);
  // A margin that is positive at t_from uplifts at once; one within round-off of zero only if it then grows
  // (the search below): a block that has just landed where a margin touches zero would otherwise uplift with
  // no acceleration to lift it and land again at the same instant.
  for (int e = 0; e < 4; ++e) {
    if (m0[e] > zero) {
      int best = e;
      for (int f = e + 1; f < 4; ++f) best = m0[f] > m0[best] ? f : best;
      return Uplift{t_from_s, ContactAt(m0, best, zero)};
    }
  }
  double t0 = t_from_s;
  while (t0 < t_until_s) {
    const double t1 = std::min(ground.NextBreak(t0), t_until_s);
    if (!std::isfinite(t1)) return std::nullopt;  // after the record a_g = 0: the block stays down
    const std::array<double, 4> m1 = margins_at(t1);
    // Each margin is linear on [t0, t1]: the earliest root of those that end positive.
    double t_root = std::numeric_limits<double>::infinity();
    int first = -1;
    for (int e = 0; e < 4; ++e) {
      if (!(m1[e] > 0.0)) continue;
      const double t = m0[e] >= 0.0 ? t0 : t0 + (t1 - t0) * (-m0[e]) / (m1[e] - m0[e]);
      if (t < t_root) {
        t_root = t;
        first = e;
      }
    }
    if (first >= 0) {
      const double u = (t_root - t0) / (t1 - t0);
      std::array<double, 4> at_root{};
      for (int e = 0; e < 4; ++e) at_root[e] = (1.0 - u) * m0[e] + u * m1[e];
      at_root[first] = 0.0;  // the root itself, not its round-off
      return Uplift{t_root, ContactAt(at_root, first, zero)};
    }
    t0 = t1;
    m0 = m1;
  }
  return std::nullopt;
}

}  // namespace rockfit::core
