#include "sundials_handles.hpp"

#include "contact_ode/integrators/status.hpp"

namespace contact::sundials {

Context make_context() {
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0 || ctx == nullptr)
    throw SolverFailure(Status::SolverError, 0.0, "SUNContext_Create failed");
  return Context(ctx);
}

}  // namespace contact::sundials
