#include "progress.hpp"

#include "process.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace contact {

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) && !std::getenv("CI")) {}

Progress::~Progress() {
  if (enabled_) fmt::print(stderr, "\r\033[K");
}

void Progress::step(const std::string& what) {
  throw_if_interrupted();  // every sweep passes here between runs
  ++done_;
  if (enabled_) fmt::print(stderr, "\r\033[K{} [{}/{}] {}", label_, done_, total_, what);
}

}  // namespace contact
