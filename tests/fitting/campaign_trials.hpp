// Small synthetic campaigns for the fit store and FitCampaign tests: short recordings from the simulator and
// the x-IMU measurement model (synth_trial.hpp, fixed seeds) and a fit of a few dozen simulations each.
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include "rockfit/fitting/fit_campaign.hpp"
#include "rockfit/fitting/fitter.hpp"
#include "rockfit/fitting/trial_problem.hpp"
#include "synth_trial.hpp"

namespace rockfit::testing {

// Nelder–Mead only, no global stage, linearised intervals: a fit of a few dozen simulations.
inline fitting::FitOptions QuickFitOptions() {
  fitting::FitOptions options;
  options.method = fitting::FitMethod::kNelderMead;
  options.global.enabled = false;
  options.nelder_mead.max_evaluations = 30;
  options.intervals.method = fitting::IntervalMethod::kFast;
  options.num_threads = 1;
  return options;
}

// The problem of a 1.8 s synthetic recording released at 1 s (seed → noise).
inline fitting::TrialProblem QuickProblem(std::uint64_t seed) {
  const SynthTrial trial = MakeSynthTrial(0.2, 0.8, -2.0, 0.6, seed, 1.0, 1.8);
  return fitting::PrepareTrialProblem(trial.signal, trial.block, fitting::ParameterSet::Defaults());
}

// A trial of block "b1" in `position` whose settings text is `settings`; `prepared` counts its preparations.
inline fitting::CampaignTrial QuickCampaignTrial(const std::string& id, const std::string& position,
                                                 std::uint64_t seed, const std::string& settings,
                                                 std::shared_ptr<std::atomic<int>> prepared = nullptr) {
  fitting::CampaignTrial t;
  t.id = id;
  t.labels = {"b1", position, ""};
  t.settings = [settings] { return settings; };
  t.prepare = [seed, prepared] {
    if (prepared) ++*prepared;
    fitting::TrialProblem problem = QuickProblem(seed);
    return fitting::PreparedTrial{std::move(problem.objective), std::move(problem.start), QuickFitOptions(), nullptr, problem.release_roll};
  };
  return t;
}

}  // namespace rockfit::testing
