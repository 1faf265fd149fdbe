#pragma once
// Dense state-sized matrices above 4 GiB in all are refused before allocation, by SUNDIALS' dense
// linear solver and GSL's implicit steppers alike: 4 GiB is a sixth of this machine's memory, and
// a larger request either fails (SUNDenseMatrix returned NULL, which used to be dereferenced) or
// is granted by overcommit and thrashes, or meets the OOM killer. Band, KLU and GMRES scale
// linearly.
#include "contact_ode/integrators/status.hpp"

#include <fmt/format.h>

#include <string>

namespace contact {

inline constexpr double kMaxDenseBytes = 4.0 * 1024 * 1024 * 1024;

// Throws SolverFailure(WorkLimit) at t = 0 when `count` dense n x n matrices pass kMaxDenseBytes;
// `instead` says what to use.
inline void refuse_dense_beyond_limit(double n, int count, const std::string& instead) {
  const double bytes = 8.0 * count * n * n;
  if (bytes > kMaxDenseBytes)
    throw SolverFailure(
        Status::WorkLimit, 0.0,
        fmt::format("a dense {0:.0f} x {0:.0f} Jacobian{1} {2:.3g} GiB (at most {3:g}): {4}", n,
                    count > 1 ? fmt::format(" and {} more of its size need", count - 1) : " needs",
                    bytes / (1 << 30), kMaxDenseBytes / (1 << 30), instead));
}

}  // namespace contact
