// The hybrid simulator of rockfit::core as the fitter's trajectory model: one run from the release at tilt α
// per evaluation, sampled from the integrator's dense output exactly at the requested times after the release
// (docs/design.md §4, §7). Runs that overturn or fail become model failures with a short category for counting.
#pragma once

#include <cstddef>
#include <string>

#include "rockfit/core/block.hpp"
#include "rockfit/core/simulator.hpp"
#include "rockfit/fitting/trajectory_model.hpp"

namespace rockfit::fitting {

struct SimulatorModelOptions {
  // Tolerances, Zeno and rest thresholds, release edge, gravity. sample_times_s, stop, t_max_s and
  // sample_attitude are set for each run (the run ends at the last requested time).
  core::SimulationOptions simulation = DefaultFittingSimulation();
  // The simulator's defaults, except a cap on the impacts of one run: a fitting window has a few dozen; a
  // parameter set that makes the block wobble across side edges for thousands of impacts is a failure.
  static core::SimulationOptions DefaultFittingSimulation();
  void Validate() const;  // throws InvalidArgument
};

class SimulatorModel final : public TrajectoryModel {
 public:
  SimulatorModel(const core::Block& block, SimulatorModelOptions options = {});
  void Evaluate(const core::ModelParameters& params, const std::vector<double>& t_after_release_s,
                ModelOutput* out) const override;
  // Exact derivatives: planar runs (λ_lat = 0: core/planar_sensitivity.hpp) and 3D runs (λ_lat ≠ 0, no-spin facet
  // rule: core/spatial_sensitivity.hpp); none where those passes give none (dw_B_dparams left empty).
  void EvaluateWithSensitivities(const core::ModelParameters& params, const std::vector<double>& t_after_release_s,
                                 ModelOutput* out) const override;
  std::string Describe() const override;
  std::shared_ptr<const TrajectoryModel> WithLooserTolerance(double rel_tol) const override;
  const core::Block& block() const { return block_; }
  const SimulatorModelOptions& options() const { return options_; }

 private:
  void Run(const core::ModelParameters& params, const std::vector<double>& t_after_release_s, bool sensitivities,
           ModelOutput* out) const;

  core::Block block_;
  SimulatorModelOptions options_;
};


}  // namespace rockfit::fitting
