// A synthetic x-IMU recording of one rocking trial: the block rests at its release tilt until t0, rocks as the
// hybrid simulator says (core/simulator.hpp) until it comes to rest (or the recording ends), and rests after;
// the measurement model (synth_measurement.hpp) turns that motion into device samples, and the GUI CSV
// writer (ximu_gui_writer.hpp) into files, with <prefix>_truth.json holding every input and the true motion's
// summary and impact log. Deterministic: the same inputs give the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/io/synth_measurement.hpp"
#include "rockfit/io/synth_motion.hpp"
#include "rockfit/io/ximu_gui_writer.hpp"

namespace rockfit::io {

struct SynthRecordingOptions {
  double t0_s = 2.0;          // release time in recording time [s]
  double duration_s = 10.0;   // recording length [s]: round(duration·rate) samples, the n-th at n / rate_hz (with a
                              // slower orientation rate, cut back to end on an orientation sample)
  double rate_hz = 256.0;     // inertial (gyroscope) rate, an x-IMU rate 2^(v−1) Hz
  Eigen::Matrix3d R_BS = Eigen::Matrix3d::Identity();  // mounting, sensor → block
  std::string mounting_text = "x,y,z";                 // how the mounting was given (for the truth file)
  // The accelerometer's position in B [m]; default the centre of the top face (0, 0, 2h).
  std::optional<Eigen::Vector3d> sensor_position_B;
  MeasurementOptions measurement;
  XimuGuiWriterOptions files;
  // Simulator settings. Synthesize() overrides sample_times_s, stop (t_max) and t_max_s (the last sample of the
  // recording) and needs sample_attitude; the rest (release edge, tolerances, Zeno and rest thresholds) is used.
  core::SimulationOptions simulation;
  std::string command_line;  // provenance, copied into the truth file when not empty

  // Throws InvalidArgument naming the bad option.
  void Validate() const;
};

struct SynthRecording {
  core::Trajectory trajectory;  // sampled at τ = 0 and at the recording's sample times after the release
  BlockMotion motion;           // the true motion at every inertial sample (recording time)
  SensorMounting mounting;
  DeviceSamples device;
  std::size_t release_sample = 0;        // first inertial sample at or after t0
  std::optional<double> phase4_end_s;    // recording time of the impact ending phase 4 (docs/design.md §4), if any
};

// Simulates and measures one trial. Throws InvalidArgument for bad options, NumericalFailure when the
// simulation fails or the block overturns (a synthetic rocking trial needs a block that comes back).
SynthRecording Synthesize(const core::Block& block, const core::ModelParameters& params, const SynthRecordingOptions& options);

// Writes the x-IMU GUI CSV set and <prefix>_truth.json; returns the paths written. Throws OutputError.
std::vector<std::string> WriteSynthRecording(const std::string& prefix, const core::Block& block,
                                             const core::ModelParameters& params, const SynthRecordingOptions& options,
                                             const SynthRecording& recording);

}  // namespace rockfit::io
