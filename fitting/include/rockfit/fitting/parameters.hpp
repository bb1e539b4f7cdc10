// The fitted quantities of one trial (paper Sect. 5.1, docs/design.md §7): the release time t0 and tilt α (initial
// conditions) and the impact parameters λ (edge impacts (19)), λ_lat and λ_lon (facet impacts (21)), plus the
// edge-impact torque τ_edge, fixed at 0 by default as in the paper, and the release roll β (a release on one
// corner of the release edge, core/rolled_release.hpp), fixed at 0 unless the fit is asked to estimate it. Each
// parameter has a value, bounds and a fixed flag; a ParameterSet is a plain value type that the fitter copies and
// never shares.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "rockfit/core/impact_maps.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::fitting {

enum class ParameterId : int { kT0 = 0, kAlpha, kLambda, kLambdaLat, kLambdaLon, kTauEdge, kReleaseRoll };
inline constexpr std::size_t kNumParameters = 7;
inline constexpr std::array<ParameterId, kNumParameters> kAllParameters = {
    ParameterId::kT0,        ParameterId::kAlpha,     ParameterId::kLambda,   ParameterId::kLambdaLat,
    ParameterId::kLambdaLon, ParameterId::kTauEdge,   ParameterId::kReleaseRoll};

// "t0", "alpha", "lambda", "lambda_lat", "lambda_lon", "tau_edge", "release_roll".
const char* Name(ParameterId id);
// "s", "rad", "1", "1", "1", "N*m*s", "rad".
const char* Unit(ParameterId id);
// Parses a name of Name(); throws InvalidArgument listing the valid names.
ParameterId ParseParameterName(const std::string& name);

struct Parameter {
  double value = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  bool fixed = false;
};

// Which default bounds a ParameterSet starts from.
//  kEmpirical:   wider than (25)/(27), because fitted values beyond them are normal (paper Sect. 5.3):
//                α ∈ [0.01, 0.3] rad, λ ∈ [−0.5, 4], λ_lat ∈ [−6, 6], λ_lon ∈ [−0.5, 2.5].
//  kTheoretical: (25) and (27) with the energy-compatible signs of Sect. 2 and 4.8 (τ = 0 ⇒ λ ≥ 0):
//                λ ∈ [0, 1], λ_lat ∈ [−1, 1], λ_lon ∈ [0, 1]; α as above.
// t0 has unbounded defaults; the fitter narrows them from the recording (see fitting/README.md).
// β's default bounds [rad]: beyond the rolls a careful release leaves (MuJoCo studies: 0–0.01 rad) with room to
// spare, far below π/4 (a block on a side edge).
inline constexpr double kReleaseRollBound_rad = 0.05;

enum class BoundsSet { kEmpirical, kTheoretical };
const char* ToString(BoundsSet set);             // "empirical", "theoretical"
bool FromString(std::string_view text, BoundsSet* value);  // the inverse of ToString
BoundsSet ParseBoundsSet(const std::string& name);  // throws InvalidArgument

class ParameterSet {
 public:
  // The defaults of docs/design.md §7: t0, α, λ, λ_lat, λ_lon free; τ_edge = 0 and the release roll β = 0
  // fixed (β's bounds ±kReleaseRollBound_rad for `--free release_roll`); facet τ from the no-spin rule.
  static ParameterSet Defaults(BoundsSet bounds = BoundsSet::kEmpirical);

  Parameter& operator[](ParameterId id) { return params_[static_cast<std::size_t>(id)]; }
  const Parameter& operator[](ParameterId id) const { return params_[static_cast<std::size_t>(id)]; }
  double value(ParameterId id) const { return (*this)[id].value; }

  core::FacetTauRule facet_tau_rule() const { return facet_tau_rule_; }
  void set_facet_tau_rule(core::FacetTauRule rule) { facet_tau_rule_ = rule; }

  // Free parameters in the order of kAllParameters.
  std::vector<ParameterId> FreeIds() const;

  // Throws InvalidArgument naming the parameter when a value or bound is not finite (t0 bounds may be
  // infinite), lower > upper, a free parameter has lower == upper, or a value lies outside its bounds.
  void Validate() const;

  // The simulator's view: everything except t0.
  core::ModelParameters ToModel() const;

  // The parameters a fit reports (tables, JSON, HDF5, Python), in the order of kAllParameters: all but the release
  // roll while it is fixed at 0, so that a fit that does not estimate the roll reports what it did before.
  std::vector<ParameterId> ReportedIds() const;

 private:
  std::array<Parameter, kNumParameters> params_{};
  core::FacetTauRule facet_tau_rule_ = core::FacetTauRule::kNoSpin;
};

}  // namespace rockfit::fitting
