// After EnsureGslErrorHandlerOff() a GSL error is a returned status, not an abort.
#include "rockfit/core/gsl_setup.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <gtest/gtest.h>

namespace rockfit::core {
namespace {

double Positive(double x, void*) { return x * x + 1.0; }

TEST(GslSetup, ErrorsBecomeStatusesInsteadOfAborting) {
  EnsureGslErrorHandlerOff();
  EnsureGslErrorHandlerOff();  // idempotent
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  ASSERT_NE(solver, nullptr);
  gsl_function f;
  f.function = &Positive;
  f.params = nullptr;
  // No sign change in the bracket: GSL's default handler would abort here.
  EXPECT_EQ(gsl_root_fsolver_set(solver, &f, -1.0, 1.0), GSL_EINVAL);
  gsl_root_fsolver_free(solver);
}

}  // namespace
}  // namespace rockfit::core
