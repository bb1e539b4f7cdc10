// Why a model run, or one evaluation of the error (28), gave no usable ω_s. The fitters treat such a point as
// infeasible and count it by its category (FitSummary::failures_by_reason, the "failures" of `fit --json`).
#pragma once

#include <string>
#include <string_view>

#include "rockfit/core/general_impact_map.hpp"
#include "rockfit/core/simulator.hpp"

namespace rockfit::fitting {

enum class ModelFailure {
  kNone,                // the run succeeded
  kNonFiniteParameter,  // a parameter value is NaN or infinite
  kT0OutsideWindow,     // the release time leaves no sample of the recording in the window
  kInvalidParameters,   // the simulator refused the parameters (InvalidArgument)
  kSimulatorException,  // the simulator threw anything else
  kOverturned,          // the block overturned inside the window
  kEdgeImpact,          // an edge impact map failed; its core::ImpactStatus says how
  kFacetImpact,         // a facet impact map failed; its core::ImpactStatus says how
  kIntegrator,          // the integrator's step fell below its minimum
  kImpactCascade,       // impacts accumulated in time (Zeno) without reaching rest
  kTooManyImpacts,      // the run reached its impact budget
  kFailed,              // the energy blew up, or a map reported ok and gave a non-finite ω⁺
  kIncompleteRun,       // the run ended before the last sample time
  kWrongSampleCount,    // the model returned another number of samples than asked for
  kNonFiniteOutput,     // the simulated ω gave a non-finite error (28)
  kInterrupted,         // the user interrupted the fit; every later run fails at once
};

// "none", "non-finite parameter", "t0 outside the recording window", "invalid parameters", "simulator exception",
// "overturned", "edge impact", "facet impact", "integrator", "impact cascade", "too many impacts", "failed",
// "incomplete run", "model returned a wrong number of samples", "non-finite simulated angular velocity",
// "interrupted".
const char* ToString(ModelFailure failure);
bool FromString(std::string_view text, ModelFailure* value);  // the inverse of ToString

// The category a failure is counted and reported by: ToString(failure), and for an impact failure with a status
// also that status ("edge impact singular", "facet impact infeasible").
std::string FailureCategory(ModelFailure failure, core::ImpactStatus impact_status = core::ImpactStatus::kOk);

// The failure of a simulator run that ended with EndReason::kFailed (core::Trajectory::failure; for an impact
// failure, the status of the last impact record). An impact failure whose map reported ok gave a non-finite ω⁺
// and is kFailed, as is the energy blow-up.
ModelFailure FromSimulation(core::FailureReason reason, core::ImpactStatus status);

}  // namespace rockfit::fitting
