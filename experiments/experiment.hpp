#pragma once
// The skeleton every experiment shares, so that an experiment file is only its recipe:
//   options  declared on the Experiment (--out is added, with its default);
//   run      parses the command line (exit 0 after --help, 2 on bad input), checks that --out can
//            receive results before any work, starts the clock, runs the body, then writes the
//            body's outputs with meta.json (options, command line, git revision, libraries, wall
//            time) by a staged swap, and prints where.
// The body reports bad input by throwing std::invalid_argument (exit 2, nothing written) and a
// failed run by throwing anything else (exit 1, nothing written); require() turns a RunResult
// that failed into such an exception, naming the run.
#include "cli.hpp"
#include "output.hpp"

#include <functional>
#include <string>
#include <type_traits>

namespace contact {

struct RunResult;

class Experiment : public cli::Options {
 public:
  Experiment(std::string name, std::string description, std::string default_out);
  const std::string& out() const { return out_; }
  // The exit code: 0, 1 (run or write failed), 2 (bad input). The body returns nothing: it
  // reports failure by throwing, so that no exit code can be dropped on the way.
  template <class Body>
  int run(int argc, char** argv, Body&& body) {
    static_assert(std::is_void_v<std::invoke_result_t<Body&, OutputSet&>>,
                  "an experiment's body reports failure by throwing, not by returning a code");
    return run_body(argc, argv, std::function<void(OutputSet&)>(body));
  }

 private:
  int run_body(int argc, char** argv, const std::function<void(OutputSet& outputs)>& body);
  std::string out_;
};

// Throws std::runtime_error "<what>: <status> at t = ... s: <solver message>" unless r succeeded.
RunResult require(RunResult r, const std::string& what);
// For sweeps, where a failed run is a row rather than the end: prints that same line on stderr
// when r failed, and returns whether it succeeded.
bool report(const RunResult& r, const std::string& what);

}  // namespace contact
