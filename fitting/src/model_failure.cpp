#include "rockfit/fitting/model_failure.hpp"

#include "rockfit/core/enum_names.hpp"

namespace rockfit::fitting {

const char* ToString(ModelFailure failure) {
  switch (failure) {
    case ModelFailure::kNone: return "none";
    case ModelFailure::kNonFiniteParameter: return "non-finite parameter";
    case ModelFailure::kT0OutsideWindow: return "t0 outside the recording window";
    case ModelFailure::kInvalidParameters: return "invalid parameters";
    case ModelFailure::kSimulatorException: return "simulator exception";
    case ModelFailure::kOverturned: return "overturned";
    case ModelFailure::kEdgeImpact: return "edge impact";
    case ModelFailure::kFacetImpact: return "facet impact";
    case ModelFailure::kIntegrator: return "integrator";
    case ModelFailure::kImpactCascade: return "impact cascade";
    case ModelFailure::kTooManyImpacts: return "too many impacts";
    case ModelFailure::kFailed: return "failed";
    case ModelFailure::kIncompleteRun: return "incomplete run";
    case ModelFailure::kWrongSampleCount: return "model returned a wrong number of samples";
    case ModelFailure::kNonFiniteOutput: return "non-finite simulated angular velocity";
    case ModelFailure::kInterrupted: return "interrupted";
  }
  return "?";
}

bool FromString(std::string_view text, ModelFailure* value) {
  static constexpr ModelFailure kAll[] = {
      ModelFailure::kNone,           ModelFailure::kNonFiniteParameter, ModelFailure::kT0OutsideWindow,
      ModelFailure::kInvalidParameters, ModelFailure::kSimulatorException, ModelFailure::kOverturned,
      ModelFailure::kEdgeImpact,     ModelFailure::kFacetImpact,        ModelFailure::kIntegrator,
      ModelFailure::kImpactCascade,  ModelFailure::kTooManyImpacts,     ModelFailure::kFailed,
      ModelFailure::kIncompleteRun,  ModelFailure::kWrongSampleCount,   ModelFailure::kNonFiniteOutput,
      ModelFailure::kInterrupted};
  return core::FromStringAmong(text, kAll, value);
}

std::string FailureCategory(ModelFailure failure, core::ImpactStatus impact_status) {
  std::string category = ToString(failure);
  const bool impact = failure == ModelFailure::kEdgeImpact || failure == ModelFailure::kFacetImpact;
  if (impact && impact_status != core::ImpactStatus::kOk) category += std::string(" ") + core::ToString(impact_status);
  return category;
}

ModelFailure FromSimulation(core::FailureReason reason, core::ImpactStatus status) {
  switch (reason) {
    case core::FailureReason::kEdgeImpact:
      return status == core::ImpactStatus::kOk ? ModelFailure::kFailed : ModelFailure::kEdgeImpact;
    case core::FailureReason::kFacetImpact:
      return status == core::ImpactStatus::kOk ? ModelFailure::kFailed : ModelFailure::kFacetImpact;
    case core::FailureReason::kIntegratorStep: return ModelFailure::kIntegrator;
    case core::FailureReason::kImpactCascade: return ModelFailure::kImpactCascade;
    case core::FailureReason::kMaxImpacts: return ModelFailure::kTooManyImpacts;
    case core::FailureReason::kEnergyBlowUp:
    case core::FailureReason::kNone: break;
  }
  return ModelFailure::kFailed;
}

}  // namespace rockfit::fitting
