// GSL's default error handler aborts the program; rockfit checks every GSL status itself.
#pragma once

namespace rockfit::core {

// Calls gsl_set_error_handler_off() once per process (thread-safe).
void EnsureGslErrorHandlerOff();

}  // namespace rockfit::core
