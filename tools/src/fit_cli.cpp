#include "fit_cli.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include <fmt/format.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::tools {
namespace {

// Splits "a,b" items of repeated options into single items.
std::vector<std::string> Items(const std::vector<std::string>& values) {
  std::vector<std::string> items;
  for (const std::string& v : values) {
    std::stringstream stream(v);
    std::string item;
    while (std::getline(stream, item, ',')) {
      if (!item.empty()) items.push_back(item);
    }
  }
  return items;
}

double ParseNumber(const std::string& text, const std::string& option, const std::string& item) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0' || !std::isfinite(value)) {
    throw InvalidArgument(fmt::format("{} expects NAME=NUMBER items, got '{}'", option, item));
  }
  return value;
}

}  // namespace

void AddFitOptions(CLI::App& app, FitArgs& args, bool with_t_end) {
  app.add_option("--method", args.method,
                 "nelder-mead, ceres, or auto (global stage, then Nelder–Mead, then a Ceres polish; the best by (28))")
      ->capture_default_str()
      ->check(CLI::IsMember({"nelder-mead", "ceres", "auto"}))
      ->group("Fit");
  app.add_option("--bounds", args.bounds,
                 "Default bounds: empirical (wider than (25)/(27): λ ∈ [-0.5, 4], λ_lat ∈ [-6, 6], λ_lon ∈ [-0.5, 2.5]) or "
                 "theoretical ((25), (27) with λ, λ_lon ≥ 0)")
      ->capture_default_str()
      ->check(CLI::IsMember({"empirical", "theoretical"}))
      ->group("Fit");
  app.add_option("--bound", args.bound, "Bounds of one parameter, NAME=LO:HI (repeatable), e.g. lambda_lon=0:1.5")
      ->group("Fit");
  app.add_option("--free", args.free, "Parameters to fit besides the defaults, e.g. tau_edge (comma separated)")
      ->group("Fit");
  app.add_option("--fix", args.fix, "Parameters held at a value, NAME=VALUE (comma separated), e.g. lambda_lat=0")
      ->group("Fit");
  app.add_option("--start", args.start, "Starting values instead of the estimate from the data, NAME=VALUE,...")
      ->group("Fit");
  if (with_t_end) {
    app.add_option("--t-end", args.t_end_s, "End of the fitting window in recording time [s] (default: detected)")
        ->group("Fit");
  }
  app.add_option("--t-end-impact", args.t_end_impact,
                 "End the window at the N-th |ω_y| impact counted from the first one (default 0: where phase 4 ends)")
      ->group("Fit");
  app.add_option("--impact-prominence", args.impact_prominence_rad_s,
                 "Least prominence of an |ω_y| peak counted as an impact [rad/s]")
      ->capture_default_str()
      ->group("Fit");
  app.add_option("--facet-tau", args.facet_tau, "τ of facet impacts: no-spin ((24), default) or zero (paper Sect. 5)")
      ->capture_default_str()
      ->check(CLI::IsMember({"no-spin", "zero"}))
      ->group("Fit");
  app.add_flag("--no-global", args.no_global, "Skip the global stage: local search from the estimate only")->group("Fit");
  app.add_option("--max-evaluations", args.max_evaluations,
                 "Budget of the local Nelder–Mead stage in evaluations of (28) (default 1500)")
      ->group("Fit");
  app.add_flag("--keep-bias", args.keep_bias, "Do not subtract the gyro bias measured at rest before the release")
      ->group("Fit");
  app.add_option("--seed", args.seed, "Seed of the global stage's Latin hypercube")->capture_default_str()->group("Fit");
  app.add_option("--threads", args.threads, "Threads of the global stage (0: all cores)")->capture_default_str()->group("Fit");
}

std::vector<std::pair<fitting::ParameterId, double>> ParseAssignments(const std::vector<std::string>& values,
                                                                      const std::string& option) {
  std::vector<std::pair<fitting::ParameterId, double>> out;
  for (const std::string& item : Items(values)) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos) throw InvalidArgument(fmt::format("{} expects NAME=VALUE items, got '{}'", option, item));
    out.emplace_back(fitting::ParseParameterName(item.substr(0, eq)), ParseNumber(item.substr(eq + 1), option, item));
  }
  return out;
}

fitting::ParameterSet MakeParameterSet(const FitArgs& args) {
  using fitting::ParameterId;
  fitting::ParameterSet set = fitting::ParameterSet::Defaults(fitting::ParseBoundsSet(args.bounds));
  set.set_facet_tau_rule(args.facet_tau == "zero" ? core::FacetTauRule::kFixed : core::FacetTauRule::kNoSpin);
  for (const std::string& item : Items(args.bound)) {
    const std::size_t eq = item.find('='), colon = item.find(':');
    if (eq == std::string::npos || colon == std::string::npos || colon < eq) {
      throw InvalidArgument(fmt::format("--bound expects NAME=LO:HI, got '{}'", item));
    }
    const ParameterId id = fitting::ParseParameterName(item.substr(0, eq));
    set[id].lower = ParseNumber(item.substr(eq + 1, colon - eq - 1), "--bound", item);
    set[id].upper = ParseNumber(item.substr(colon + 1), "--bound", item);
    if (!(set[id].lower < set[id].upper)) {
      throw InvalidArgument(fmt::format("--bound {}: the lower bound must be below the upper bound", item));
    }
    if (id != ParameterId::kT0) set[id].value = std::clamp(set[id].value, set[id].lower, set[id].upper);
  }
  for (const std::string& name : Items(args.free)) {
    const ParameterId id = fitting::ParseParameterName(name);
    set[id].fixed = false;
    if (id == ParameterId::kTauEdge && set[id].lower == set[id].upper) {
      // τ_edge has no default range: the impulse is small against the block's angular momentum.
      set[id].lower = -0.05;
      set[id].upper = 0.05;
    }
  }
  for (const auto& [id, value] : ParseAssignments(args.fix, "--fix")) {
    set[id].fixed = true;
    set[id].value = value;
  }
  set.Validate();
  if (set.FreeIds().empty()) {
    throw InvalidArgument("every parameter is fixed: free at least one (--free NAME) or use --evaluate");
  }
  return set;
}

fitting::TrialFitOptions MakeTrialFitOptions(const FitArgs& args) {
  fitting::TrialFitOptions o;
  o.fit.method = fitting::ParseFitMethod(args.method);
  o.fit.global.enabled = !args.no_global;
  o.fit.global.seed = args.seed;
  if (args.max_evaluations) {
    if (*args.max_evaluations < 1) throw InvalidArgument("--max-evaluations must be at least 1");
    o.fit.nelder_mead.max_evaluations = *args.max_evaluations;
  }
  if (args.threads < 0) throw InvalidArgument("--threads must be 0 (all cores) or positive");
  o.fit.num_threads = args.threads;
  o.t_end_s = args.t_end_s;
  if (args.t_end_impact < 0) throw InvalidArgument("--t-end-impact must be 0 (phase 4) or a positive count");
  o.estimate.t_end_impact = args.t_end_impact;
  o.estimate.impacts.min_prominence_rad_s = args.impact_prominence_rad_s;
  o.subtract_rest_bias = !args.keep_bias;
  o.start_values = ParseAssignments(args.start, "--start");
  o.Validate();
  return o;
}

}  // namespace rockfit::tools
