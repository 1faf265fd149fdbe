#pragma once
// One-line progress for long sweeps: shown on a terminal, silent in CI or when stderr is a file.
#include <cstddef>
#include <string>

namespace contact {

class Progress {
 public:
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void step(const std::string& what);

 private:
  std::string label_;
  std::size_t total_, done_ = 0;
  bool enabled_;
};

}  // namespace contact
