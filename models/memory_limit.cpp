#include "contact_ode/models/memory_limit.hpp"

#include <algorithm>
#include <fstream>
#include <limits>

#include <sys/resource.h>
#include <unistd.h>

namespace contact {

namespace {

// A cgroup's memory limit [bytes] from its control file, or +inf where there is none ("max" in
// cgroup v2, a number near 2^63 in v1) or the file is absent.
double cgroup_limit(const char* path) {
  std::ifstream file(path);
  double bytes = 0;
  if (!(file >> bytes) || !(bytes > 0) || bytes >= 0x1p62) return std::numeric_limits<double>::infinity();
  return bytes;
}

}  // namespace

double memory_limit() {
  static const double limit = [] {
    double bytes = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
    bytes = std::min({bytes, cgroup_limit("/sys/fs/cgroup/memory.max"),
                      cgroup_limit("/sys/fs/cgroup/memory/memory.limit_in_bytes")});
    rlimit as{};
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
      bytes = std::min(bytes, static_cast<double>(as.rlim_cur));
    return bytes;
  }();
  return limit;
}

double half_the_memory_limit() { return 0.5 * memory_limit(); }

}  // namespace contact
