// Ground-motion records → the ground acceleration a_g(t) in W that the simulator takes
// (io/README.md, "Ground-motion records"):
//  * a first horizontal component acts along (cos β, sin β, 0), β the incidence angle from the block's x axis
//    at rest; a second horizontal component along (−sin β, cos β, 0); a vertical component along +z;
//  * all components must have the same time step; a shorter one is padded with zeros (with a note);
//  * a scale factor multiplies every component; a target PGA instead scales them all by one factor so that
//    the largest horizontal resultant (or, with no horizontal component, the largest |a_z|) equals it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rockfit/core/ground_motion.hpp"

namespace rockfit::io {

struct RecordComponent {
  std::string source;  // file (and column) for messages
  double dt_s = 0.0;
  std::vector<double> accel_m_s2;
};

struct GroundMotionAssembly {
  std::optional<RecordComponent> horizontal_1;
  std::optional<RecordComponent> horizontal_2;
  std::optional<RecordComponent> vertical;
  double incidence_rad = 0.0;              // β
  double scale = 1.0;                      // used when target_pga_m_s2 is empty
  std::optional<double> target_pga_m_s2;
};

struct AssembledGroundMotion {
  core::GroundMotion ground;
  double scale = 1.0;              // the factor applied (given, or from the target PGA)
  std::vector<std::string> notes;  // e.g. padding of a shorter component
};

// Throws InvalidArgument for bad options (no component, non-positive target), BadInput for components whose
// time steps differ (exit code 2), naming both files.
AssembledGroundMotion AssembleGroundMotion(const GroundMotionAssembly& assembly);

}  // namespace rockfit::io
