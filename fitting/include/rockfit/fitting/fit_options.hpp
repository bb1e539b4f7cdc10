// Every knob of the fitter, with its default and the criterion it controls. FitOptions::Validate() names the
// first bad option. Per-parameter settings are arrays indexed by ParameterId (t0, α, λ, λ_lat, λ_lon, τ_edge).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "rockfit/fitting/final_stage.hpp"
#include "rockfit/fitting/gyro_scale.hpp"
#include "rockfit/fitting/lateral_motion_check.hpp"
#include "rockfit/fitting/lateral_rescan.hpp"
#include "rockfit/fitting/model_error.hpp"
#include "rockfit/fitting/motion_before_release.hpp"
#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/window_extension.hpp"

namespace rockfit::fitting {

using PerParameter = std::array<double, kNumParameters>;

enum class FitMethod { kNelderMead, kCeres, kAuto };
const char* ToString(FitMethod method);             // "nelder-mead", "ceres", "auto"
bool FromString(std::string_view text, FitMethod* value);  // the inverse of ToString
FitMethod ParseFitMethod(const std::string& name);  // throws InvalidArgument

// NLopt LN_NELDERMEAD (as MATLAB's fminsearch in the paper, Sect. 5.1).
struct NelderMeadOptions {
  int max_evaluations = 1500;
  // Stops when one step changes ε by less than this [rad/s] …
  double ftol_abs_rad_s = 1e-7;
  // … or moves every parameter by less than its xtol_abs (units of the parameter).
  PerParameter xtol_abs = {1e-5, 1e-5, 1e-4, 1e-4, 1e-5, 1e-7, 1e-6};
  // Size of the initial simplex along each parameter.
  PerParameter initial_step = {4e-3, 5e-3, 0.2, 0.3, 0.05, 1e-3, 2e-3};
  // After convergence, restart from the best point with a fresh simplex up to this many times while that
  // improves ε by more than ftol_abs_rad_s (within max_evaluations in total).
  int restarts = 2;
  void Validate() const;
};

// The default of CeresOptions::exact_jacobian (fit_options.cpp).
extern const bool kDefaultExactJacobian;

// Ceres trust-region least squares on per-sample residuals (see fitting/README.md, "Ceres back end").
struct CeresOptions {
  int max_iterations = 40;
  double function_tolerance = 1e-7;   // relative change of the Ceres cost
  double parameter_tolerance = 1e-8;  // relative step size
  double gradient_tolerance = 1e-10;
  // Soft-L1 scale c [rad/s]: residuals well above c count linearly (the sum then approximates (28)), those
  // below c quadratically, which keeps the cost smooth at a perfect fit. Gyro noise is ~0.01 rad/s.
  double soft_l1_scale_rad_s = 0.02;
  // Central-difference steps per parameter. Impacts make the simulated ω jump, so residuals are only
  // piecewise smooth in the parameters; steps of a fraction of a sample period (t0) or of the typical
  // resolution (others) average over that instead of differentiating it.
  PerParameter difference_step = {5e-4, 5e-4, 5e-3, 1e-2, 2e-3, 1e-4, 2e-4};
  // Use the model's exact derivatives (residual_jacobian.hpp) wherever it gives them, in the search and in the
  // covariance; the differences above elsewhere (and throughout under a gyro scale estimate, whose dependence on
  // the parameters the model's derivatives do not include).
  bool exact_jacobian = kDefaultExactJacobian;
  void Validate() const;
};

// Global stage: multi-start on a short first window, continuation to the full window (global_stage.hpp).
struct GlobalStageOptions {
  bool enabled = true;
  int num_samples = 32;          // Latin-hypercube starts in the first window (plus the data estimate)
  int num_polished = 6;          // best distinct starts polished there (the best of each sign of λ_lat included)
  int polish_evaluations = 120;  // Nelder–Mead evaluations per polished start
  int num_continued = 4;         // polished starts carried to the full window (the best of each sign of λ_lat first)
  // The first window ends this long after the model's first impact [s]: long enough to see the jump and the
  // start of the lateral motion, short enough that no lateral half-cycle completes.
  double first_window_s = 0.03;
  double continuation_growth = 2.0;   // each window is this factor longer (after the first impact)
  int continuation_evaluations = 100; // Nelder–Mead evaluations per continuation window
  double continuation_step_fraction = 0.25;  // their initial simplex, as a fraction of nelder_mead.initial_step
  // The stop rule of the continuation: after each window, a carried start whose (28) there exceeds this factor
  // times the best carried start's is dropped (0: none is). On the sample campaign and 100 coverage-study trials
  // the start that won on the full window had at most 2.2 times the best (28) of any window on its way.
  double continuation_prune_ratio = 3.0;
  // A parameter that starts acting in a continuation window (λ at the first edge impact) is first scanned
  // over its bounds at this many equally spaced values.
  int scan_points = 48;
  // The scans over bounds (above, the final scan, the joint scan) first bound each point's (28) from below by a
  // run over this fraction of the window after t0 (prefix_screen.hpp) and run the whole window only where the
  // bound leaves the point a chance: the same scan results for less simulated time. 0: no screen.
  double scan_prefix_fraction = 0.7;
  // On the full window, scan every parameter sampled over its whole bounds once more, then search locally.
  bool final_scan = true;
  // Refinement of the best continued start: a joint scan of λ (scan_points values over its bounds) and λ_lat
  // (joint_scan_lat_points values within ±joint_scan_lat_fraction of its value; 0 points: no joint scan)
  // on the full window, then the best point and the best of the joint scan are each carried once more from
  // the first window to the full window (global_stage.hpp).
  bool refine = true;
  int joint_scan_lat_points = 13;
  double joint_scan_lat_fraction = 0.2;
  // … and, after that pass, a scan along the ridge t0 + T(α) = const at ridge_points values of t0 within
  // ±ridge_t0_halfwidth_s (fewer than 1: no ridge scan), λ_lon re-fitted at each from three values
  // ridge_lambda_lon_step apart; T'(α) by central differences with the α step ridge_alpha_difference_rad.
  // 21 (steps of 1 ms) instead of 41: on the 16 sample trials and 100 coverage-study trials ε rose by at most
  // 0.04 % and the coverage held (fitting/README.md, "The global stage"), for half the ridge's runs.
  int ridge_points = 21;
  double ridge_t0_halfwidth_s = 0.01;
  double ridge_lambda_lon_step = 0.01;
  double ridge_alpha_difference_rad = 1e-4;
  std::uint64_t seed = 20211230;
  // Relative tolerance of the simulator in this stage (absolute: 100 times smaller); 0 keeps the model's own.
  // The stage only has to find the basin: at 1e-9 one evaluation of (28) costs about a quarter less than at the
  // default 1e-12 and ε moves by ~5e-9 relative (tests/bench/bench_fit.cpp, BM_Error28EvaluationAtTolerance). The
  // local stages, the intervals and every ε reported run at the model's own tolerance.
  double simulation_rel_tol = 1e-9;
  // Half-widths of the sampling box around the data estimate for the parameters that phase 1 determines
  // well; the other parameters are sampled over their whole bounds.
  double t0_halfwidth_s = 0.015;
  double alpha_halfwidth_rad = 0.015;
  void Validate() const;
};

// "Not identifiable": ε does not change when the parameter is moved by ±probe_step (within its bounds).
struct IdentifiabilityOptions {
  PerParameter probe_step = {2e-3, 2e-3, 0.1, 0.2, 0.05, 1e-3, 2e-3};
  // |Δε| ≤ relative_tolerance·ε counts as no change: changes of ε below round-off of its sum.
  double relative_tolerance = 1e-9;
  void Validate() const;
};

// Intervals for the fitted parameters (uncertainty.hpp, fitting/README.md "Intervals").
//  kNone:      standard errors only (linearised, AR(1) noise correction).
//  kFast:      linearised intervals value ± z·σ, σ from the Gauss–Newton covariance with the noise level and
//              its correlation in time estimated from the residuals (long-run variance, Bartlett window).
//  kThorough:  profile intervals of the sum of squares behind (28): each parameter is stepped outwards
//              from the optimum, the others re-fitted at every step, until the rise exceeds the χ²₁ quantile
//              times the same effective noise level; curved ridges and bounds are followed, not linearised.
enum class IntervalMethod { kNone, kFast, kThorough };
const char* ToString(IntervalMethod method);                // "none", "fast", "thorough"
bool FromString(std::string_view text, IntervalMethod* value);  // the inverse of ToString
IntervalMethod ParseIntervalMethod(const std::string& name);  // throws InvalidArgument

// How kThorough re-fits the other parameters at a profile point (and minimises S from the fit first):
//  kNelderMead  NLopt's simplex, IntervalOptions::profile_evaluations (centre_evaluations) evaluations;
//  kExact       Ceres (Levenberg–Marquardt) on the least-squares residuals with the model's exact Jacobian,
//               warm-started as the simplex is; Nelder–Mead as above, from the same start, where the model gives no
//               exact Jacobian, Ceres fails, stops at its iteration limit, or ends above its start or past the
//               profile's 95 % crossing (the better of the two ends is kept). fitting/README.md, "Intervals".
enum class ProfileRefit { kNelderMead, kExact };
const char* ToString(ProfileRefit refit);                     // "nelder-mead", "exact"
bool FromString(std::string_view text, ProfileRefit* value);  // the inverse of ToString

// The calibrated defaults of IntervalOptions::model_error_widening and t0_floor_samples, and the default of
// IntervalOptions::profile_refit (fit_options.cpp).
extern const double kDefaultModelErrorWidening;
extern const double kDefaultT0FloorSamples;
extern const ProfileRefit kDefaultProfileRefit;

struct IntervalOptions {
  IntervalMethod method = IntervalMethod::kFast;  // the command line defaults to kThorough (--intervals)
  // Largest lag of the residual autocorrelation that enters the effective noise level [s]: ringing after
  // impacts (tens of ms) and slowly varying model error make neighbouring residuals alike.
  double noise_correlation_window_s = 0.1;
  // Factor on every effective noise variance for what the noise model cannot see: ringing follows the impacts
  // (systematic, not noise) and the model is not the device. Calibrated on the coverage study of
  // tools/coverage_study.py (seed 1; fitting/README.md, "Intervals"): with 1 the 95 % profile intervals held
  // the truth of α in 88 % and of λ_lat in 76 % of the trials.
  double model_error_allowance = 2.0;
  // kThorough: the 95 % interval is the hull of the profile interval and the linearised one (both with the
  // same noise level). Measured on the coverage study: the profile alone held λ_lat in 86 % of the trials at
  // 95 %, the hull in 92 % (fitting/README.md, "Intervals").
  bool hull_with_linearised = true;
  // The 68 % interval uses the bulk noise level of the standard errors — s² inflated only for the lag-1
  // correlation of the residuals, (1 + ρ₁)/(1 − ρ₁) — instead of κ_j·allowance: the errors of the fitted
  // parameters are heavy-tailed (most are of the size of the standard error, a few many times larger), so
  // one noise level cannot put both levels on target. Measured on the coverage study (fitting/README.md,
  // "Intervals"): with the 95 % level's noise the 68 % intervals held the truth in 80–93 % of the trials
  // for t0, α and λ_lon. false: both levels use κ_j·allowance.
  bool bulk_noise_for_68 = true;
  // kThorough: the 68 % interval from the profile too (the crossing of the signed root at 1) instead of the
  // linearised value ± σ_j at the 68 % level's noise. Measured on the coverage study: the profile's 68 %
  // intervals are 1.2–1.9 times wider than the linearised ones (medians) and held the truth of t0 and λ_lon
  // in 82–84 % of the trials, the linearised ones in 66–83 %.
  bool profile_68 = false;
  // Intervals under model error (model_error_widening.hpp): every 95 % interval's half-widths × f =
  // √(1 + c²·(r² − 1)), r = ε/ε_noise the ratio of the model-error statement (model_error.hpp), c this
  // coefficient (0: off). Calibrated on the tuning families of the coverage studies (fitting/README.md,
  // "Intervals under model error"): the smallest c with 95 % coverage of t0 and α ≥ 90 % on each of them.
  double model_error_widening = kDefaultModelErrorWidening;
  // A floor on t0's 95 % half-widths, in sample periods, added in quadrature (0: off): soft contact, clock
  // error, jitter and dropped samples move the apparent first impact by a fraction of a sample without raising
  // ε. Calibrated with model_error_widening.
  double t0_floor_samples = kDefaultT0FloorSamples;
  // Nelder–Mead evaluations per profile point (the other parameters re-fitted, warm-started).
  int profile_evaluations = 120;
  // Evaluations of the least-squares refinement of the optimum that the profiles start from.
  int centre_evaluations = 300;
  // How the others are re-fitted at each profile point and the optimum refined (ProfileRefit above), and the
  // Ceres iterations of one exact re-fit (each a model run with sensitivities, a few plain runs' cost) and of the
  // exact refinement of the optimum.
  ProfileRefit profile_refit = kDefaultProfileRefit;
  int refit_iterations = 20;
  int centre_iterations = 40;
  // kExact: Nelder–Mead also where Ceres stops at its iteration limit or ends past the profile's 95 % crossing
  // (ProfileRefit above). false: Ceres' end is kept wherever it lies below its start — 2–4 times fewer simulations
  // for the intervals, but Ceres stalls on the ripples of S and ends some profiles early (fitting/README.md,
  // "Intervals", "Exact re-fits, measured").
  bool refit_checked = true;
  // Profile points per side at most.
  int profile_points = 14;
  // The profile points aimed at the 95 % crossing of the signed root ρ (profile_steps.hpp): the first at
  // profile_aim_rho·σ_j, each next one by the secant of ρ, one point inside the bracket where the point beyond
  // lies past profile_refine_above_rho; the re-fits start from the better of the previous point and its
  // shift along the linearised ridge. Measured (fitting/README.md, "Intervals"): the intervals' simulations 37 %
  // fewer than with the fixed grid; ε and coverage kept on the sample campaign and coverage study seed 1, but on
  // seed 2 (ringing ×2) ε rose by 0.19–0.30 % on two trials and the 68 % coverage fell by 4 values: off.
  // false: the fixed grid 1, 2, then × profile_growth times σ_j, each re-fit started from the previous point.
  bool profile_aimed = false;
  double profile_aim_rho = 2.2;           // a little beyond 1.96, so that a quadratic profile brackets it at once
  double profile_refine_above_rho = 3.0;  // a first bracket this loose is refined by one point inside it
  double profile_growth = 1.5;  // the fixed grid: factor between successive offsets (after the first two)
  // Smallest profile step per parameter (units of the parameter), used where the linearised σ is smaller or
  // not available: about a tenth of a sample period for t0, the resolution of the model otherwise.
  PerParameter min_step = {2e-4, 2e-4, 0.01, 0.01, 0.005, 1e-5, 1e-4};
  // A 95 % interval wider than this fraction of the parameter's range counts as not determining it.
  double undetermined_range_fraction = 0.5;
  void Validate() const;
};

struct FitOptions {
  FitMethod method = FitMethod::kAuto;
  // kAuto with ceres.exact_jacobian: the exact Ceres stage runs first from the global stage's point, and the local
  // Nelder–Mead only where Ceres had no exact derivatives throughout, failed, or ended above its start (then from
  // the better of the two points). false: Nelder–Mead, then the Ceres polish, as without exact derivatives.
  bool auto_exact_ceres_first = false;
  // That Ceres stage's soft-L1 scale c as this fraction of the global stage's ε (at most ceres.soft_l1_scale_rad_s):
  // residuals well above c count linearly, so the Ceres cost approaches c·T_ref·(28). With c = 0.02 rad/s (mostly
  // quadratic at ε of 5 mrad/s) it ended above the global point, by 0.01–0.1 %, on 13 of the 16 sample trials.
  double auto_soft_l1_fraction = 0.1;
  // true: free parameters start from the estimate from the recording (no starting point needed);
  // false: from the values in the parameter set.
  bool start_from_data = true;
  GlobalStageOptions global;
  NelderMeadOptions nelder_mead;
  CeresOptions ceres;
  // After the local stages: grids around the best point in λ × λ_lat and along the ridge t0 + T(α) = t1, their best
  // points polished, the lowest (28) kept (final_stage.hpp), so that the fit's end depends less on round-off of its
  // start. Off: measured (fitting/README.md, "A final stage that does not depend on the start"), it costs more than
  // the cheaper start it was to allow and the later stages' searches still end by other routes.
  FinalStageOptions final_stage;
  IdentifiabilityOptions identifiability;
  bool compute_std_errors = true;
  IntervalOptions intervals;
  // Whether the model at the fit reproduces the recorded out-of-plane motion; if not, λ and λ_lat are reported
  // not determined (lateral_motion_check.hpp).
  LateralMotionCheckOptions lateral_motion;
  // When that check flags the kept point: a rescan of λ_lat over growing windows (lateral_rescan.hpp); the fit
  // moves to its result when (28) is lower there.
  LateralRescanOptions lateral_rescan;
  // How much of ε the noise at rest explains, and a warning when model error dominates (model_error.hpp).
  ModelErrorOptions model_error;
  // The recorded motion just before the fitted t0, and a warning when the block was already moving there
  // (motion_before_release.hpp).
  MotionBeforeReleaseOptions motion_before_release;
  // When the window leaves λ_lat undetermined: fits on windows ending at the next return impacts
  // (window_extension.hpp).
  WindowExtensionOptions window_extension;
  // A gyro scale factor estimated in the fit by variable projection (gyro_scale.hpp, gyro_scale_estimate.hpp):
  // off by default (fitting/README.md, "A gyro scale in the fit", says why). Fit() evaluates the objective with
  // this mode whatever the objective's own.
  GyroScaleMode gyro_scale = GyroScaleMode::kOff;
  // Worker threads for the global stage; 0 = all cores (TBB default). Batches set 1 per trial.
  int num_threads = 0;
  // A value closer than this fraction of its range to a bound is reported "at bound".
  double at_bound_fraction = 1e-3;
  // Throws InvalidArgument naming the first bad option.
  void Validate() const;
};

}  // namespace rockfit::fitting
