// A trial made by the analytic test model, with its truth, for tests of the fitting machinery.
#pragma once

#include <cmath>
#include <memory>

#include "analytic_rocking_model.hpp"
#include "synthetic_signal.hpp"
#include "rockfit/fitting/objective.hpp"
#include "rockfit/fitting/parameters.hpp"

namespace rockfit::testing {

struct AnalyticTrial {
  core::Block block = core::Block::FromDensity(0.05, 0.04, 0.2, 2692.0);  // θ_c = 0.245 rad as in Sect. 3.1
  std::shared_ptr<const AnalyticRockingModel> model = std::make_shared<AnalyticRockingModel>(block);
  fitting::ParameterSet truth = fitting::ParameterSet::Defaults();
  SyntheticSignal data;
  double t_end_s = 0.0;

  // The start a user without a starting point might have: phase-1 guesses near, impact parameters generic.
  fitting::ParameterSet RoughStart() const {
    fitting::ParameterSet start = Bounded(fitting::BoundsSet::kEmpirical);
    start[fitting::ParameterId::kT0].value = truth.value(fitting::ParameterId::kT0) + 0.006;
    start[fitting::ParameterId::kAlpha].value = truth.value(fitting::ParameterId::kAlpha) - 0.006;
    start[fitting::ParameterId::kLambda].value = 1.0;
    start[fitting::ParameterId::kLambdaLat].value = 0.5;
    start[fitting::ParameterId::kLambdaLon].value = 1.0;
    return start;
  }

  // Parameter set with the given bound set and t0 bounds ±50 ms around the truth.
  fitting::ParameterSet Bounded(fitting::BoundsSet set) const {
    fitting::ParameterSet p = fitting::ParameterSet::Defaults(set);
    const double t0 = truth.value(fitting::ParameterId::kT0);
    p[fitting::ParameterId::kT0] = {t0, t0 - 0.05, t0 + 0.05, false};
    return p;
  }

  fitting::Objective MakeObjective(const fitting::ParameterSet& parameters) const {
    return fitting::Objective(data.signal, t_end_s, model, parameters);
  }
};

// True values (α, λ, λ_lat, λ_lon) and disturbances; t0 = 0.5 s. The window ends at the second longitudinal
// impact (phase 4), at the last sample before it.
inline AnalyticTrial MakeAnalyticTrial(double alpha, double lambda, double lambda_lat, double lambda_lon,
                                       const SyntheticSignalOptions& disturbances = {}) {
  AnalyticTrial trial;
  using fitting::ParameterId;
  trial.truth[ParameterId::kT0].value = disturbances.t0_s;
  trial.truth[ParameterId::kAlpha].value = alpha;
  trial.truth[ParameterId::kLambda].value = lambda;
  trial.truth[ParameterId::kLambdaLat].value = lambda_lat;
  trial.truth[ParameterId::kLambdaLon].value = lambda_lon;
  trial.data = MakeSyntheticSignal(*trial.model, trial.truth.ToModel(), disturbances);
  int facets = 0;
  for (const auto& e : trial.data.events) {
    if (e.kind == core::ImpactKind::kFacet && ++facets == 2) {
      trial.t_end_s = std::floor((disturbances.t0_s + e.t_s) * disturbances.rate_hz) / disturbances.rate_hz;
      break;
    }
  }
  return trial;
}

// Gyro-like disturbances as `rockfit synth` makes them by default (io/README.md, "Synthetic recordings"):
// 0.1 deg/s white noise, ringing of 25 % of each jump at 38 Hz decaying in 30 ms. No bias: removing the bias
// measured at rest is the job of the trial layer (trial_fit.hpp), not of the objective.
inline SyntheticSignalOptions RealisticDisturbances(std::uint64_t seed = 11) {
  SyntheticSignalOptions o;
  o.noise_rad_s = 0.1 * M_PI / 180.0;
  o.ringing_fraction = 0.25;
  o.ringing_hz = 38.0;
  o.ringing_decay_s = 0.03;
  o.seed = seed;
  return o;
}

}  // namespace rockfit::testing
