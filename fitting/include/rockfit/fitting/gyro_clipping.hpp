// Samples where the recorded gyro sits at its full scale (clipped): there the recording says only "at least this
// fast" on the axis at the rail. The fit enters them into the error (28) as censored observations (a one-sided
// misfit on that axis, MeasuredSignal::censored_axes and NodeMisfit) or, with `censored` off, leaves them out of
// it; either way it leaves them out of the noise floor at rest and of the data estimate of phase 1
// (MeasuredSignal::excluded), and says how many clipped (ModelErrorStatement::clipped_samples; fitting/README.md,
// "Clipped gyro samples").
//
// Detected from the data alone: one full scale serves all three gyro axes (x-IMU register 8), so the rail is the
// largest |ω| component of the whole recording, and a gyro that clipped reports that value again and again. A
// recording that did not clip reaches its largest |ω| in one sample — the last before an impact, where ω changes
// fastest — so two or more samples at the same largest |ω| are taken for a rail. The check runs on the block-frame
// ω, which keeps the sensor's values for a mounting that permutes or flips axes (not for a general rotation).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

struct GyroClippingOptions {
  bool enabled = true;
  // A component is at the rail when |ω| ≥ (1 − level_tolerance)·(the largest |ω| component). Relative, 1e-4: a
  // clipped axis repeats one output code; 1e-4 of a rail of ±100 °/s is 0.01 °/s, below the x-IMU's 1/16 °/s step,
  // so the distinct values of a smooth peak do not count.
  double level_tolerance = 1e-4;
  // The rail is accepted when at least this many samples reach it: one sample is every recording's largest value.
  std::size_t min_samples = 2;
  // How (28) treats a clipped sample: true, as a censored observation (NodeMisfit: its axes at the rail give a
  // one-sided misfit, its other axes the plain one); false, left out (no weight).
  bool censored = true;
  void Validate() const;  // throws InvalidArgument
};

struct GyroClipping {
  bool detected = false;
  double level_rad_s = 0.0;   // the largest |ω| component of the recording (the rail when detected)
  std::size_t samples = 0;    // samples with a component at the rail; 0 unless detected
  std::vector<bool> clipped;  // one per sample when detected, else empty
  std::vector<std::uint8_t> axes;  // one per sample when detected, else empty: bit a set when axis a is at the rail
};

// Never throws for the signal (an empty one has no rail); InvalidArgument for bad options.
GyroClipping DetectGyroClipping(const MeasuredSignal& signal, const GyroClippingOptions& options = {});

}  // namespace rockfit::fitting
