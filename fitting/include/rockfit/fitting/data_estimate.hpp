// The starting point of a fit from the recording alone (no manual guess, DESIGN §7):
//
//  * impacts: peaks of |ω_y| (io::DetectRatePeaks, DESIGN §6); the first facet impact t1 is the first peak that
//    reaches half the largest |ω_y| of the recording. The window ends where phase 4 ends (Sect. 5.1): at the
//    first later peak where ω_y < 0 — the block falls back onto its release side, V1 or V2 lands — and
//    |ω_y| ≥ kPhaseFourFraction·ω⁻ (ringing and lateral edge impacts near ω_y ≈ 0 do not count); or, with
//    t_end_impact = N, at the N-th peak counted from t1;
//  * α = ∫ ω_y dt over phase 1 (the block turns from tilt α to flat), from the end of the rest before the
//    release to t1; t0 = t1 − T(α) with the fall time T of core::FallTime. (α from the pre-impact rate by
//    energy, ½Jω⁻² = m g R (cos(θ_c − α) − cos θ_c), is reported for comparison: it is ten times more
//    sensitive to the unknown sub-sample impact time and to ringing);
//  * λ_lon from the first jump r = ω_y⁺/ω_y⁻ through the inverse of (6) about y (θ = Θ_yy, b = b1);
//  * λ_lat by matching ω_x⁺/ω_y⁻ with the unified facet map (18)+(21)+(24) over the bounds of λ_lat;
//  * λ from the decay of the lateral rocking: the median ratio of successive peaks of |ω_x| in the window,
//    through the inverse of (6) about x (θ = Θ_xx, b = b2), when that ratio is in (0, 1).
// The one-sided values are extrapolated to the impact time: ω⁻ by a straight line through the last samples
// before it, ω⁺ by a parabola through the samples of the next ~60 ms (the gyros ring after impacts; a single
// sample, or a short line, would carry the ringing).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/io/impact_detection.hpp"

namespace rockfit::fitting {

struct EstimateOptions {
  io::ImpactDetectionOptions impacts;
  // 0: the window ends where phase 4 ends (rule above); N ≥ 1: at the N-th |ω_y| peak counted from the first
  // facet impact (1 = that impact).
  int t_end_impact = 0;
  // The window ends this long before the sample of that impact's |ω_y| peak [s]: a simulated impact right at
  // t_end moves in and out of the window as the parameters change and makes ε jump; ending a few samples
  // early keeps the end of the window in smooth motion.
  double t_end_margin_s = 0.012;
  // Samples before an impact for the straight line giving ω⁻ …
  int side_samples = 5;
  // … and after it for the parabola giving ω⁺ (16 samples at 256 Hz span about two periods of the ringing).
  int post_impact_samples = 16;
  // Gyro bias: the mean ω over the samples at rest that end this long before the estimated release, if they
  // last at least rest_min_duration_s. The paper's x-IMU has biases of a few 0.01 rad/s.
  double rest_margin_s = 0.05;
  double rest_min_duration_s = 0.1;
  // t0 bounds when the parameter set leaves them open: the estimate ± this [s], within the recording.
  double t0_halfwidth_s = 0.1;
  void Validate() const;  // throws InvalidArgument
};

struct DataEstimate {
  ParameterSet parameters;        // the estimate in the caller's bounds (t0 bounds narrowed if they were open)
  double first_impact_s = 0.0;    // t1 (recording time)
  double t_end_s = 0.0;           // end of the window (t_end_margin_s before the impact that ends it)
  double t_end_impact_s = 0.0;    // the |ω_y| peak of the impact that ends the window
  std::vector<double> impact_times_s;  // all detected |ω_y| peaks
  Eigen::Vector3d rest_bias_rad_s = Eigen::Vector3d::Zero();
  bool bias_estimated = false;
  double w_minus_rad_s = 0.0;     // ω_y just before t1
  double alpha_from_energy_rad = 0.0;  // the energy estimate of α from ω⁻, for comparison
  Eigen::Vector3d w_plus_rad_s = Eigen::Vector3d::Zero();  // ω just after t1
  std::vector<std::string> notes;     // how each value was obtained, fallbacks
  std::vector<std::string> warnings;  // data that does not look like a release on V1V2
};

// Throws BadInput when the recording has no impact (nothing to fit) or fewer impacts than t_end_impact needs
// (with a hint to give --t-end). `signal` must be uniform in time.
DataEstimate EstimateFromData(const core::Block& block, const MeasuredSignal& signal, const ParameterSet& parameters,
                              const EstimateOptions& options);

}  // namespace rockfit::fitting
