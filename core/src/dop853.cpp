#include "dop853.hpp"

#include <string>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {

void Dop853Options::Validate() const {
  // Below this the requested accuracy is beyond double precision; the step control would only shrink h.
  constexpr double kSmallestRelTol = 1e-15;
  if (!std::isfinite(rel_tol) || rel_tol < kSmallestRelTol || rel_tol >= 1.0) {
    throw InvalidArgument("integrator rel_tol must lie in [1e-15, 1), got " + std::to_string(rel_tol));
  }
  if (!std::isfinite(abs_tol) || abs_tol <= 0.0) {
    throw InvalidArgument("integrator abs_tol must be a positive finite number, got " + std::to_string(abs_tol));
  }
  if (!(max_step > 0.0)) {
    throw InvalidArgument("integrator max_step must be positive, got " + std::to_string(max_step));
  }
}

}  // namespace rockfit::core
