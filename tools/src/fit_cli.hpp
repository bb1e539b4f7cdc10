// Command-line options of the fitter shared by `rockfit fit` and `rockfit batch`: method, free and fixed
// parameters, bounds, window, global stage, threads.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "rockfit/fitting/parameters.hpp"
#include "rockfit/fitting/trial_fit.hpp"
#include "rockfit/io/impact_detection.hpp"

namespace rockfit::tools {

struct FitArgs {
  std::string method = "auto";
  std::string bounds = "empirical";
  std::vector<std::string> free;    // names, comma separated allowed
  std::vector<std::string> fix;     // NAME=VALUE
  std::vector<std::string> bound;   // NAME=LO:HI
  std::vector<std::string> start;   // NAME=VALUE
  std::optional<double> t_end_s;
  int t_end_impact = 0;
  double impact_prominence_rad_s = io::ImpactDetectionOptions{}.min_prominence_rad_s;
  std::string facet_tau = "no-spin";
  bool no_global = false;
  std::optional<int> max_evaluations;  // Nelder–Mead budget of the local stage
  bool keep_bias = false;
  int threads = 0;
  std::uint64_t seed = fitting::GlobalStageOptions{}.seed;
};

// Adds the options to `app`; `with_t_end` adds --t-end (a single trial's time, not for batches).
void AddFitOptions(CLI::App& app, FitArgs& args, bool with_t_end);

// The parameter set (bounds set, --bound, --free, --fix, --facet-tau). InvalidArgument naming the option.
fitting::ParameterSet MakeParameterSet(const FitArgs& args);
// Fit, estimate and simulator options (--method, --no-global, --seed, --threads, --t-end, --t-end-impact,
// --keep-bias, --start). InvalidArgument naming the option.
fitting::TrialFitOptions MakeTrialFitOptions(const FitArgs& args);

// "alpha=0.2,lambda=1" or repeated options → (id, value) pairs. InvalidArgument naming `option`.
std::vector<std::pair<fitting::ParameterId, double>> ParseAssignments(const std::vector<std::string>& items,
                                                                      const std::string& option);

}  // namespace rockfit::tools
