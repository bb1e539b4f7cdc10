#include "rockfit/core/gsl_setup.hpp"

#include <gsl/gsl_errno.h>

namespace rockfit::core {

void EnsureGslErrorHandlerOff() {
  static const bool kDone = [] {
    gsl_set_error_handler_off();
    return true;
  }();
  (void)kDone;
}

}  // namespace rockfit::core
