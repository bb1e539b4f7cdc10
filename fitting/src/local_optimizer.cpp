#include "rockfit/fitting/local_optimizer.hpp"
#include "rockfit/core/enum_names.hpp"

namespace rockfit::fitting {

const char* ToString(TerminationType type) {
  switch (type) {
    case TerminationType::kConvergence: return "convergence";
    case TerminationType::kNoConvergence: return "no_convergence";
    case TerminationType::kFailure: return "failure";
    case TerminationType::kNotASearch: return "not_a_search";
  }
  return "failure";
}

bool FromString(std::string_view text, TerminationType* value) {
  static constexpr TerminationType kAll[] = {TerminationType::kConvergence, TerminationType::kNoConvergence, TerminationType::kFailure, TerminationType::kNotASearch};
  return core::FromStringAmong(text, kAll, value);
}

}  // namespace rockfit::fitting
