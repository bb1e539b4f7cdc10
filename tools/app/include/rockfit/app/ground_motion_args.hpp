// The ground-motion options shared by `rockfit respond` and `rockfit ground-motion`: records (PEER AT2 or CSV),
// a generated Clough–Penzien record, scale or target PGA, incidence angle.
#pragma once

#include <optional>
#include <string>
#include <vector>


#include "rockfit/io/ground_motion_input.hpp"
#include "rockfit/io/stochastic_ground_motion.hpp"

namespace rockfit::app {

struct GroundMotionArgs {
  std::string record;       // first horizontal component (or a CSV with up to three)
  std::string record2;      // second horizontal component
  std::string vertical;     // vertical component
  std::string record_format = "auto";
  std::string units = "g";  // CSV only
  std::optional<double> csv_dt_s;
  std::optional<std::uint64_t> synthetic_seed;
  double synthetic_duration_s = 20.0;
  double synthetic_dt_s = 0.005;
  std::optional<double> scale;
  std::optional<double> pga_g;
  double angle_deg = 0.0;
};


struct LoadedGroundMotion {
  io::AssembledGroundMotion assembled;
  std::vector<std::string> sources;  // one line per component: file, NPTS, DT, role
};

// Throws InvalidArgument for bad options, BadInput for bad files.
LoadedGroundMotion LoadGroundMotion(const GroundMotionArgs& args);

}  // namespace rockfit::app
