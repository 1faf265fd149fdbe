#include "sundials_handles.hpp"

#include <stdexcept>

namespace contact::sundials {

Context make_context() {
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0 || ctx == nullptr)
    throw std::runtime_error("SUNContext_Create failed");
  return Context(ctx);
}

}  // namespace contact::sundials
