// The starting point of a fit from the recording alone (docs/design.md §7: no manual starting point), and the end of
// the fitting window.
//
//  * First base impact: the first peak of |ω_y| (io impact detection) that reaches a fraction of the largest.
//  * Release (t0, α): the planar phase 1 (rocking about the release edge V1V2, core/planar_rocking.hpp) fitted
//    to the measured ω_y from well before the release up to the last sample before the first impact (the fall
//    tabulated, initial_guess_fall.hpp). α is
//    searched around two estimates: the landing rate (LandingRate(α) = peak ω_y, inverted by bisection) and the
//    swept angle ∫ω_y dt up to the impact (robust near the critical angle); t0 = t_impact − T(α).
//  * λ_lon: from the first jump of ω_y, r = ω_y⁺/ω_y⁻ (ω_y keeps its sign when the block rocks on about the
//    far side), through the inverse of (6); then (λ_lat, λ_lon) refined so that the facet impact map (18)+(21)
//    reproduces the measured (ω_x⁺, ω_y⁺). The sign of λ_lat is the sign of ω_x⁺ (for ω_y⁻ > 0).
//  * λ: a default (the global stage scans it over its bounds; it acts only once edge impacts occur).
//  * t_end: the impact that ends phase 4, by default the second base impact: the next |ω_y| peak on the release
//    side (ω_y reversed, base near flat) where |ω_y| drops abruptly.
#pragma once

#include <string>
#include <vector>

#include "rockfit/core/block.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trajectory_error.hpp"
#include "rockfit/io/impact_detection.hpp"

namespace rockfit::fitting {

struct InitialGuessOptions {
  io::ImpactDetectionOptions detection;
  // The first impact is the first |ω_y| peak of at least this fraction of the largest peak: drops and
  // touches before the release are smaller than the landing from a release tilt.
  double first_impact_fraction = 0.5;
  // The base impact ending phase 4 is the n-th |ω_y| peak of at least `later_impact_fraction` of the
  // first impact's peak (n = 2: the second base impact, docs/design.md §7).
  int window_end_impact = 2;
  double later_impact_fraction = 0.2;
  // A later base impact is on the release side (ω_y of the opposite sign to the first landing) and |ω_y| drops
  // by at least this fraction from the peak sample to the next: an impact with a restitution of r < 0.97 does,
  // a smooth maximum (a change of ½·ω̈·Δt², below 1 % at 256 Hz) does not.
  double min_jump_fraction = 0.03;
  // … and the base is back near flat: the tilt about y since the first impact (the elevation of the body x axis,
  // from the attitude integrated from ω with the base flat at the first impact) is at most this fraction of its
  // largest value in between (edge impacts between the far vertices V3, V4 happen at a large tilt about y).
  double flat_tilt_fraction = 0.25;
  // λ when the data do not determine it before the fit (no edge impact seen yet).
  double default_lambda = 1.0;
  // Samples after an impact used for ω⁺ (the median damps the gyro's ringing).
  int post_impact_samples = 3;
  // The phase-1 fit with the fall's nodes from its closed form and t0, α by Brent's method instead of RK4 and
  // golden sections: ~13 ms less a fit (the estimate from 17 % of a fit to 6 %), the same t0 and α to ~4e-9 s and
  // 3e-10 rad. Off by default: the fits after a start moved by that round-off move too, a few by more than the
  // 0.1 % in ε that a change keeping the fits may (fitting/README.md, "Starting point from the data").
  bool closed_form_fall = false;
  void Validate() const;  // throws InvalidArgument
};

struct InitialGuess {
  ParameterSet parameters;        // the input set with t0, α, λ, λ_lat, λ_lon values replaced (clamped to bounds)
  double t_first_impact_s = 0.0;  // sample time of the first impact peak
  double t_end_s = 0.0;           // end of the fitting window (recording time)
  // The base impacts after the one that ends the window (the later return impacts), for a longer window
  // (window_extension.hpp); empty when the window ends at the end of the recording.
  std::vector<double> later_impacts_s;
  double landing_rate_rad_s = 0.0;  // ω_y just before the first impact (planar fit)
  double jump_ratio = 0.0;        // r = ω_y⁺/ω_y⁻ at the first impact
  std::vector<std::string> notes;  // how each value was found, for summaries
};

// The impact peaks of |ω_y| that count as base impacts (first, second, …), in recording time [s].
// Throws BadInput when no impact is found (a recording without a release).
std::vector<double> DetectBaseImpactTimes(const MeasuredSignal& signal, const InitialGuessOptions& options);

// The end of the fitting window: the options.window_end_impact-th base impact; the end of the recording when
// there are fewer impacts.
double DetectWindowEnd(const MeasuredSignal& signal, const InitialGuessOptions& options);

// The release time alone, for a caller that needs t0 only (the rest segment before the release, trial_problem.cpp):
// the first impact and the phase-1 fit of EstimateInitialGuess, without the later base impacts, the first jump and
// the facet map's (λ_lat, λ_lon) grid. With the same options, t0_s is EstimateInitialGuess's t0 bit for bit.
struct ReleaseEstimate {
  double t0_s = 0.0;              // the fit's t0 clamped to the bounds of `base`, or its value when fixed
  double t_first_impact_s = 0.0;  // sample time of the first impact peak (as InitialGuess)
};

// Throws BadInput as EstimateInitialGuess does before it looks after the first impact (no impact; the impact at the
// start of the recording); unlike it, never for a recording that ends at the first impact.
ReleaseEstimate EstimateRelease(const MeasuredSignal& signal, const core::Block& block, const ParameterSet& base,
                                const InitialGuessOptions& options = {});

// The estimate above. `base` supplies bounds and fixed values: fixed parameters keep their values.
// Throws BadInput when the recording shows no release (no impact, nothing before it).
InitialGuess EstimateInitialGuess(const MeasuredSignal& signal, const core::Block& block, const ParameterSet& base,
                                  const InitialGuessOptions& options = {});

}  // namespace rockfit::fitting
