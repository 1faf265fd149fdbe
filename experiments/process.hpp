#pragma once
// How an experiment process starts, runs children and stops.
//
// Interrupts: SIGINT, SIGTERM, SIGHUP (the terminal closed) and SIGPIPE (stdout's reader gone)
// first only raise a flag. Long work checks it at every progress step, every figure and every child
// process (throw_if_interrupted), and an Interrupted exception unwinds the stack, so that scratch
// and staging folders are removed by their owners and no half-written output is left; guarded_main
// turns it into exit code 128 + the signal (130 for SIGINT).
// A signal reaching the process while it waits for a child is passed on to the child.
//
// Children (gnuplot, the experiments a study runs) are started without a shell: arguments are
// passed as they are, so a quote or a space in a path (TMPDIR, --out) cannot break a command.
#include <csignal>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace contact {

// Not a std::exception on purpose: the handlers experiments keep for their own failures
// (catch (const std::exception&)) must not swallow an interrupt. `outcome` says what the run
// leaves behind (empty: nothing written), for a program, like the study, that keeps some of it.
struct Interrupted {
  std::string outcome;
};

// Installs the flag handlers of the signals stop_signals() holds (once per process; SIGHUP only
// where it is not ignored: `nohup` means it); `program` (a string literal) names it in their
// messages. The stop is the program's own only while it is quick: a second stop signal (not
// SIGPIPE), or kStopGraceSeconds after the first without an end, stops it at once by the signal's
// default action (its children killed), whatever it is doing. A signal within
// kSameInterruptSeconds of the first is a copy of it, not a second request: one Ctrl-C reaches
// every process of the terminal's group and the study passes it on to its experiments, and
// `timeout` signals its command and then its group, so one interrupt may arrive twice.
constexpr unsigned kStopGraceSeconds = 10;
constexpr double kSameInterruptSeconds = 1.0;
void install_interrupt_handlers(const char* program);
// The signals that stop a program: SIGINT, SIGTERM, SIGHUP, SIGPIPE.
sigset_t stop_signals();
bool interrupted();
void throw_if_interrupted();

// Runs `argv` (argv[0] looked up on PATH if it has no slash) in `cwd` (empty: this one), with
// stdout and stderr sent to `log` (empty: inherited). Returns the exit code, 128 + N if killed by
// signal N, or throws std::runtime_error if it cannot be started; throws Interrupted if this
// process was interrupted before it started or meanwhile, unless the child exited 0 (its work is
// done, and the caller's next check stops).
int run_process(const std::vector<std::string>& argv, const std::filesystem::path& cwd = {},
                const std::filesystem::path& log = {});

// Calls body(i) for every i in [0, count), each once, on up to `jobs` threads (this one among
// them). The first exception a call throws (an Interrupted too) stops the others taking new
// indices and is rethrown here once every thread has stopped.
void run_parallel(std::size_t count, long jobs, const std::function<void(std::size_t)>& body);

// A text file's whole content ("" if it cannot be read).
std::string read_text(const std::filesystem::path& path);

// The first line a shell command prints on stdout, without its newline ("" if it prints nothing
// or cannot run): tool versions and machine facts for the paper.
std::string first_line_of(const std::string& command);

// main() for every executable: installs the handlers and runs `body`; bad input it throws as
// std::invalid_argument is exit 2, any other exception exit 1, an interrupt 130, each with one
// line on stderr naming the program, and a report that could not be written to stdout (a full
// disk) exit 1. No exception escapes.
int guarded_main(const char* name, int argc, char** argv, int (*body)(int, char**));

}  // namespace contact
