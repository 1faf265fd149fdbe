#include "progress.hpp"

#include "process.hpp"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

namespace contact {

std::string progress_line(const std::string& label, std::size_t done, std::size_t total,
                          const std::string& what, std::size_t columns) {
  std::string line = fmt::format("{} [{}/{}] {}", label, done, total, what);
  if (columns > 0 && line.size() >= columns) line.resize(columns - 1);
  return line;
}

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) && !std::getenv("CI")) {}

// The line is drawn with the cursor left at its start, so that whatever the program prints next
// (a run's failure on stderr, the report on stdout) writes over it from the first column: it was
// glued to its end ("ball_drop [2/2] event-exactBall drop: m = 1 kg, ..."). Here the cursor is
// either still there (the line is erased) or at the start of an empty row below what was printed.
Progress::~Progress() {
  if (enabled_) fmt::print(stderr, "\033[K");
}

void Progress::step(const std::string& what) {
  throw_if_interrupted();  // every sweep passes here between runs
  ++done_;
  what_ = what;
  if (enabled_) draw(what_);
}

// Drawn at a whole percent of the span, and not before a fifth of a second from the run's start
// or from the last draw: a line costs microseconds (a terminal write and a window-size query), and
// ball_drop reports each run's wall time, which a draw at every percent made 16 times larger for
// the exact bounces (46 us -> 0.72 ms). A run that ends sooner draws nothing and pays at most a
// hundred clock reads.
std::function<void(double)> Progress::follow(double t_end) {
  if (!enabled_ || !(t_end > 0)) return {};
  using Clock = std::chrono::steady_clock;
  return [this, t_end, shown = 0.0, last = Clock::now()](double t) mutable {
    const double percent = std::floor(100 * t / t_end);
    if (!(percent > shown)) return;
    shown = percent;
    const auto now = Clock::now();
    if (now - last < std::chrono::milliseconds(200)) return;
    last = now;
    try {
      draw(fmt::format("{}: t = {:.4g} s of {:.4g} s", what_, t, t_end));
    } catch (const std::exception&) {
      // A line that cannot be drawn (a terminal gone) is no reason to end the run it follows.
    }
  };
}

void Progress::draw(const std::string& what) const {
  winsize size{};  // asked at every draw: the window may have been resized
  const std::size_t columns = ::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 ? size.ws_col : 0;
  std::fflush(stdout);  // what the program printed before comes before the line
  fmt::print(stderr, "\r\033[K{}\r", progress_line(label_, done_, total_, what, columns));
}

}  // namespace contact
