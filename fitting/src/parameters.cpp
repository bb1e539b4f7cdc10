#include "rockfit/fitting/parameters.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "rockfit/core/enum_names.hpp"
#include "rockfit/core/errors.hpp"

namespace rockfit::fitting {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Starting values before any data is seen: a typical slender-block release and Housner-like impacts.
// The fitter replaces free values by its estimate from the recording unless told to start from these.
constexpr double kDefaultAlphaRad = 0.1;
constexpr double kDefaultLambda = 1.0;
constexpr double kDefaultLambdaLat = 0.0;
constexpr double kDefaultLambdaLon = 1.0;

// α bounds of both sets [rad]: tilts below 0.01 rad give too little motion to fit; 0.3 rad is beyond the
// release tilts of slender blocks (the simulator reports overturning for tilts past the critical angle).
constexpr double kAlphaLowerRad = 0.01;
constexpr double kAlphaUpperRad = 0.3;

}  // namespace

const char* Name(ParameterId id) {
  switch (id) {
    case ParameterId::kT0: return "t0";
    case ParameterId::kAlpha: return "alpha";
    case ParameterId::kLambda: return "lambda";
    case ParameterId::kLambdaLat: return "lambda_lat";
    case ParameterId::kLambdaLon: return "lambda_lon";
    case ParameterId::kTauEdge: return "tau_edge";
    case ParameterId::kReleaseRoll: return "release_roll";
  }
  return "?";
}

const char* Unit(ParameterId id) {
  switch (id) {
    case ParameterId::kT0: return "s";
    case ParameterId::kAlpha: return "rad";
    case ParameterId::kReleaseRoll: return "rad";
    case ParameterId::kTauEdge: return "N*m*s";
    default: return "1";
  }
}

ParameterId ParseParameterName(const std::string& name) {
  for (ParameterId id : kAllParameters) {
    if (name == Name(id)) return id;
  }
  throw InvalidArgument(fmt::format(
      "unknown parameter '{}'; the parameters are t0, alpha, lambda, lambda_lat, lambda_lon, tau_edge, release_roll", name));
}

const char* ToString(BoundsSet set) { return set == BoundsSet::kEmpirical ? "empirical" : "theoretical"; }

bool FromString(std::string_view text, BoundsSet* value) {
  static constexpr BoundsSet kAll[] = {BoundsSet::kEmpirical, BoundsSet::kTheoretical};
  return core::FromStringAmong(text, kAll, value);
}

BoundsSet ParseBoundsSet(const std::string& name) {
  BoundsSet set = BoundsSet::kEmpirical;
  if (FromString(name, &set)) return set;
  throw InvalidArgument(fmt::format("unknown bounds set '{}'; use 'empirical' or 'theoretical'", name));
}

ParameterSet ParameterSet::Defaults(BoundsSet bounds) {
  ParameterSet set;
  set[ParameterId::kT0] = {0.0, -kInfinity, kInfinity, false};
  set[ParameterId::kAlpha] = {kDefaultAlphaRad, kAlphaLowerRad, kAlphaUpperRad, false};
  set[ParameterId::kTauEdge] = {0.0, 0.0, 0.0, true};
  set[ParameterId::kReleaseRoll] = {0.0, -kReleaseRollBound_rad, kReleaseRollBound_rad, true};
  if (bounds == BoundsSet::kEmpirical) {
    set[ParameterId::kLambda] = {kDefaultLambda, -0.5, 4.0, false};
    set[ParameterId::kLambdaLat] = {kDefaultLambdaLat, -6.0, 6.0, false};
    set[ParameterId::kLambdaLon] = {kDefaultLambdaLon, -0.5, 2.5, false};
  } else {
    set[ParameterId::kLambda] = {kDefaultLambda, 0.0, 1.0, false};         // (25), ΔE ≤ 0 ⇒ λ ≥ 0 (26)
    set[ParameterId::kLambdaLat] = {kDefaultLambdaLat, -1.0, 1.0, false};  // (27)
    set[ParameterId::kLambdaLon] = {kDefaultLambdaLon, 0.0, 1.0, false};   // (27), ΔE ≤ 0 ⇒ λ_lon ≥ 0
  }
  return set;
}

std::vector<ParameterId> ParameterSet::FreeIds() const {
  std::vector<ParameterId> ids;
  for (ParameterId id : kAllParameters) {
    if (!(*this)[id].fixed) ids.push_back(id);
  }
  return ids;
}

void ParameterSet::Validate() const {
  for (ParameterId id : kAllParameters) {
    const Parameter& p = (*this)[id];
    const char* name = Name(id);
    if (!std::isfinite(p.value)) {
      throw InvalidArgument(fmt::format("parameter {}: the value must be a finite number, got {}", name, p.value));
    }
    const bool infinite_bounds_allowed = id == ParameterId::kT0;
    if (std::isnan(p.lower) || std::isnan(p.upper) ||
        (!infinite_bounds_allowed && (!std::isfinite(p.lower) || !std::isfinite(p.upper)))) {
      throw InvalidArgument(fmt::format("parameter {}: the bounds must be finite numbers, got [{}, {}]", name,
                                        p.lower, p.upper));
    }
    if (p.lower > p.upper) {
      throw InvalidArgument(fmt::format("parameter {}: lower bound {} is above upper bound {}; swap them", name,
                                        p.lower, p.upper));
    }
    if (!p.fixed && p.lower == p.upper) {
      throw InvalidArgument(fmt::format(
          "parameter {}: free but its bounds [{}, {}] leave no room; widen them or fix the parameter", name,
          p.lower, p.upper));
    }
    if (!p.fixed && (p.value < p.lower || p.value > p.upper)) {
      throw InvalidArgument(fmt::format("parameter {}: value {} {} lies outside its bounds [{}, {}]", name, p.value,
                                        Unit(id), p.lower, p.upper));
    }
  }
}

core::ModelParameters ParameterSet::ToModel() const {
  core::ModelParameters model;
  model.alpha_rad = value(ParameterId::kAlpha);
  model.lambda = value(ParameterId::kLambda);
  model.tau_edge = value(ParameterId::kTauEdge);
  model.lambda_lat = value(ParameterId::kLambdaLat);
  model.lambda_lon = value(ParameterId::kLambdaLon);
  model.release_roll_rad = value(ParameterId::kReleaseRoll);
  model.facet_tau_rule = facet_tau_rule_;
  return model;
}

std::vector<ParameterId> ParameterSet::ReportedIds() const {
  std::vector<ParameterId> ids;
  for (ParameterId id : kAllParameters) {
    const Parameter& p = (*this)[id];
    if (id == ParameterId::kReleaseRoll && p.fixed && p.value == 0.0) continue;
    ids.push_back(id);
  }
  return ids;
}

}  // namespace rockfit::fitting
