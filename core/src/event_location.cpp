#include "rockfit/core/event_location.hpp"

#include <cmath>
#include <new>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include "rockfit/core/gsl_setup.hpp"

namespace rockfit::core {
namespace {

constexpr int kMaxBrentIterations = 200;  // Brent halves the bracket at worst every few steps

}  // namespace

RootPolisher::RootPolisher() {
  EnsureGslErrorHandlerOff();
  solver_ = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (solver_ == nullptr) throw std::bad_alloc();
}

RootPolisher::~RootPolisher() { gsl_root_fsolver_free(static_cast<gsl_root_fsolver*>(solver_)); }

std::optional<double> RootPolisher::SolveErased(double (*f)(double, void*), void* params, double lo, double hi,
                                                double tolerance) {
  auto* solver = static_cast<gsl_root_fsolver*>(solver_);
  gsl_function function;
  function.function = f;
  function.params = params;
  // The solver evaluates both ends and refuses a bracket without a sign change (the error handler is off).
  if (gsl_root_fsolver_set(solver, &function, lo, hi) != GSL_SUCCESS) return std::nullopt;
  for (int iteration = 0; iteration < kMaxBrentIterations; ++iteration) {
    if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS) return std::nullopt;
    const double x_lo = gsl_root_fsolver_x_lower(solver);
    const double x_hi = gsl_root_fsolver_x_upper(solver);
    if (gsl_root_test_interval(x_lo, x_hi, tolerance, 0.0) == GSL_SUCCESS) return gsl_root_fsolver_root(solver);
  }
  return std::nullopt;
}

}  // namespace rockfit::core
