// Recordings made by other physics: a granite box released tilted from rest on a plane, simulated by MuJoCo
// (C API; soft contact, timestep ≤ 1e-4 s) instead of rockfit's hybrid simulator, and measured by rockfit's x-IMU
// measurement model (io/synth_measurement.hpp). The impacts are MuJoCo's stiff soft contacts, not the paper's
// maps: the truth of such a recording is its release time t0 and tilt α only. Optional perturbed bodies: the
// centre of mass off the axis (an inertial offset) and one base corner proud (a small extra geom).
//
// Only compiled where CMake found MuJoCo (ROCKFIT_HAVE_MUJOCO; Debian's libmujoco-dev); tests skip otherwise.
#pragma once

#ifdef ROCKFIT_HAVE_MUJOCO

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <Eigen/Geometry>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/io/synth_measurement.hpp"
#include "rockfit/io/synth_motion.hpp"
#include "rockfit/io/ximu_gui_writer.hpp"

namespace rockfit::testing {

struct MujocoRockingOptions {
  // The block (a homogeneous granite cuboid unless perturbed below): half-extents and density.
  double b1_m = 0.05000453, b2_m = 0.035, h_m = 0.2, density_kg_m3 = 2692.0;
  double alpha_rad = 0.2;   // release tilt about y (+x side lifted, φy = −α)
  double roll_rad = 0.01;   // release roll about x: the motion is not planar from the start
  double t0_s = 1.0;        // release in recording time; a multiple of the step
  // A push at the release: the block leaves its tilt at rest turning about its lowest base point at this rate
  // about body y [rad/s] (> 0: towards the fall, < 0: away from it); 0: released from rest, as the model is.
  double push_w_y_rad_s = 0.0;
  double duration_s = 3.0;
  double rate_hz = 256.0;
  // The step: an integer number of steps per sample at 256 Hz (1/10240 s ≤ 1e-4 s).
  int steps_per_sample = 40;
  // Soft contact: solref (time constant [s], damping ratio); a 1 ms time constant is a stiff stone contact.
  double solref_time_constant_s = 0.001;
  double solref_damping_ratio = 1.0;
  // solimp "d0 dwidth width" (MuJoCo's impedance, comma- or space-separated); empty: MuJoCo's default. A damping
  // ratio below 1 makes the contact springy: the block rocks for several cycles (AVRF and OPMF measurable).
  std::string solimp;
  double friction = 1.0;  // sliding friction (no sliding is modelled by rockfit)
  // Perturbed bodies: the centre of mass shifted in B [m] (inertia unchanged about the new COM); a base corner
  // (vertex 1–4 of docs/design.md §2, 0: none) standing proud of the base by proud_corner_m.
  Eigen::Vector3d com_offset_B_m = Eigen::Vector3d::Zero();
  int proud_vertex = 0;
  double proud_corner_m = 1e-4;
  // Angular accelerations above this mark an impact for the measurement model's ringing [rad/s²]: gravity turns
  // these blocks at most 3g/(4R)·sin θ_c ≈ 9 rad/s² (h = 0.2 m), a landing changes ω by ≳ 0.1 rad/s within 1–2 ms.
  double impact_acceleration_rad_s2 = 50.0;
  io::MeasurementOptions measurement;  // rockfit synth's defaults
};

struct MujocoRockingTrial {
  io::BlockMotion motion;        // the true motion at the samples
  io::DeviceSamples device;      // what the x-IMU reports
  fitting::MeasuredSignal signal;  // the gyro in rad/s, sensor axes = block axes
  core::Block block = core::Block::FromDensity(0.05, 0.035, 0.2, 2692.0);
  double t0_s = 0.0, alpha_rad = 0.0;
  int impacts = 0;               // impacts found for the ringing
};

namespace mujoco_detail {

inline std::string Xml(const MujocoRockingOptions& o, const Eigen::Quaterniond& q, const Eigen::Vector3d& p) {
  const double mass = 8.0 * o.density_kg_m3 * o.b1_m * o.b2_m * o.h_m;
  const double Ixx = mass / 3.0 * (o.b2_m * o.b2_m + o.h_m * o.h_m);
  const double Iyy = mass / 3.0 * (o.b1_m * o.b1_m + o.h_m * o.h_m);
  const double Izz = mass / 3.0 * (o.b1_m * o.b1_m + o.b2_m * o.b2_m);
  std::string solimp = o.solimp;
  std::replace(solimp.begin(), solimp.end(), ',', ' ');
  const std::string contact =
      fmt::format("solref=\"{} {}\" friction=\"{} 0.005 0.0001\"{}", o.solref_time_constant_s, o.solref_damping_ratio,
                  o.friction, solimp.empty() ? std::string() : fmt::format(" solimp=\"{}\"", solimp));
  std::string proud;
  if (o.proud_vertex >= 1 && o.proud_vertex <= 4) {
    // Vertices V1=(−b1,−b2), V2=(−b1,+b2), V3=(+b1,+b2), V4=(+b1,−b2) of the base; a thin massless pad under one
    // corner, just inside it, reaching proud_corner_m below the base.
    const double sx[] = {-1, -1, 1, 1}, sy[] = {-1, 1, 1, -1};
    const double pad = 0.002;  // half-size of the pad in x and y [m]
    proud = fmt::format("<geom type=\"box\" size=\"{} {} {}\" pos=\"{} {} {}\" mass=\"0\" {}/>", pad, pad,
                        0.5 * o.proud_corner_m, sx[o.proud_vertex - 1] * (o.b1_m - pad), sy[o.proud_vertex - 1] * (o.b2_m - pad),
                        -o.h_m - 0.5 * o.proud_corner_m, contact);
  }
  const Eigen::Vector3d c = o.com_offset_B_m;
  return fmt::format(R"(<mujoco model="rockfit granite block">
  <option timestep="{dt}" gravity="0 0 -9.81"/>
  <worldbody>
    <geom type="plane" size="2 2 0.1" {contact}/>
    <body name="block" pos="{px} {py} {pz}" quat="{qw} {qx} {qy} {qz}">
      <freejoint/>
      <inertial pos="{cx} {cy} {cz}" mass="{mass}" diaginertia="{Ixx} {Iyy} {Izz}"/>
      <geom type="box" size="{b1} {b2} {h}" mass="0" {contact}/>
      {proud}
    </body>
  </worldbody>
</mujoco>
)",
                     fmt::arg("dt", 1.0 / (o.rate_hz * o.steps_per_sample)), fmt::arg("contact", contact),
                     fmt::arg("px", p.x()), fmt::arg("py", p.y()), fmt::arg("pz", p.z()), fmt::arg("qw", q.w()),
                     fmt::arg("qx", q.x()), fmt::arg("qy", q.y()), fmt::arg("qz", q.z()), fmt::arg("cx", c.x()),
                     fmt::arg("cy", c.y()), fmt::arg("cz", c.z()), fmt::arg("mass", mass), fmt::arg("Ixx", Ixx),
                     fmt::arg("Iyy", Iyy), fmt::arg("Izz", Izz), fmt::arg("b1", o.b1_m), fmt::arg("b2", o.b2_m),
                     fmt::arg("h", o.h_m), fmt::arg("proud", proud));
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

}  // namespace mujoco_detail

// Simulates and measures one release. Throws std::runtime_error when MuJoCo cannot load the model.
inline MujocoRockingTrial MakeMujocoRockingTrial(const MujocoRockingOptions& o) {
  MujocoRockingTrial trial;
  trial.block = core::Block::FromDensity(o.b1_m, o.b2_m, o.h_m, o.density_kg_m3);
  trial.t0_s = o.t0_s;
  trial.alpha_rad = o.alpha_rad;
  // The release attitude (ZYX: R = Ry(−α)·Rx(roll)) and the body centre so that the lowest base point touches z = 0.
  const Eigen::Quaterniond q0 = Eigen::Quaterniond(Eigen::AngleAxisd(-o.alpha_rad, Eigen::Vector3d::UnitY()) *
                                                   Eigen::AngleAxisd(o.roll_rad, Eigen::Vector3d::UnitX()));
  double lowest = 0.0;
  Eigen::Vector3d pivot_at_release_B = Eigen::Vector3d::Zero();  // the lowest base point (body origin: the centre)
  const auto consider = [&](const Eigen::Vector3d& v_B) {
    if ((q0 * v_B).z() < lowest) {
      lowest = (q0 * v_B).z();
      pivot_at_release_B = v_B;
    }
  };
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) consider(Eigen::Vector3d(sx * o.b1_m, sy * o.b2_m, -o.h_m));
  }
  if (o.proud_vertex != 0) {
    const double sx[] = {-1, -1, 1, 1}, sy[] = {-1, 1, 1, -1};
    const int k = o.proud_vertex - 1;
    consider(Eigen::Vector3d(sx[k] * o.b1_m, sy[k] * o.b2_m, -o.h_m - o.proud_corner_m));
  }
  const Eigen::Vector3d centre(0.0, 0.0, -lowest);

  const auto dir = std::filesystem::temp_directory_path() / fmt::format("rockfit_mujoco_{}", ::getpid());
  std::filesystem::create_directories(dir);
  const auto xml = dir / "block.xml";
  std::ofstream(xml) << mujoco_detail::Xml(o, q0, centre);
  char error[1000] = "";
  std::unique_ptr<mjModel, mujoco_detail::ModelDeleter> model(mj_loadXML(xml.c_str(), nullptr, error, sizeof error));
  std::filesystem::remove_all(dir);
  if (!model) throw std::runtime_error(std::string("MuJoCo cannot load the block model: ") + error);
  std::unique_ptr<mjData, mujoco_detail::DataDeleter> data(mj_makeData(model.get()));
  // The push: ω_B = (0, w, 0) about the lowest base point, so that the point stays where it is; the free joint
  // takes the linear velocity of the body origin in world axes and the angular velocity in body axes.
  const Eigen::Vector3d w0_B(0.0, o.push_w_y_rad_s, 0.0);
  const Eigen::Vector3d p_pivot_origin_W = -(q0 * pivot_at_release_B);  // origin − lowest point
  const Eigen::Vector3d v0_W = (q0 * w0_B).cross(p_pivot_origin_W);
  for (int i = 0; i < 3; ++i) {
    data->qvel[i] = v0_W[i];
    data->qvel[3 + i] = w0_B[i];
  }
  mj_forward(model.get(), data.get());

  io::BlockMotion& m = trial.motion;
  m.rate_hz = o.rate_hz;
  m.gravity_m_s2 = 9.81;
  const auto samples = static_cast<std::size_t>(std::llround(o.duration_s * o.rate_hz));
  const auto release = static_cast<std::size_t>(std::llround(o.t0_s * o.rate_hz));
  const double dt = 1.0 / (o.rate_hz * o.steps_per_sample);
  // The contact point for the accelerometer's lever: the lowest base vertex, in B (origin at the base centre).
  const auto pivot_B = [&](const Eigen::Quaterniond& q) {
    Eigen::Vector3d best(0, 0, 0);
    double z = 1e9;
    for (double sx : {-1.0, 1.0}) {
      for (double sy : {-1.0, 1.0}) {
        const Eigen::Vector3d v(sx * o.b1_m, sy * o.b2_m, -o.h_m);
        if ((q * v).z() < z) {
          z = (q * v).z();
          best = v + Eigen::Vector3d(0, 0, o.h_m);
        }
      }
    }
    return best;
  };
  m.breaks_s.push_back(o.t0_s);
  Eigen::Vector3d w_prev = w0_B, w_before = Eigen::Vector3d::Zero();  // the push is not an impact
  bool in_impact = false;
  double impact_start = 0.0;
  for (std::size_t n = 0; n < samples; ++n) {
    if (n > release) {
      for (int s = 0; s < o.steps_per_sample; ++s) {
        mj_step(model.get(), data.get());
        const Eigen::Vector3d w(data->qvel[3], data->qvel[4], data->qvel[5]);  // free joint: body-frame ω
        const bool fast = (w - w_prev).norm() / dt > o.impact_acceleration_rad_s2;
        const double t = o.t0_s + data->time;
        if (fast && !in_impact) {
          in_impact = true;
          impact_start = t - dt;
          w_before = w_prev;
        } else if (!fast && in_impact) {
          in_impact = false;
          m.impacts.push_back({impact_start, w_before, w_prev});
          m.breaks_s.push_back(impact_start);
          ++trial.impacts;
        }
        w_prev = w;
      }
    }
    // The block's attitude: its free joint's quaternion (qpos[3..6], w first). data->xquat[0..3] would be the
    // world body's, always the identity.
    const Eigen::Quaterniond q(data->qpos[3], data->qpos[4], data->qpos[5], data->qpos[6]);
    m.q_WB.push_back(q.normalized());
    m.w_B.push_back(n > release ? Eigen::Vector3d(data->qvel[3], data->qvel[4], data->qvel[5]) : Eigen::Vector3d::Zero());
    m.p_BK_B.push_back(pivot_B(q));
  }
  io::SensorMounting mounting;
  mounting.p_BS_B = Eigen::Vector3d(0, 0, 2.0 * o.h_m);
  trial.device = io::MeasureMotion(m, mounting, o.measurement);
  for (std::size_t n = 0; n < trial.device.size(); ++n) {
    trial.signal.t_s.push_back(static_cast<double>(n) / o.rate_hz);
    trial.signal.w_B.push_back(trial.device.gyro_dps[n].cast<double>() * (M_PI / 180.0));
  }
  return trial;
}

// Writes the x-IMU GUI file set of the trial (rate registers, orientation, …) and <prefix>_truth.json with the
// truth (t0_s, alpha_rad) and the options that made it; returns the paths written.
inline std::vector<std::string> WriteMujocoRockingTrial(const std::string& prefix, const MujocoRockingOptions& o,
                                                        const MujocoRockingTrial& trial) {
  io::XimuGuiWriterOptions files;
  files.rotation_matrix_file = false;
  std::vector<std::string> paths = io::WriteXimuGuiCsv(prefix, trial.device, files);
  const std::string truth = prefix + "_truth.json";
  std::ofstream(truth) << fmt::format(
      "{{\"generator\": \"MuJoCo {}\", \"t0_s\": {}, \"alpha_rad\": {}, \"roll_rad\": {}, \"b1_m\": {}, "
      "\"b2_m\": {}, \"h_m\": {}, \"density_kg_m3\": {}, \"com_offset_B_m\": [{}, {}, {}], \"proud_vertex\": {}, "
      "\"proud_corner_m\": {}, \"push_w_y_rad_s\": {}, \"solref\": [{}, {}], \"solimp\": \"{}\", \"seed\": {}, "
      "\"impacts\": {}}}\n",
      mj_versionString(), trial.t0_s, trial.alpha_rad, o.roll_rad, o.b1_m, o.b2_m, o.h_m, o.density_kg_m3,
      o.com_offset_B_m.x(), o.com_offset_B_m.y(), o.com_offset_B_m.z(), o.proud_vertex, o.proud_corner_m, o.push_w_y_rad_s,
      o.solref_time_constant_s, o.solref_damping_ratio, o.solimp, o.measurement.seed, trial.impacts);
  paths.push_back(truth);
  return paths;
}

}  // namespace rockfit::testing

#endif  // ROCKFIT_HAVE_MUJOCO
