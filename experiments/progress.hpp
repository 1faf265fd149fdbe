#pragma once
// One-line progress for long sweeps: shown on a terminal, silent in CI or when stderr is a file.
#include <cstddef>
#include <functional>
#include <string>

namespace contact {

// The progress line's text, "label [done/total] what", cut to columns - 1 characters (0: uncut):
// "\r" returns to the start of the terminal's last row only, so a line that wrapped left a copy of
// its first row behind at every step in a narrow window.
std::string progress_line(const std::string& label, std::size_t done, std::size_t total,
                          const std::string& what, std::size_t columns);

class Progress {
 public:
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void step(const std::string& what);
  // For SolveOptions::progress of the run the last step() announced: the line gains how far the
  // run has come ("penalty: t = 1.5 s of 3 s"), redrawn at whole percents of t_end, at most five
  // times a second and never in a run's first 0.2 s (which a fast run's timing would pay for),
  // so that a long run shows it is moving. Empty where no line is shown: the run calls nothing.
  std::function<void(double t)> follow(double t_end);

 private:
  void draw(const std::string& what) const;

  std::string label_, what_;
  std::size_t total_, done_ = 0;
  bool enabled_;
};

}  // namespace contact
