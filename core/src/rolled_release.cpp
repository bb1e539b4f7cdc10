#include "rockfit/core/rolled_release.hpp"

#include <cmath>
#include <string>

#include "rockfit/core/edge_dynamics.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::core {

RolledRelease MakeRolledRelease(const Block& block, int edge_first, int edge_second, double alpha_rad,
                                double roll_rad) {
  if (!std::isfinite(roll_rad) || roll_rad == 0.0) {
    throw InvalidArgument("a rolled release needs a finite, non-zero roll, got " + std::to_string(roll_rad));
  }
  // Gravity does not enter the attitude; any positive value builds the edge's geometry.
  constexpr double kAnyGravity_m_s2 = 1.0;
  const EdgeDynamics edge(block, edge_first, edge_second, kAnyGravity_m_s2);
  RolledRelease release;
  release.q_WB = (edge.Tilt(alpha_rad) * Eigen::Quaterniond(Eigen::AngleAxisd(roll_rad, edge.inward_B()))).normalized();
  const double z_first = (release.q_WB * block.p_BV_B(edge_first)).z();
  const double z_second = (release.q_WB * block.p_BV_B(edge_second)).z();
  release.pivot_vertex = Block::WrapVertex(z_first <= z_second ? edge_first : edge_second);
  return release;
}

}  // namespace rockfit::core
