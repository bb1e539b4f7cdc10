// rockfit_mujoco_synth: one recording made by MuJoCo instead of rockfit's simulator (mujoco_rocking.hpp), written
// as an x-IMU GUI file set with <prefix>_truth.json, for studies of fits of recordings the model did not make
// (tools/other_physics_study.py). Test support, built only where CMake found MuJoCo; not installed.
//
//   rockfit_mujoco_synth -o PREFIX [--alpha RAD] [--roll RAD] [--t0 S] [--push RAD_S] [--duration S]
//                        [--b1 M --b2 M --h M] [--com-offset-y FRACTION_OF_B2] [--proud-vertex 1-4] [--seed N]
//                        [--solref-time-constant S] [--solref-damping-ratio R] [--solimp D0,DWIDTH,WIDTH_M]
#include <cstdlib>
#include <iostream>
#include <string>

#include "mujoco_rocking.hpp"

int main(int argc, char** argv) {
  rockfit::testing::MujocoRockingOptions o;
  std::string prefix;
  // A fraction of b2, applied once every option is read: the same offset whether --b2 comes before or after it.
  double com_offset_fraction_of_b2 = 0.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "-o") prefix = value;
    else if (key == "--alpha") o.alpha_rad = std::stod(value);
    else if (key == "--roll") o.roll_rad = std::stod(value);
    else if (key == "--t0") o.t0_s = std::stod(value);
    else if (key == "--push") o.push_w_y_rad_s = std::stod(value);
    else if (key == "--duration") o.duration_s = std::stod(value);
    else if (key == "--b1") o.b1_m = std::stod(value);
    else if (key == "--b2") o.b2_m = std::stod(value);
    else if (key == "--h") o.h_m = std::stod(value);
    else if (key == "--com-offset-y") com_offset_fraction_of_b2 = std::stod(value);
    else if (key == "--proud-vertex") o.proud_vertex = std::stoi(value);
    else if (key == "--seed") o.measurement.seed = std::stoull(value);
    else if (key == "--solref-time-constant") o.solref_time_constant_s = std::stod(value);
    else if (key == "--solref-damping-ratio") o.solref_damping_ratio = std::stod(value);
    else if (key == "--solimp") o.solimp = value;
    else {
      std::cerr << "rockfit_mujoco_synth: unknown option " << key << "\n";
      return 1;
    }
  }
  if (prefix.empty() || argc % 2 == 0) {
    std::cerr << "usage: rockfit_mujoco_synth -o PREFIX [--alpha RAD] [--roll RAD] [--t0 S] [--push RAD_S] "
                 "[--duration S] [--b1 M --b2 M --h M] [--com-offset-y F] [--proud-vertex 1-4] [--seed N] "
                 "[--solref-time-constant S] [--solref-damping-ratio R] [--solimp D0,DWIDTH,WIDTH_M]\n";
    return 1;
  }
  o.com_offset_B_m.y() = com_offset_fraction_of_b2 * o.b2_m;
  try {
    const rockfit::testing::MujocoRockingTrial trial = rockfit::testing::MakeMujocoRockingTrial(o);
    rockfit::testing::WriteMujocoRockingTrial(prefix, o, trial);
    std::cout << prefix << ": " << trial.device.size() << " samples, release at " << trial.t0_s << " s, α "
              << trial.alpha_rad << " rad, " << trial.impacts << " impacts\n";
  } catch (const std::exception& e) {
    std::cerr << "rockfit_mujoco_synth: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
