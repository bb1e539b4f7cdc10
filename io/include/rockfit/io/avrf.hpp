// Angular velocity reduction factor measured from the peak inclinations (paper Sect. 3.2, docs/design.md §6).
//
// A block released from rest rocks in the plane with its energy held between impacts: at a peak inclination
// φ_i the kinetic energy is zero and the COM stands u_i above its height at rest, so the pre-impact kinetic
// energy of the next impact is m·g·u_i and the post-impact one m·g·u_(i+1). With ω⁺ = r·ω⁻ (2),
//     r_i = √(u_(i+1) / u_i),   AVRF = median of the r_i,
// and the λ of Chatzis' map with the same AVRF follows from the inverse of (6) with b = b1, θ = Θ_yy.
// The COM lies b1 across and h above the b1-edge the block stands on; tilted by φ about that edge it rises by
//     u = b1·sin φ − h·(1 − cos φ)   (the default),
// while the paper prints h·sin φ − b1·(1 − cos φ) with h and b1 swapped; that formula is kept as an option.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/io/drift_correction.hpp"

namespace rockfit::io {

enum class UpliftFormula {
  kComUplift,      // u = b1·sin φ − h·(1 − cos φ), the height gained by the COM (default)
  kPaperPrinted,   // u = h·sin φ − b1·(1 − cos φ), as printed in the paper's Sect. 3.2
};
// "com", "paper".
const char* ToString(UpliftFormula formula);
// The inverse of ToString; false (and *formula untouched) for any other text.
bool FromString(std::string_view text, UpliftFormula* formula);

struct AvrfOptions {
  std::size_t max_peaks = 10;  // the paper's ten peak inclinations (nine ratios)
  std::size_t min_peaks = 3;   // fewer usable peaks (two ratios) is the status kTooFewPeaks
  // A peak of the corrected |φ_y| must stand this far above its bases; 0.002 rad ≈ 0.1° is ten times the
  // angle noise of an x-IMU and far below the inclinations used (> 0.01 rad).
  double min_peak_prominence_rad = 0.002;
  bool refine_peaks = true;    // parabolic vertex through the three samples at each peak (removes O(Δt²) bias)
  UpliftFormula uplift = UpliftFormula::kComUplift;
  void Validate() const;
};

enum class AvrfStatus { kOk, kNoImpact, kTooFewPeaks, kInvalidUplift, kNoBlock };
// "ok", "no_impact", "too_few_peaks", "invalid_uplift", "no_block".
const char* ToString(AvrfStatus status);

struct AvrfResult {
  AvrfStatus status = AvrfStatus::kNoImpact;
  std::string message;               // why there is no value (empty when ok)
  double avrf = 0.0;                 // median of the ratios (only when ok)
  std::vector<double> ratios;        // r_i = √(u_(i+1)/u_i)
  std::vector<double> peak_times_s;  // the peaks used, in time order
  std::vector<double> peak_angles_rad;  // |φ_y| at the peaks
  std::vector<double> uplifts_m;        // u_i
  std::size_t peaks_used = 0;
  std::optional<double> lambda_equivalent;  // λ of (6) with this AVRF (ok and r ≠ −1)
  bool ok() const { return status == AvrfStatus::kOk; }
};

// u(φ) of the chosen formula.
double Uplift(const core::Block& block, double phi_rad, UpliftFormula formula);

// Peaks of |φ_y| after the first impact of `correction` (at most one between consecutive impacts: the highest).
AvrfResult ComputeAvrf(const std::vector<double>& t_s, const DriftCorrection& correction, const core::Block& block,
                       const AvrfOptions& options);

}  // namespace rockfit::io
