// Ceres back end and the covariance-based standard errors.
//
// Residual layout. Ceres needs a fixed number of residuals, but the nodes of (28) depend on t0. Every sample
// that can ever be a node (t0_min < t_k < t_end, t0_min the lower bound of t0) gets a slot, plus one slot for
// the t0 node and one for the t_end node; samples before the current t0 have residual 0. Each slot is one
// residual block of three components.
//
// Scaling. With trapezoid weight w_k, nominal sample interval Δt and window T = t_end − t0, the fitted
// residual is f_k = (T_ref/T)·(w_k/√Δt)·(ω_m − ω_s), equal to √w_k·(ω_m − ω_s) for interior samples when
// T = T_ref, under ceres::SoftLOneLoss with a = c·√Δt. For ‖ω_m − ω_s‖ ≫ c, ½ρ(‖f_k‖²) ≈ a‖f_k‖ =
// c·T_ref·w_k‖ω_m − ω_s‖/T, so the Ceres cost approaches c·T_ref·ε of (28) (README, "Ceres back end").
//
// All residual blocks share one model run per parameter vector through a small cache. Jacobians are exact where
// the model gives sensitivities and CeresOptions::exact_jacobian asks for them (residual_jacobian.hpp), otherwise
// limited central differences with per-parameter steps (one-sided at a bound).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <vector>

#include <Eigen/SVD>
#include <ceres/ceres.h>
#include <fmt/format.h>
#include <glog/logging.h>

#include "rockfit/fitting/censored_noise_level.hpp"
#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/fitting/residual_jacobian.hpp"
#include "rockfit/fitting/uncertainty.hpp"

namespace rockfit::fitting {
namespace {

// Ceres reports through glog on stderr (e.g. "Residual and Jacobian evaluation failed" when the model fails at
// the start point). The fit summary already carries every termination; keep stderr for rockfit's own messages.
void SilenceCeresLogging() {
  static std::once_flag once;
  std::call_once(once, [] { FLAGS_minloglevel = google::GLOG_FATAL; });
}

enum class ResidualScaling {
  kSoftL1,        // f_k = (T_ref/T)·(w_k/√Δt)·(ω_m − ω_s), used with SoftLOneLoss(c·√Δt)
  kLeastSquares,  // f_k = √w_k·(ω_m − ω_s), used without a loss for the covariance
};

// Residuals of every slot for parameter vectors, with a small least-recently-used cache so that all residual
// blocks (and the 2n perturbed points of their Jacobians) share one model run per distinct vector.
class ResidualEvaluator {
 public:
  ResidualEvaluator(const Objective& objective, ResidualScaling scaling, double t_ref_s, bool exact_jacobian,
                    bool exact_only = false)
      : objective_(objective), scaling_(scaling), t_ref_s_(t_ref_s), exact_jacobian_(exact_jacobian),
        exact_only_(exact_only) {
    const MeasuredSignal& s = objective.signal();
    double t0_min = s.t_s.front();
    const Parameter& t0 = objective.parameters()[ParameterId::kT0];
    t0_min = std::max(t0_min, t0.fixed ? t0.value : t0.lower);
    first_slot_sample_ = static_cast<std::size_t>(std::upper_bound(s.t_s.begin(), s.t_s.end(), t0_min) - s.t_s.begin());
    const std::size_t end_sample =
        static_cast<std::size_t>(std::lower_bound(s.t_s.begin(), s.t_s.end(), objective.t_end_s()) - s.t_s.begin());
    num_slots_ = (end_sample > first_slot_sample_ ? end_sample - first_slot_sample_ : 0) + 2;
    // Nominal sample interval: the median spacing inside the window.
    std::vector<double> dt;
    for (std::size_t k = std::max<std::size_t>(first_slot_sample_, 1); k < end_sample; ++k) dt.push_back(s.t_s[k] - s.t_s[k - 1]);
    if (dt.empty()) dt.push_back(s.t_s[1] - s.t_s[0]);
    std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
    nominal_dt_s_ = dt[dt.size() / 2];
    capacity_ = 2 * objective.num_free() + 3;
    cache_.reserve(capacity_);
  }

  std::size_t num_slots() const { return num_slots_; }
  std::int64_t evaluations() const { return evaluations_; }
  std::int64_t exact_jacobians() const { return exact_jacobians_; }
  // Whether some residual block was differentiated numerically (no exact Jacobian at its point).
  bool differenced() const { return differenced_; }
  void NoteDifferenced() { differenced_ = true; }
  // Whether a missing exact Jacobian fails the evaluation instead of being differenced.
  bool exact_only() const { return exact_only_; }
  // The lowest (28) of the feasible points evaluated, and its point (empty when none).
  double best_epsilon_rad_s() const { return best_epsilon_rad_s_; }
  const std::vector<double>& best_epsilon_x() const { return best_epsilon_x_; }
  // (28) at x (infinite where the model fails).
  double epsilon_at(const double* x) {
    return Lookup(x) ? last_entry_->epsilon_rad_s : std::numeric_limits<double>::infinity();
  }
  double nominal_dt_s() const { return nominal_dt_s_; }
  std::size_t num_nodes_at(const double* x) {
    return Lookup(x) ? last_num_nodes_ : 0;
  }
  // The nodes with weight at x (the others are clipped samples, whose slots hold 0); 0 when the model fails.
  std::size_t num_weighted_nodes_at(const double* x) {
    return Lookup(x) ? last_entry_->num_weighted_nodes : 0;
  }
  // Components at x that are censored observations the model satisfies (SatisfiedCensoredAxes): 0 whatever the
  // model does nearby, so no residual and no degree of freedom.
  std::size_t num_unobserved_components_at(const double* x) {
    return Lookup(x) ? last_entry_->num_unobserved_components : 0;
  }

  // Residuals (3 per slot) at x, or nullptr when the model fails there. The pointer stays valid until the
  // next call.
  const double* Residuals(const double* x) { return Lookup(x); }
  // The exact Jacobian of all residuals at x (row-major, 3 rows per slot, one column per free parameter), or
  // nullptr when it is not available there (then the caller differentiates numerically).
  const double* Jacobian(const double* x) {
    if (Lookup(x) == nullptr) return nullptr;
    return last_entry_->jacobian_ok ? last_entry_->jacobian.data() : nullptr;
  }

 private:
  struct Entry {
    std::vector<double> key;
    std::vector<double> residuals;
    std::vector<double> jacobian;
    bool ok = false;
    bool jacobian_ok = false;
    double epsilon_rad_s = std::numeric_limits<double>::infinity();  // (28) at the point
    std::size_t num_nodes = 0;
    std::size_t num_weighted_nodes = 0;
    std::size_t num_unobserved_components = 0;
    std::uint64_t last_used = 0;
    // The cache_ index of the entry looked up right after this one, the last time (a guess for the next time).
    std::size_t next = std::numeric_limits<std::size_t>::max();
  };

  const double* Lookup(const double* x) {
    const std::size_t n = objective_.num_free();
    ++clock_;
    // Keys are distinct (an entry is added only when none matches), so at most one entry matches and the scan
    // may start anywhere. The residual blocks ask for the same points in the same order (x, then its 2n perturbed
    // points) one block after the other: the entry asked for after the last one, the last time, is tried first.
    const std::size_t size = cache_.size();
    const std::size_t previous = last_index_;
    const std::size_t guess = previous < size ? cache_[previous].next : size;
    auto matches = [&](std::size_t index) { return std::equal(cache_[index].key.begin(), cache_[index].key.end(), x); };
    std::size_t found = size;
    if (guess < size && matches(guess)) {
      found = guess;
    } else {
      for (std::size_t index = 0; index < size && found == size; ++index) {
        if (index != guess && matches(index)) found = index;
      }
    }
    if (found < size) {
      Entry& e = cache_[found];
      e.last_used = clock_;
      last_num_nodes_ = e.num_nodes;
      last_entry_ = &e;
      if (previous < size) cache_[previous].next = found;
      last_index_ = found;
      return e.ok ? e.residuals.data() : nullptr;
    }
    Entry* entry = nullptr;
    if (cache_.size() < capacity_) {
      cache_.emplace_back();
      entry = &cache_.back();
    } else {
      entry = &*std::min_element(cache_.begin(), cache_.end(),
                                 [](const Entry& a, const Entry& b) { return a.last_used < b.last_used; });
    }
    ++evaluations_;
    last_entry_ = entry;
    const auto entry_index = static_cast<std::size_t>(entry - cache_.data());
    if (previous < cache_.size()) cache_[previous].next = entry_index;
    last_index_ = entry_index;
    entry->jacobian_ok = false;
    entry->key.assign(x, x + n);
    entry->last_used = clock_;
    entry->residuals.assign(3 * num_slots_, 0.0);
    Eigen::VectorXd xv = Eigen::Map<const Eigen::VectorXd>(x, static_cast<Eigen::Index>(n));
    const Evaluation e = objective_.EvaluateDetailed(objective_.WithFree(xv), &nodes_, &output_, exact_jacobian_);
    entry->ok = e.feasible && nodes_.size() >= 2 && nodes_.first_sample >= first_slot_sample_;
    entry->epsilon_rad_s = e.epsilon_rad_s;
    entry->num_nodes = entry->ok ? nodes_.size() : 0;
    entry->num_weighted_nodes = entry->ok ? nodes_.size() - nodes_.num_excluded : 0;
    entry->num_unobserved_components = entry->ok ? NumSatisfiedCensoredComponents(nodes_, output_.w_B) : 0;
    last_num_nodes_ = entry->num_nodes;
    if (!entry->ok) return nullptr;
    if (e.epsilon_rad_s < best_epsilon_rad_s_) {
      best_epsilon_rad_s_ = e.epsilon_rad_s;
      best_epsilon_x_ = entry->key;
    }
    ResidualScale scale;
    scale.kind = scaling_ == ResidualScaling::kSoftL1 ? ResidualScale::Kind::kSoftL1 : ResidualScale::Kind::kLeastSquares;
    scale.t_ref_s = t_ref_s_;
    scale.nominal_dt_s = nominal_dt_s_;
    const ResidualJacobianSummary exact = NodeResiduals(objective_, nodes_, output_, scale, &node_residuals_);
    entry->jacobian_ok = exact_jacobian_ && exact.available;
    if (entry->jacobian_ok) {
      entry->jacobian.assign(3 * num_slots_ * n, 0.0);
      ++exact_jacobians_;
    }
    const std::size_t last = nodes_.size() - 1;
    for (std::size_t i = 0; i <= last; ++i) {
      const std::size_t slot = i == 0 ? 0 : (i == last ? num_slots_ - 1 : 1 + nodes_.first_sample + i - 1 - first_slot_sample_);
      const NodeResidual& r = node_residuals_[i];
      for (int c = 0; c < 3; ++c) {
        const std::size_t row = 3 * slot + static_cast<std::size_t>(c);
        entry->residuals[row] = r.f[c];
        if (!entry->jacobian_ok) continue;
        for (std::size_t j = 0; j < n; ++j) entry->jacobian[row * n + j] = r.df_dx(c, static_cast<Eigen::Index>(j));
      }
    }
    return entry->residuals.data();
  }

  const Objective& objective_;
  ResidualScaling scaling_;
  double t_ref_s_;
  bool exact_jacobian_ = false;
  bool exact_only_ = false;
  double best_epsilon_rad_s_ = std::numeric_limits<double>::infinity();
  std::vector<double> best_epsilon_x_;
  std::size_t first_slot_sample_ = 0;
  std::size_t num_slots_ = 0;
  double nominal_dt_s_ = 0.0;
  std::size_t capacity_ = 0;
  std::uint64_t clock_ = 0;
  std::size_t last_num_nodes_ = 0;
  std::int64_t evaluations_ = 0;
  std::int64_t exact_jacobians_ = 0;
  bool differenced_ = false;
  std::vector<Entry> cache_;  // reserved to capacity_: entries never move, so last_entry_ stays valid
  Entry* last_entry_ = nullptr;
  std::size_t last_index_ = std::numeric_limits<std::size_t>::max();  // cache_ index of the last entry looked up
  ErrorNodes nodes_;
  ModelOutput output_;
  std::vector<NodeResidual> node_residuals_;
};

// One slot: three residuals, one parameter block (all free parameters), central differences.
class SlotCost final : public ceres::CostFunction {
 public:
  SlotCost(ResidualEvaluator* evaluator, std::size_t slot, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
           const Eigen::VectorXd& step, bool limited)
      : evaluator_(evaluator), slot_(slot), lower_(lower), upper_(upper), step_(step), limited_(limited) {
    set_num_residuals(3);
    mutable_parameter_block_sizes()->push_back(static_cast<std::int32_t>(lower.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* x = parameters[0];
    const double* r = evaluator_->Residuals(x);
    if (r == nullptr) return false;
    std::copy(r + 3 * slot_, r + 3 * slot_ + 3, residuals);
    if (jacobians == nullptr || jacobians[0] == nullptr) return true;
    const auto n = static_cast<std::size_t>(lower_.size());
    if (const double* exact = evaluator_->Jacobian(x)) {
      std::copy(exact + 3 * slot_ * n, exact + 3 * (slot_ + 1) * n, jacobians[0]);
      return true;
    }
    if (evaluator_->exact_only()) return false;
    evaluator_->NoteDifferenced();
    // The perturbed points, on the stack (this runs for every slot at every Jacobian).
    std::array<double, kNumParameters> xp{};
    std::array<double, kNumParameters> xm{};
    std::copy(x, x + n, xp.begin());
    std::copy(x, x + n, xm.begin());
    for (std::size_t j = 0; j < n; ++j) {
      const auto k = static_cast<Eigen::Index>(j);
      xp[j] = std::min(x[j] + step_[k], upper_[k]);
      xm[j] = std::max(x[j] - step_[k], lower_[k]);
      double plus[3] = {residuals[0], residuals[1], residuals[2]};
      double minus[3] = {residuals[0], residuals[1], residuals[2]};
      if (xp[j] > x[j]) {
        const double* rp = evaluator_->Residuals(xp.data());
        if (rp == nullptr) return false;
        std::copy(rp + 3 * slot_, rp + 3 * slot_ + 3, plus);
      }
      if (xm[j] < x[j]) {
        const double* rm = evaluator_->Residuals(xm.data());
        if (rm == nullptr) return false;
        std::copy(rm + 3 * slot_, rm + 3 * slot_ + 3, minus);
      }
      for (std::size_t c = 0; c < 3; ++c) {
        const double h_minus = x[j] - xm[j];
        const double h_plus = xp[j] - x[j];
        jacobians[0][c * n + j] = limited_ ? LimitedDifference(minus[c], residuals[c], plus[c], h_minus, h_plus)
                                           : (h_minus + h_plus > 0.0 ? (plus[c] - minus[c]) / (h_minus + h_plus) : 0.0);
      }
      xp[j] = x[j];
      xm[j] = x[j];
    }
    return true;
  }

  // The derivative of one residual from its values at x − h₋, x, x + h₊ (h = 0 where a bound cuts the step).
  // Central where both one-sided slopes agree (same sign, within a factor kSlopeAgreement); otherwise the
  // smaller one-sided slope, or 0 when they disagree in sign (minmod). A simulated impact that crosses the
  // sample time between two of the points makes the residual jump; that jump is an artefact of sampling ω_s
  // at discrete times, and differentiating it would give a huge, meaningless slope.
  static double LimitedDifference(double r_minus, double r0, double r_plus, double h_minus, double h_plus) {
    constexpr double kSlopeAgreement = 4.0;
    if (h_minus <= 0.0 && h_plus <= 0.0) return 0.0;
    if (h_minus <= 0.0) return (r_plus - r0) / h_plus;
    if (h_plus <= 0.0) return (r0 - r_minus) / h_minus;
    const double right = (r_plus - r0) / h_plus;
    const double left = (r0 - r_minus) / h_minus;
    if (right * left <= 0.0) return 0.0;
    const double small = std::min(std::abs(right), std::abs(left));
    const double large = std::max(std::abs(right), std::abs(left));
    if (large <= kSlopeAgreement * small) return (r_plus - r_minus) / (h_plus + h_minus);
    return std::abs(right) < std::abs(left) ? right : left;
  }

 private:
  ResidualEvaluator* evaluator_;
  std::size_t slot_;
  Eigen::VectorXd lower_, upper_, step_;
  bool limited_;
};

Eigen::VectorXd FreeSteps(const Objective& objective, const CeresOptions& options) {
  Eigen::VectorXd step(static_cast<Eigen::Index>(objective.num_free()));
  for (std::size_t i = 0; i < objective.num_free(); ++i) {
    step[static_cast<Eigen::Index>(i)] = options.difference_step[static_cast<std::size_t>(objective.free_ids()[i])];
  }
  return step;
}

// Builds the problem: one parameter block `x` with its bounds, one residual block per slot. `limited`: limited
// differences (used by the minimiser and the covariance); plain central differences otherwise.
void BuildProblem(const Objective& objective, ResidualEvaluator* evaluator, const CeresOptions& options,
                  ceres::LossFunction* loss, bool limited, Eigen::VectorXd* x, ceres::Problem* problem) {
  const Eigen::VectorXd lower = objective.FreeLower();
  const Eigen::VectorXd upper = objective.FreeUpper();
  const Eigen::VectorXd step = FreeSteps(objective, options);
  for (std::size_t slot = 0; slot < evaluator->num_slots(); ++slot) {
    problem->AddResidualBlock(new SlotCost(evaluator, slot, lower, upper, step, limited), loss, x->data());
  }
  for (Eigen::Index j = 0; j < x->size(); ++j) {
    if (std::isfinite(lower[j])) problem->SetParameterLowerBound(x->data(), static_cast<int>(j), lower[j]);
    if (std::isfinite(upper[j])) problem->SetParameterUpperBound(x->data(), static_cast<int>(j), upper[j]);
  }
}

class CeresLeastSquares final : public LocalOptimizer {
 public:
  explicit CeresLeastSquares(const CeresOptions& options) : options_(options) { options_.Validate(); }
  const char* name() const override { return "ceres"; }

  LocalResult Minimize(const Objective& objective, const Eigen::VectorXd& x0) const override {
    SilenceCeresLogging();
    const auto start = std::chrono::steady_clock::now();
    Eigen::VectorXd x = x0.cwiseMax(objective.FreeLower()).cwiseMin(objective.FreeUpper());
    const double t0_start = objective.WithFree(x).value(ParameterId::kT0);
    ResidualEvaluator evaluator(objective, ResidualScaling::kSoftL1, objective.t_end_s() - t0_start,
                                options_.exact_jacobian);
    ceres::SoftLOneLoss loss(options_.soft_l1_scale_rad_s * std::sqrt(evaluator.nominal_dt_s()));
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    BuildProblem(objective, &evaluator, options_, &loss, true, &x, &problem);

    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options_.max_iterations;
    solver.function_tolerance = options_.function_tolerance;
    solver.parameter_tolerance = options_.parameter_tolerance;
    solver.gradient_tolerance = options_.gradient_tolerance;
    solver.logging_type = ceres::SILENT;
    solver.minimizer_progress_to_stdout = false;
    solver.num_threads = 1;  // the evaluator is not thread-safe; parallelism lives in the global stage
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);

    LocalResult result;
    result.termination = fmt::format("ceres: {}: {}", ceres::TerminationTypeToString(summary.termination_type),
                                     summary.message);
    result.converged = summary.termination_type == ceres::CONVERGENCE;
    result.termination_type = summary.termination_type == ceres::CONVERGENCE     ? TerminationType::kConvergence
                              : summary.termination_type == ceres::NO_CONVERGENCE ? TerminationType::kNoConvergence
                                                                                  : TerminationType::kFailure;
    // Ceres leaves x at the best accepted point; report (28) there.
    result.x = x;
    const Evaluation e = objective.EvaluateFree(x);
    result.epsilon_rad_s = e.epsilon_rad_s;
    result.feasible = e.feasible;
    if (!e.feasible) {
      result.converged = false;
      result.termination_type = TerminationType::kFailure;
    }
    result.evaluations = evaluator.evaluations() + 1;
    result.exact_derivatives = evaluator.exact_jacobians() > 0 && !evaluator.differenced();
    result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }

 private:
  CeresOptions options_;
};

}  // namespace

std::unique_ptr<LocalOptimizer> MakeCeres(const CeresOptions& options) {
  return std::make_unique<CeresLeastSquares>(options);
}

ExactLeastSquaresResult MinimizeSumOfSquaresExact(const Objective& objective, const Eigen::VectorXd& x0,
                                                  int max_iterations) {
  SilenceCeresLogging();
  ExactLeastSquaresResult result;
  Eigen::VectorXd x = x0.cwiseMax(objective.FreeLower()).cwiseMin(objective.FreeUpper());
  result.x = x;
  ResidualEvaluator evaluator(objective, ResidualScaling::kLeastSquares, 1.0, /*exact_jacobian=*/true,
                              /*exact_only=*/true);
  auto finish = [&] {
    result.runs = evaluator.evaluations();
    result.best_epsilon_rad_s = evaluator.best_epsilon_rad_s();
    if (!evaluator.best_epsilon_x().empty()) {
      result.best_epsilon_x = Eigen::Map<const Eigen::VectorXd>(evaluator.best_epsilon_x().data(), x.size());
    }
    return result;
  };
  const auto sum_of_squares = [&](const double* r) {
    double sum = 0.0;
    for (std::size_t i = 0; i < 3 * evaluator.num_slots(); ++i) sum += r[i] * r[i];
    return sum;
  };
  // The start: its S, and whether the model gives the exact Jacobian there (from the same run).
  const double* r_start = evaluator.Residuals(x.data());
  if (r_start == nullptr) {
    result.failed = true;
    return finish();
  }
  result.sum_sq_start = sum_of_squares(r_start);
  result.sum_sq = result.sum_sq_start;
  result.feasible = true;
  result.epsilon_rad_s = evaluator.epsilon_at(x.data());
  result.exact_at_start = evaluator.Jacobian(x.data()) != nullptr;
  if (!result.exact_at_start || x.size() == 0 || max_iterations < 1) {
    result.failed = !result.exact_at_start;
    return finish();
  }
  ceres::Problem problem;
  BuildProblem(objective, &evaluator, CeresOptions{}, nullptr, true, &x, &problem);
  ceres::Solver::Options solver;
  // The tolerances of the Ceres back end (CeresOptions' defaults): relative changes below them are round-off of S.
  const CeresOptions tolerances;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = max_iterations;
  solver.function_tolerance = tolerances.function_tolerance;
  solver.parameter_tolerance = tolerances.parameter_tolerance;
  solver.gradient_tolerance = tolerances.gradient_tolerance;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  solver.num_threads = 1;  // the evaluator is not thread-safe
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  result.failed = summary.termination_type == ceres::FAILURE || summary.termination_type == ceres::USER_FAILURE;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  // Ceres leaves x at the best point it accepted; S and (28) there come from the evaluator's cache.
  const double* r_end = evaluator.Residuals(x.data());
  result.feasible = r_end != nullptr;
  if (result.feasible) {
    result.x = x;
    result.sum_sq = sum_of_squares(r_end);
    result.epsilon_rad_s = evaluator.epsilon_at(x.data());
  }
  return finish();
}

StandardErrors ComputeStandardErrors(const Objective& objective, const Eigen::VectorXd& x_in,
                                     const CeresOptions& options) {
  SilenceCeresLogging();
  StandardErrors result;
  const auto n = static_cast<Eigen::Index>(objective.num_free());
  result.std_error = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXd x = x_in;
  ResidualEvaluator evaluator(objective, ResidualScaling::kLeastSquares, 1.0, options.exact_jacobian);
  const double* r = evaluator.Residuals(x.data());
  if (r == nullptr) {
    result.message = "the model fails at the optimum";
    return result;
  }
  result.residuals = Eigen::Map<const Eigen::VectorXd>(r, static_cast<Eigen::Index>(3 * evaluator.num_slots()));
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < 3 * evaluator.num_slots(); ++i) sum_sq += r[i] * r[i];
  // Residuals of neighbouring samples are correlated (gyro ringing after impacts, model error that varies
  // slowly), so they carry less information than independent ones. With the lag-1 autocorrelation ρ of the
  // residual series (each component in time order), an AR(1) process has an effective sample size
  // N·(1 − ρ)/(1 + ρ); the variances grow by the inverse factor (never shrink). Slots that are no node (before
  // t0) or a node without weight (a clipped sample) hold 0: they add nothing to either sum of ρ, so no pair
  // across them is counted as adjacent.
  const double inflation = Lag1InflationFactor(r, evaluator.num_slots(), 3);
  // The degrees of freedom count the residuals: the nodes with weight only, less the censored components the
  // model satisfies.
  const std::size_t nodes = evaluator.num_weighted_nodes_at(x.data());
  const double dof = ResidualDegreesOfFreedom(nodes, evaluator.num_unobserved_components_at(x.data()),
                                              static_cast<std::size_t>(n));
  result.weighted_nodes = nodes;
  result.dof = dof;
  result.lag1_factor = inflation;
  if (dof <= 0.0) {
    result.message = "fewer residuals than free parameters";
    return result;
  }
  ceres::Problem problem;
  BuildProblem(objective, &evaluator, options, nullptr, true, &x, &problem);
  // Rank test first (Ceres would log an error for a rank-deficient Jacobian); the Jacobian comes from the
  // evaluator's cache, so this costs no model run.
  {
    ceres::CRSMatrix crs;
    // Fails where the model fails within the difference steps around x (a point at the edge of the feasible set).
    if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &crs) ||
        crs.num_cols != static_cast<int>(n) || crs.rows.size() != static_cast<std::size_t>(crs.num_rows) + 1) {
      result.message = "the Jacobian cannot be evaluated at the optimum (the model fails within the difference steps)";
      return result;
    }
    Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
    for (int row = 0; row < crs.num_rows; ++row) {
      for (int i = crs.rows[static_cast<std::size_t>(row)]; i < crs.rows[static_cast<std::size_t>(row) + 1]; ++i) {
        jacobian(row, crs.cols[static_cast<std::size_t>(i)]) = crs.values[static_cast<std::size_t>(i)];
      }
    }
    const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXd>(jacobian).singularValues();
    result.jacobian = jacobian;

    // (JᵀJ) has reciprocal condition (σ_min/σ_max)²; Ceres' default threshold for it is 1e-14.
    constexpr double kMinReciprocalCondition = 1e-14;
    if (singular.size() == 0 || !(singular.minCoeff() > std::sqrt(kMinReciprocalCondition) * singular.maxCoeff())) {
      result.message = "the Jacobian is rank-deficient at the optimum (covariance not defined)";
      return result;
    }
  }
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.num_threads = 1;
  ceres::Covariance covariance(covariance_options);
  const std::vector<std::pair<const double*, const double*>> blocks = {{x.data(), x.data()}};
  if (!covariance.Compute(blocks, &problem)) {
    result.message = "the Jacobian is rank-deficient at the optimum (covariance not defined)";
    return result;
  }
  Eigen::MatrixXd cov(n, n);
  if (!covariance.GetCovarianceBlock(x.data(), x.data(), cov.data())) {
    result.message = "ceres::Covariance could not return the block";
    return result;
  }
  // With censored components the noise level of the censored likelihood (censored_noise_level.hpp); exactly
  // inflation·S/dof without them.
  const double noise_dof = dof / CensoredNoiseFactorAt(objective, objective.WithFree(x), static_cast<std::size_t>(n));
  const double s2 = inflation * sum_sq / noise_dof;
  result.inverse_normal_matrix = cov;
  for (Eigen::Index i = 0; i < n; ++i) {
    result.std_error[i] = cov(i, i) >= 0.0 ? std::sqrt(s2 * cov(i, i)) : std::numeric_limits<double>::quiet_NaN();
  }
  result.available = result.std_error.allFinite();
  if (!result.available) result.message = "negative variance from the covariance";
  return result;
}

}  // namespace rockfit::fitting
