// Whether a recording calls for the release roll β as a fit parameter, and where to start it (fitting/README.md,
// "The release roll in the fit").
//
// A block released on one corner of its release edge (core/rolled_release.hpp) rolls about the base's inward axis
// (the body x axis) while it falls: ω_x = dβ/dt for the attitude R_WB = Ry(−α)·Rx(β), so the gyro sees a lateral
// rate from the first instant of the fall, and the roll angle β(t) = β − ∫ω_x dt goes through 0 when the edge's other
// corner lands (after which a rolled block rocks from corner to corner). A release on the edge (β = 0) shows no ω_x
// before the first base impact at all: the motion is planar until then.
//
// The rule looks at the fall, from the end of the rest segment (t_release − rest margin, where the gyro bias and
// the noise are measured) to the sample before the first base impact:
//
//   ω'_x,k = ω_x,k − s·ω_y,k,   s = Σ ω_x ω_y / Σ ω_y²   (over the fall)
//
// removes what a gyro whose x axis leans towards y by an angle s would see of a planar rocking (axis
// non-orthogonality, a mounting off by a fraction of a degree; a rolled block's lateral rocking is not
// proportional to ω_y and survives it). The roll the gyro sees is the largest |∫ω'_x dt| over the fall (a running
// sum Δt·Σ ω'_x), its noise σ_β = σ_x·Δt·√(Σ c_k²), σ_x the RMS of ω_x at rest and c_k the weights of the sum with
// the regression in it (c_k = 1 − ω_y,k Σω_y / Σω_y², so σ_β ≤ σ_x·Δt·√n). β is fitted when
//
//   max_k |Δt·Σ_{j≤k} ω'_x,j|  ≥  min_roll_to_noise · σ_β   (8 by default).
//
// The start: β₀ = −Δt·Σ ω'_x up to the first peak of |ω'_x| that stands min_rate_to_noise·σ_x out of the noise (the
// other corner's landing, where β(t) = 0), clamped to the bounds; the running sum at the landing is about 0.8–1 β
// on the MuJoCo releases (the soft landing spreads over a sample or two).
#pragma once

#include <string>
#include <string_view>

#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trajectory_error.hpp"

namespace rockfit::fitting {

// off: β held at its given value; on: β fitted (started from the data); auto: fitted when the rule above says so.
enum class ReleaseRollMode { kOff, kAuto, kOn };
const char* ToString(ReleaseRollMode mode);                     // "off", "auto", "on"
bool FromString(std::string_view text, ReleaseRollMode* value);  // the inverse of ToString
ReleaseRollMode ParseReleaseRollMode(const std::string& name);   // throws InvalidArgument naming the choices

struct ReleaseRollChoiceOptions {
  ReleaseRollMode mode = ReleaseRollMode::kAuto;
  // The roll seen over its noise that turns β on. White noise at rest would pass 5 σ about once in 10⁶
  // recordings (the running sum's largest |value| exceeds a level about four times as often as its end does one
  // sign), but the 16 planar sample recordings reach 1.4–4.2 σ (the rest's σ_x understates the fall's); 8 leaves
  // them a factor of 2 and still turns β on for MuJoCo rolls from 0.3 mrad (9–12 σ; 0.1 mrad reaches 3–4 σ).
  double min_roll_to_noise = 8.0;
  // A rate peak of ω'_x this many σ_x above the noise marks the other corner's landing (for the start only).
  double min_rate_to_noise = 5.0;
  // The rest segment before the release (as the gyro bias is measured, trial_problem.hpp).
  double rest_margin_s = 0.05;
  double rest_min_duration_s = 0.1;
  void Validate() const;  // throws InvalidArgument
};

struct ReleaseRollChoice {
  ReleaseRollMode mode = ReleaseRollMode::kAuto;
  bool judged = false;        // a rest segment and a fall were there to measure (auto and on)
  bool fitted = false;        // β is a fit parameter
  double roll_seen_rad = 0.0;     // max |Δt·Σ ω'_x| over the fall (0 when not judged)
  double roll_noise_rad = 0.0;    // σ_β
  double leak = 0.0;              // s, the part of ω_y removed from ω_x
  double start_rad = 0.0;         // β₀ (0 when β is not fitted or not judged)
  double fall_start_s = 0.0, fall_end_s = 0.0;  // the samples summed (recording time)
  std::string reason;         // one sentence for people
};

// The choice for a recording whose gyro bias at rest is already removed; t_release_s and t_first_impact_s are the
// data estimates (initial_guess.hpp). Never throws for short or odd signals (judged = false instead; then auto
// leaves β off and on starts it at 0); InvalidArgument for bad options.
ReleaseRollChoice ChooseReleaseRoll(const MeasuredSignal& signal, double t_release_s, double t_first_impact_s,
                                    const ReleaseRollChoiceOptions& options = {});

// {"mode", "judged", "fitted", "roll_seen_rad", "roll_noise_rad", "leak", "start_rad", "reason"}, for the fit JSON.
std::string ReleaseRollChoiceJson(const ReleaseRollChoice& choice);
// One line for the tables: "fitted (auto): a roll of 4.2 mrad seen in the fall, 61 × its noise; start 4.1 mrad".
std::string ReleaseRollChoiceText(const ReleaseRollChoice& choice);

}  // namespace rockfit::fitting
