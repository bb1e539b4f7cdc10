// Intervals for the fitted parameters of one trial: 68 % and 95 % intervals, whether the data determine each
// parameter, and the correlation matrix (fitting/README.md, "Intervals").
//
// The noise behind (28) is neither white nor known: gyro noise and quantisation, ringing after impacts, drift
// and model error make neighbouring residuals alike, and ringing follows the impacts, where the model is most
// sensitive. Both methods use an effective noise level per parameter from the residuals at the optimum,
// s²_eff,j = κ_j·s², s² = Σ w_k‖r_k‖²/(3·nodes − p), with κ_j the ratio of the heteroscedasticity- and
// autocorrelation-consistent (Newey–West, Bartlett window up to IntervalOptions::noise_correlation_window_s)
// sandwich variance M·B·M of parameter j to the white-noise one s²·M (M = (JᵀJ)⁻¹, B the long-run covariance
// of the score contributions J_kᵀr_k); κ_j ≥ 1. Without a Jacobian, κ is the long-run variance factor of the
// residual series itself. Both are multiplied by IntervalOptions::model_error_allowance. That level sets the
// 95 % intervals; the 68 % intervals use the bulk level of the standard errors, s² inflated only for the
// lag-1 correlation of the residuals (IntervalOptions::bulk_noise_for_68), because the errors are
// heavy-tailed: the bulk is as large as the standard error says, the tail much larger.
//
//  fast      value ± z·σ_j, σ_j² = κ_j·s²·M_jj (linearised, the Jacobian of the Ceres back end; z = 1.96),
//            and value ± σ_j at the bulk level for 68 %;
//  thorough  95 %: profile intervals of S = Σ w_k‖ω_m − ω_s‖² (the least-squares form of (28)): parameter j
//            is stepped outwards from the least-squares optimum (a fixed grid of multiples of σ_j, or aimed at the
//            crossing: IntervalOptions::profile_aimed, profile_steps.hpp), the others re-fitted by Nelder–Mead at
//            every step (warm-started; or by Ceres with the exact Jacobian, IntervalOptions::profile_refit), and the interval ends where S_profile − S_min = z²·s²_eff (z = 1.96, the
//            χ²₁ quantile), widened to the linearised one. Curved valleys (t0 + T(α) near θ_c, λ–λ_lat with weak
//            lateral motion) are followed by the re-fits instead of linearised. 68 %: linearised at the bulk
//            level, as in fast (or the profile's crossing at z = 1, IntervalOptions::profile_68).
//
// An end is open (NaN) where the profile reaches a bound still below the threshold, or for a parameter that
// does not act on (28). A parameter is "determined" when its 95 % interval is closed and narrower than a
// fraction of its range; "sign only" when the interval excludes 0 but is open or that wide; "no" otherwise.
#pragma once

#include <string_view>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

enum class Determination { kYes, kSignOnly, kNo };
const char* ToString(Determination d);  // "yes", "sign only", "no"
bool FromString(std::string_view text, Determination* value);  // the inverse of ToString

// [lower, upper]; NaN marks an open end.
using Interval = std::array<double, 2>;

struct UncertaintySummary {
  IntervalMethod method = IntervalMethod::kNone;
  std::string description;  // one line: the method and the noise model, for reports and JSON
  // Per ParameterId; both ends NaN for fixed parameters and where intervals were not computed.
  std::array<Interval, kNumParameters> interval_68{};
  std::array<Interval, kNumParameters> interval_95{};
  std::array<std::optional<Determination>, kNumParameters> determined{};  // empty for fixed parameters
  // Linearised correlation of the parameters (kNumParameters²; NaN where undefined, 1 on the diagonal of
  // parameters that have a standard error).
  Eigen::MatrixXd correlation;
  double noise_rms_rad_s = 0.0;    // √(s²/Δt): the residual level per component, white-noise equivalent
  double correlation_factor = 1.0; // the largest κ_j (the model-error allowance for white residuals)
  PerParameter noise_inflation{};  // κ_j per parameter (NaN where not computed)
  double bulk_inflation = std::numeric_limits<double>::quiet_NaN();  // the 68 % level's factor (NaN: κ_j as at 95 %)
  // The linearised σ_j of the 95 % level, √(κ_j·s²·M_jj) (NaN where not computed): with `correlation` the
  // covariance of the parameters at the level of the 95 % intervals before the hull, the other basins and the
  // model-error widening — consistent across parameters, as the interval ends are not.
  PerParameter linearised_sigma_95{};
  // s² of the censored likelihood over S/dof at the fit (censored_noise_level.hpp): 1 without clipped samples.
  double censored_noise_factor = 1.0;
  // Sentences: what the data fix ("t0 and alpha: only t0 + T(α) is fixed (correlation −0.998)", …).
  std::vector<std::string> statements;
  std::int64_t evaluations = 0;
  // IntervalOptions::profile_refit kExact: the model runs of `evaluations` that computed sensitivities too (each
  // costs a few plain runs), the re-fits Ceres ended and those left to Nelder–Mead. 0 otherwise.
  std::int64_t sensitivity_runs = 0;
  std::int64_t exact_refits = 0;
  std::int64_t nelder_mead_refits = 0;
  double wall_time_s = 0.0;
  // A point with a lower (28) met on the way (a profile that left the fit's basin); the fitter restarts there.
  std::optional<ParameterSet> better_point;
  double better_epsilon_rad_s = 0.0;
  // The best alternative within the 95 % threshold that lies clearly apart from the fit (λ_lat of the other
  // sign, or farther than the width of a 95 % profile interval outside it): a second solution the data do not
  // exclude.
  std::optional<ParameterSet> second_solution;
  double second_solution_epsilon_rad_s = 0.0;
};

// The residual series r_k = √w_k·(ω_m − ω_s) at `at` in time order (3 per node), over the nodes with weight
// (excluded samples have none); false when the model fails there. `on_node_grid`, when given: the same residuals
// at their nodes' places, 0 at a node without weight, for statistics of the correlation in time.
// `unobserved_components`, when given: how many components of the series are censored observations that the
// model satisfies (SatisfiedCensoredAxes: 0 by definition, no residual), which the degrees of freedom leave out.
bool WeightedResiduals(const Objective& objective, const ParameterSet& at, std::vector<Eigen::Vector3d>* residuals,
                       double* epsilon_rad_s = nullptr, std::vector<Eigen::Vector3d>* on_node_grid = nullptr,
                       std::size_t* unobserved_components = nullptr);

// Degrees of freedom of a residual series: its components, less those that are no residual (censored and
// satisfied), less the free parameters.
double ResidualDegreesOfFreedom(std::size_t nodes, std::size_t unobserved_components, std::size_t free_parameters);

// κ = long-run variance / variance of the series (each component, pooled), Bartlett weights up to max_lag;
// at least 1 (negative correlation at short lags never shrinks the noise level).
double LongRunVarianceFactor(const std::vector<Eigen::Vector3d>& residuals, int max_lag);

// The linearisation at the fit (from ComputeStandardErrors): parameters of the columns, (JᵀJ)⁻¹, the Jacobian
// (rows: residual components in time order, 3 per sample) and the residuals. Empty when not available.
struct Linearisation {
  std::vector<ParameterId> ids;
  Eigen::MatrixXd inverse_normal_matrix;
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd residuals;
  bool available() const {
    const auto n = static_cast<Eigen::Index>(ids.size());
    return n > 0 && inverse_normal_matrix.rows() == n && jacobian.cols() == n && jacobian.rows() == residuals.size();
  }
};

// (1 + ρ₁)/(1 − ρ₁), ρ₁ the lag-1 autocorrelation of the residual series (all components pooled, clamped to
// [0, 0.99]): the factor on the white-noise variance of an AR(1) series; the standard errors and the bulk
// noise level of the 68 % intervals use it. `values` holds the series interleaved with `stride` components.
double Lag1InflationFactor(const double* values, std::size_t samples, std::size_t stride);

// κ_j of the header comment for every column of `lin` (Bartlett window of max_lag samples).
Eigen::VectorXd SandwichInflation(const Linearisation& lin, int max_lag);

// Intervals at the fitted point `fitted` of `objective`. `identifiable` as CheckIdentifiability reports it.
// `alternatives`: other local minima met by the search (the global stage's candidates). The confidence set of
// a profile is every point whose rise of S stays below the threshold, also in another basin: an alternative
// that passes a parameter's threshold widens that parameter's interval to include it (both methods), and is
// listed in `UncertaintySummary::second_solution` when it lies clearly apart. Never throws for numerical
// trouble.
UncertaintySummary ComputeUncertainty(const Objective& objective, const ParameterSet& fitted, double fitted_epsilon_rad_s,
                                      const std::array<bool, kNumParameters>& identifiable, const Linearisation& lin,
                                      const std::vector<ParameterSet>& alternatives, const IntervalOptions& options,
                                      int num_threads);

// The determination of a parameter from its 95 % interval and its bounds (see the header comment).
Determination Determine(const Interval& interval_95, double lower_bound, double upper_bound,
                        double undetermined_range_fraction);

// JSON pieces shared by the library's and the command line's JSON: an interval as [lower, upper] with null
// for open ends (null as a whole for a fixed parameter), and the correlation matrix of the free parameters
// as {"parameters": [names], "matrix": [[…]]} (null entries where undefined).
std::string IntervalJson(const Interval& interval, bool fixed);
std::string CorrelationJson(const UncertaintySummary& u, const ParameterSet& parameters);
// {"t0": κ, …} for the free parameters (null where not computed).
std::string NoiseInflationJson(const UncertaintySummary& u, const ParameterSet& parameters);

// Sentences for pairs with |correlation| ≥ kStrongCorrelation and for parameters not fully determined.
std::vector<std::string> DescribeUncertainty(const UncertaintySummary& u, const ParameterSet& parameters);

}  // namespace rockfit::fitting
