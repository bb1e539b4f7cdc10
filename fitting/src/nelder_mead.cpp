// NLopt LN_NELDERMEAD back end.
#include <chrono>
#include <exception>
#include <limits>
#include <new>
#include <stdexcept>
#include <vector>

#include <nlopt.hpp>

#include "rockfit/fitting/local_optimizer.hpp"

namespace rockfit::fitting {
namespace {

const char* ResultText(nlopt::result result) {
  switch (result) {
    case nlopt::SUCCESS: return "success";
    case nlopt::STOPVAL_REACHED: return "stopval reached";
    case nlopt::FTOL_REACHED: return "ftol reached";
    case nlopt::XTOL_REACHED: return "xtol reached";
    case nlopt::MAXEVAL_REACHED: return "max evaluations reached";
    case nlopt::MAXTIME_REACHED: return "max time reached";
    default: return "failure";
  }
}

// The objective as NLopt sees it; also keeps the best feasible point, so that any termination — including
// the exceptions NLopt throws — returns the best point evaluated.
struct NelderMeadProblem {
  const Objective* objective = nullptr;
  Eigen::VectorXd best_x;
  double best_epsilon = std::numeric_limits<double>::infinity();
  bool best_feasible = false;
  Eigen::VectorXd x;  // scratch
  std::int64_t evaluations = 0;
};

double NelderMeadObjective(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  auto* problem = static_cast<NelderMeadProblem*>(data);
  ++problem->evaluations;
  for (std::size_t i = 0; i < x.size(); ++i) problem->x[static_cast<Eigen::Index>(i)] = x[i];
  const Evaluation e = problem->objective->EvaluateFree(problem->x);
  if (e.epsilon_rad_s < problem->best_epsilon) {
    problem->best_epsilon = e.epsilon_rad_s;
    problem->best_x = problem->x;
    problem->best_feasible = e.feasible;
  }
  return e.epsilon_rad_s;
}

class NelderMead final : public LocalOptimizer {
 public:
  explicit NelderMead(const NelderMeadOptions& options) : options_(options) { options_.Validate(); }
  const char* name() const override { return "nelder-mead"; }

  LocalResult Minimize(const Objective& objective, const Eigen::VectorXd& x0) const override {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = objective.num_free();
    const Eigen::VectorXd lower = objective.FreeLower();
    const Eigen::VectorXd upper = objective.FreeUpper();

    NelderMeadProblem problem;
    problem.objective = &objective;
    problem.x = x0;
    std::vector<double> x(n), lb(n), ub(n), step(n), xtol(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      const std::size_t id = static_cast<std::size_t>(objective.free_ids()[i]);
      lb[i] = lower[k];
      ub[i] = upper[k];
      x[i] = std::min(std::max(x0[k], lb[i]), ub[i]);
      // The simplex must fit in the box: at most half the range along each parameter.
      step[i] = std::min(options_.initial_step[id], 0.5 * (ub[i] - lb[i]));
      xtol[i] = options_.xtol_abs[id];
    }

    LocalResult result;
    // Nelder–Mead can stall on the small steps of (28) (simulated impacts crossing sample times); a restart
    // from the best point with a fresh simplex costs little and often moves on.
    for (int run = 0; run <= options_.restarts; ++run) {
      const double best_before = problem.best_epsilon;
      const int remaining = options_.max_evaluations - static_cast<int>(problem.evaluations);
      if (run > 0) {
        if (remaining <= static_cast<int>(2 * n + 2) || !problem.best_feasible) break;
        for (std::size_t i = 0; i < n; ++i) x[i] = problem.best_x[static_cast<Eigen::Index>(i)];
      }
      try {
        nlopt::opt opt(nlopt::LN_NELDERMEAD, static_cast<unsigned>(n));
        opt.set_lower_bounds(lb);
        opt.set_upper_bounds(ub);
        opt.set_min_objective(NelderMeadObjective, &problem);
        opt.set_initial_step(step);
        opt.set_xtol_abs(xtol);
        opt.set_ftol_abs(options_.ftol_abs_rad_s);
        opt.set_maxeval(remaining);
        double f = 0.0;
        const nlopt::result code = opt.optimize(x, f);
        result.termination = std::string("nlopt: ") + ResultText(code);
        result.converged = code == nlopt::SUCCESS || code == nlopt::FTOL_REACHED || code == nlopt::XTOL_REACHED ||
                           code == nlopt::STOPVAL_REACHED;
        result.termination_type = result.converged                                      ? TerminationType::kConvergence
                                  : code == nlopt::MAXEVAL_REACHED || code == nlopt::MAXTIME_REACHED ? TerminationType::kNoConvergence
                                                                                                      : TerminationType::kFailure;
      } catch (const nlopt::roundoff_limited&) {
        // The simplex cannot shrink further in floating point: a normal end at a (locally) flat minimum.
        result.termination = "nlopt: roundoff limited";
        result.converged = true;
        result.termination_type = TerminationType::kConvergence;
      } catch (const nlopt::forced_stop&) {
        result.termination = "nlopt: forced stop";
        result.converged = false;
        result.termination_type = TerminationType::kFailure;
      } catch (const std::bad_alloc&) {
        result.termination = "nlopt: out of memory";
        result.converged = false;
        result.termination_type = TerminationType::kFailure;
      } catch (const std::invalid_argument& e) {
        result.termination = std::string("nlopt: invalid argument: ") + e.what();
        result.converged = false;
        result.termination_type = TerminationType::kFailure;
      } catch (const std::runtime_error& e) {
        result.termination = std::string("nlopt: failure: ") + e.what();
        result.converged = false;
        result.termination_type = TerminationType::kFailure;
      }
      if (!result.converged) break;
      if (run > 0 && !(problem.best_epsilon < best_before - options_.ftol_abs_rad_s)) break;  // no progress
    }

    if (problem.best_x.size() == static_cast<Eigen::Index>(n)) {
      result.x = problem.best_x;
      result.epsilon_rad_s = problem.best_epsilon;
      result.feasible = problem.best_feasible;
    } else {  // not a single evaluation happened
      result.x = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(n));
      ++problem.evaluations;
      const Evaluation e = objective.EvaluateFree(result.x);
      result.epsilon_rad_s = e.epsilon_rad_s;
      result.feasible = e.feasible;
    }
    if (!result.feasible) {  // a search that found no feasible point has failed, whatever NLopt's test said
      result.converged = false;
      result.termination_type = TerminationType::kFailure;
    }
    result.evaluations = problem.evaluations;
    result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }

 private:
  NelderMeadOptions options_;
};

}  // namespace

std::unique_ptr<LocalOptimizer> MakeNelderMead(const NelderMeadOptions& options) {
  return std::make_unique<NelderMead>(options);
}

}  // namespace rockfit::fitting
