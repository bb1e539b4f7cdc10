// A release that is not in the rocking plane: the block at rest tilted α about its release edge and rolled β
// about the base's inward axis of that edge (the base-plane axis from the edge towards the base centre), so that
// it stands on one corner of the edge. Released, it rocks about that corner (a vertex phase, docs/design.md §4)
// until the edge's other corner lands. For the default edge V1V2 the attitude is R_WB = Ry(−α)·Rx(β): β > 0
// lowers V1 (the −y corner), β < 0 lowers V2. β = 0 is the paper's release on the edge (Sect. 5.1), which the
// simulator starts as an edge phase without this file.
#pragma once

#include <Eigen/Geometry>

#include "rockfit/core/block.hpp"

namespace rockfit::core {

struct RolledRelease {
  int pivot_vertex = 1;                                   // the corner of the edge that stays on the ground
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();  // tilt about the edge, then the roll
};

// The attitude and pivot of the release tilted alpha_rad about edge V_iV_j and rolled roll_rad (≠ 0) about the
// edge's inward axis. Throws InvalidArgument unless V_i, V_j are neighbours and roll_rad is finite and non-zero.
RolledRelease MakeRolledRelease(const Block& block, int edge_first, int edge_second, double alpha_rad, double roll_rad);

}  // namespace rockfit::core
