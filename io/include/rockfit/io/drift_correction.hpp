// Drift correction of the Euler angles as in the paper's Sect. 3.1 (docs/design.md §6).
//
// At every impact of the base detected as a peak of |ω_y| the block lands on a base edge along x or on the
// whole base, so the true φ_y is zero there; the measured φ_y at those instants is the drift. The correction
// subtracts the piecewise-linear interpolant through these values (constant before the first and after the last
// impact). Peaks of |ω_y| where the gyro shows that φ_y is not zero (impact_consistency.hpp) are left out.
// φ_x is corrected the same way at the peaks of |ω_x| (landings on a base edge along y or on the whole base),
// and, where ω_x has no significant peak between two impacts (planar rocking), at the |ω_y| impacts.
// φ_z is left as measured.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rockfit/io/impact_anchor.hpp"
#include "rockfit/io/impact_consistency.hpp"
#include "rockfit/io/impact_detection.hpp"
#include "rockfit/io/impact_zero_crossing.hpp"
#include "rockfit/io/recording.hpp"

namespace rockfit::io {

// How the drift at an impact is read off the measured angle.
enum class AnchorMethod {
  kSubsample,  // the impact time and angle inside the sample interval (impact_anchor.hpp); the default
  kSample,     // the angle at the sample of the |ω| peak, as the paper describes it
};
// "subsample", "sample".
const char* ToString(AnchorMethod method);
// The inverse of ToString; false (and *method untouched) for any other text.
bool FromString(std::string_view text, AnchorMethod* method);

struct DriftCorrectionOptions {
  ImpactDetectionOptions impacts;
  AnchorMethod anchor_method = AnchorMethod::kSubsample;
  // Length of the local fit on each side of an impact (kSubsample); 0.02 s = 5 samples at 256 Hz, shorter
  // than the quarter period of the smallest rocking the detector keeps.
  double anchor_fit_half_window_s = 0.02;
  // A rate jump smaller than this does not locate an impact inside its sample interval.
  double min_rate_jump_rad_s = 0.01;
  // An |ω_x| peak this close to an impact of φ_y is the same landing on the whole base. 0.008 s = 2 samples at
  // 256 Hz: ringing after an impact can delay the peak of the smaller rate that much; two distinct landings that
  // close (a vertex wobbling between two others) cannot be told apart at that rate anyway.
  double same_impact_s = 0.008;
  // Keep only the peaks where the angle integrated from the gyro is back at zero (impact_consistency.hpp).
  bool check_zero_instants = true;
  ImpactConsistencyOptions consistency;
  // A recording without attitude (gyro_attitude.hpp): after a first correction of the angle integrated by the
  // mean rule, its anchors are moved to where the angle minus its slowly varying error crosses zero
  // (impact_zero_crossing.hpp), the angle is integrated again with those sample intervals split there, and
  // corrected again; this many times (each pass reads the error from an angle with fewer misplaced rate jumps).
  // 0: the mean rule only. 3 gave the closest agreement with the attitude files on the sample campaign and on
  // 16 further trials, 2 and 4 slightly less close (io/README.md, "Where in the interval").
  int gyro_impact_passes = 3;
  ZeroCrossingOptions zero_crossing;
  void Validate() const;
};

// Which gyro axis marked an anchor.
enum class AnchorSource { kOmegaY, kOmegaX };
// "omega_y", "omega_x".
const char* ToString(AnchorSource source);
bool FromString(std::string_view text, AnchorSource* value);  // the inverse of ToString

struct Anchor {
  double t_s = 0.0;          // impact time [s] (sub-sample with kSubsample)
  std::size_t index = 0;     // sample of the |ω| peak that marked the impact
  double value_rad = 0.0;    // measured angle at t_s: the drift that is removed there
  AnchorSource source = AnchorSource::kOmegaY;
  double peak_rad_s = 0.0;   // |ω| at the peak sample
};

struct DriftCorrection {
  std::vector<Eigen::Vector3d> euler_raw_zyx;        // (φz, φy, φx) as measured [rad]
  std::vector<Eigen::Vector3d> euler_corrected_zyx;  // φz as measured, φy and φx corrected [rad]
  std::vector<Anchor> impacts_y;  // anchors of φ_y: the detected impacts, in time order
  std::vector<Anchor> anchors_x;  // anchors of φ_x, in time order (source says which gyro axis)
  std::size_t omega_x_peaks = 0;  // how many anchors of φ_x came from |ω_x| peaks
  std::size_t rejected_y = 0;     // peaks of |ω_y| where φ_y is not zero (not impacts)
  std::size_t rejected_x = 0;     // candidate anchors of φ_x where φ_x is not zero
  std::vector<std::string> warnings;
  // Where the angles came from: "file", or how they were integrated from the gyro (gyro_attitude.hpp) when the
  // recording has none.
  std::string attitude = "file";
  double first_impact_s() const { return impacts_y.empty() ? 0.0 : impacts_y.front().t_s; }
  double last_impact_s() const { return impacts_y.empty() ? 0.0 : impacts_y.back().t_s; }
};

// A recording without Euler angles gets them from its gyro first (WithAttitude, gyro_attitude.hpp).
// Throws BadInput for an empty recording or one without a valid rate.
DriftCorrection CorrectDrift(const Recording& recording, const DriftCorrectionOptions& options);

// The piecewise-linear interpolant through (anchor time, anchor value), constant outside; 0 without anchors.
double DriftAt(const std::vector<Anchor>& anchors, double t_s);

}  // namespace rockfit::io
