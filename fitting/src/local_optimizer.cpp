#include "rockfit/fitting/local_optimizer.hpp"

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

}  // namespace rockfit::fitting
