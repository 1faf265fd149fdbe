#include "contact_ode/integrators/gsl_handles.hpp"

#include <gsl/gsl_errno.h>

#include <mutex>

namespace contact::gsl {

void report_errors_by_return_code() {
  static std::once_flag once;
  std::call_once(once, [] { gsl_set_error_handler_off(); });
}

}  // namespace contact::gsl
