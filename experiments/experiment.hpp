#pragma once
// The skeleton every experiment shares, so that an experiment file is only its recipe:
//   options  declared on the Experiment (--out is added, with its default);
//   run      parses the command line (exit 0 after --help, 2 on bad input), checks that --out can
//            receive results before any work, starts the clock, runs the body, draws the figures
//            it queued (render(): one gnuplot run for all), then writes the body's outputs with
//            meta.json (options, command line, git revision, libraries, wall time) by a staged
//            swap, and prints where.
// Under mpirun (or srun) every rank runs the body and rank 0 alone writes; a sweep deals its
// cases out over the ranks with share(), and only rank 0 goes on to tables and figures.
// The body reports bad input by throwing std::invalid_argument (exit 2, nothing written) and a
// failed run by throwing anything else (exit 1, nothing written); require() turns a RunResult
// that failed into such an exception, naming the run.
#include "cli.hpp"
#include "output.hpp"

#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/method_registry.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

namespace contact {

struct RunResult;
class Ranks;

class Experiment : public cli::Options {
 public:
  Experiment(std::string name, std::string description, std::string default_out);
  ~Experiment();
  const std::string& out() const { return out_; }
  // The exit code: 0, 1 (run or write failed), 2 (bad input). The body returns nothing: it
  // reports failure by throwing, so that no exit code can be dropped on the way.
  template <class Body>
  int run(int argc, char** argv, Body&& body) {
    static_assert(std::is_void_v<std::invoke_result_t<Body&, OutputSet&>>,
                  "an experiment's body reports failure by throwing, not by returning a code");
    return run_body(argc, argv, std::function<void(OutputSet&)>(body));
  }
  // A sweep's cases 0 .. count-1: run_case(i) for each, its result as JSON (NaN and infinities
  // survive: the ranks exchange CBOR). Serially without mpirun; under mpirun case i runs on rank
  // i mod size. Returns every result in case order on rank 0, and std::nullopt on the others:
  // their share is done and the body returns. A case's exception is rethrown on rank 0 (the
  // first by case index; std::invalid_argument stays bad input) once every rank has finished.
  // One call per run, from the body.
  std::optional<std::vector<nlohmann::json>> share(
      std::size_t count, const std::function<nlohmann::json(std::size_t)>& run_case);

 private:
  int run_body(int argc, char** argv, const std::function<void(OutputSet& outputs)>& body);
  std::string out_;
  std::unique_ptr<Ranks> ranks_;
};

// "<status> at t = ... s: <solver message>": how a failed run ended.
std::string failure_text(const RunResult& r);
// Throws std::runtime_error "<what>: <status> at t = ... s: <solver message>" unless r succeeded.
RunResult require(RunResult r, const std::string& what);
// For sweeps, where a failed run is a row rather than the end: prints that same line on stderr
// when r failed, and returns whether it succeeded.
bool report(const RunResult& r, const std::string& what);

// A run a sweep will make, for the checks before its first.
struct PlannedRun {
  std::string what;  // how a message names it
  Method method;
  double t_end;
};
// Before a sweep's first run: throws std::invalid_argument naming --dt when a run would take more
// steps at its dt than a run may (solve() refuses such a run only when its turn comes, after the
// runs before it: zeno's game run, after half a minute of the others), with the least --dt at
// which every run fits (the run that needs the largest named). `option` is the option that set the
// steps (--dt, or rigid_impacts' list --dts).
void refuse_dt_beyond_work_limit(const std::vector<PlannedRun>& runs, const std::string& option = "--dt");

// Whether `method` reads the command-line option (a method setting such as --dt or --max-steps by
// the registry's list; --k and --law when it uses a contact law).
bool reads_option(const std::string& method, const std::string& option);

// For each of `options` given (a method setting such as --dt or --integrator; --k and --law, read by
// the methods that use a contact law) that none of `methods` reads, a note on stderr naming the
// options they do read, as co.solve() warns in Python.
void note_unread_options(const std::string& program, const cli::Options& app,
                         const std::vector<std::string>& methods, const std::vector<std::string>& options);

// A table row through share(): its cells as JSON (strings, integers and doubles keep their kind).
nlohmann::json row_to_json(const std::vector<Table::Cell>& row);
std::vector<Table::Cell> row_from_json(const nlohmann::json& cells);

}  // namespace contact
