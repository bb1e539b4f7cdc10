// The local back ends behind one interface: NLopt's Nelder–Mead simplex (derivative-free, as the paper's
// fminsearch) and Ceres' trust-region least squares on per-sample residuals. Both minimise over the free
// parameters of an Objective within its bounds and report (28) at the point they return.
#pragma once

#include <string_view>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "rockfit/fitting/fit_options.hpp"
#include "rockfit/fitting/objective.hpp"

namespace rockfit::fitting {

// How a search ended, as Ceres' TerminationType; the text beside it says it in the back end's words.
enum class TerminationType {
  kConvergence,    // a convergence test was met (tolerance, or a simplex that cannot shrink in floating point)
  kNoConvergence,  // the evaluation budget ran out first
  kFailure,        // a forced stop, an infeasible end or an error of the back end
  kNotASearch,     // the start point and the global stage: evaluated points, not a convergence test
};
const char* ToString(TerminationType type);  // "convergence", "no_convergence", "failure", "not_a_search"
bool FromString(std::string_view text, TerminationType* value);  // the inverse of ToString

struct LocalResult {
  Eigen::VectorXd x;           // the best point found (free parameters, in the order of free_ids())
  double epsilon_rad_s = 0.0;  // (28) at x (the penalty when no feasible point was found)
  bool feasible = false;
  bool converged = false;      // stopped by a convergence test, not by a budget or a failure
  TerminationType termination_type = TerminationType::kFailure;
  std::string termination;     // "nlopt: xtol reached", "ceres: CONVERGENCE: …", "nlopt: roundoff limited", …
  std::int64_t evaluations = 0;  // objective evaluations (model runs plus points rejected before a run)
  // Ceres: every Jacobian of the search was the model's exact one (CeresOptions::exact_jacobian), none differenced.
  bool exact_derivatives = false;
  double wall_time_s = 0.0;
};

class LocalOptimizer {
 public:
  virtual ~LocalOptimizer() = default;
  virtual const char* name() const = 0;  // "nelder-mead", "ceres"
  // Starts at x0 (clamped into the bounds). Never throws for numerical trouble: that is a termination.
  virtual LocalResult Minimize(const Objective& objective, const Eigen::VectorXd& x0) const = 0;
};

std::unique_ptr<LocalOptimizer> MakeNelderMead(const NelderMeadOptions& options);
std::unique_ptr<LocalOptimizer> MakeCeres(const CeresOptions& options);

// S = Σ‖r_k‖², r_k = √w_k·(ω_m − ω_s) (the least-squares form of (28), no loss), minimised over the free parameters of
// `objective` from x0 by Ceres' trust region with the model's exact Jacobian only (residual_jacobian.hpp): a point
// where the model gives none stops the search (no differences are taken). For the profile re-fits of the intervals.
struct ExactLeastSquaresResult {
  Eigen::VectorXd x;  // the best point accepted (x0 clamped into the bounds when none)
  double sum_sq_start = std::numeric_limits<double>::infinity();  // S at x0 (infinite where the model fails there)
  double sum_sq = std::numeric_limits<double>::infinity();        // S at x
  double epsilon_rad_s = std::numeric_limits<double>::infinity(); // (28) at x
  bool feasible = false;         // the model runs at x
  bool exact_at_start = false;   // the model gave the exact Jacobian at x0 (otherwise nothing was searched)
  bool failed = false;           // Ceres ended in failure (a point without exact Jacobian, a model failure at x0)
  bool converged = false;
  // The lowest (28) of every point evaluated, and its point (free parameters; empty when none was feasible).
  double best_epsilon_rad_s = std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_epsilon_x;
  std::int64_t runs = 0;              // model runs, every one with sensitivities
};
ExactLeastSquaresResult MinimizeSumOfSquaresExact(const Objective& objective, const Eigen::VectorXd& x0,
                                                  int max_iterations);

// Standard errors of the free parameters of `objective` at x from the Gauss–Newton covariance
// κ·s²·(JᵀJ)⁻¹ of the residuals √w_k·(ω_m − ω_s) (ceres::Covariance, dense SVD), with
// s² = Σ w_k‖ω_m − ω_s‖² / (3·nodes − free parameters) and κ = (1 + ρ)/(1 − ρ) for the lag-1 autocorrelation ρ
// of the residuals (an AR(1) correction for correlated errors). J is the model's exact one where it gives it and
// options.exact_jacobian asks for it, otherwise the limited differences of the Ceres back end: the jumps of
// residuals where a simulated impact crosses a sample time are not differentiated.
// These are local, linearised uncertainties; see fitting/README.md for where they fail.
// `std_error` holds NaN where the covariance is not defined (rank-deficient Jacobian); `message` says why.
struct StandardErrors {
  Eigen::VectorXd std_error;
  // (JᵀJ)⁻¹ of the residuals √w_k·(ω_m − ω_s) (free parameters × free parameters; empty when not available):
  // the covariance is κ·s²·(JᵀJ)⁻¹. Intervals (uncertainty.hpp) use it with their own noise level.
  Eigen::MatrixXd inverse_normal_matrix;
  // The residuals √w_k·(ω_m − ω_s) in time order (3 per slot: the t0 node, every sample that can be a node,
  // the t_end node; 0 before t0) and their Jacobian (as J above), for the correlated-noise sandwich.
  Eigen::VectorXd residuals;
  Eigen::MatrixXd jacobian;
  // What the noise level s² = lag1_factor·Σr²/dof counted: the residuals of the nodes with weight (clipped samples
  // have none and are no residuals: not in dof, not in the lag-1 pairs), 3 per node, less the free parameters.
  std::size_t weighted_nodes = 0;
  double dof = 0.0;
  double lag1_factor = 1.0;
  bool available = false;
  std::string message;
};
StandardErrors ComputeStandardErrors(const Objective& objective, const Eigen::VectorXd& x, const CeresOptions& options);

}  // namespace rockfit::fitting
