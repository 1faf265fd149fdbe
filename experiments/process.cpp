#include "process.hpp"

#include "cli.hpp"
#include "contact_ode/integrators/status.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string_view>
#include <system_error>
#include <thread>

extern char** environ;

namespace contact {

namespace {

volatile std::sig_atomic_t g_signal = 0;
// When the first stop signal came (CLOCK_MONOTONIC seconds; 0: none yet), claimed by one handler
// call: the copies of one interrupt may be handled on two threads at once.
std::atomic<double> g_first_signal_at{0};
static_assert(std::atomic<double>::is_always_lock_free);
const char* g_program = "contact-ode";  // a string literal, for the handlers' messages
// The children being waited for (by up to kSlots threads at once: the study runs experiments in
// parallel), to pass the stop signal on. Lock-free atomics, so the handler may read them.
constexpr int kSlots = 64;
std::atomic<pid_t> g_children[kSlots];
static_assert(std::atomic<pid_t>::is_always_lock_free);

void say(const char* text) {
  for (const char* part : {g_program, ": ", text}) {
    const ssize_t ignored = ::write(STDERR_FILENO, part, std::strlen(part));
    (void)ignored;  // nothing to be done about a closed stderr here
  }
}

// The stop that does not wait for the program (async-signal-safe throughout): the children are
// killed (they may ignore `sig`), and `sig` ends this process by its default action once the
// handler returns (or, if the folder swap holds it, once the swap is done). Scratch and staging
// folders the program was working in may be left, as after SIGKILL.
void stop_at_once(int sig, const char* why) {
  say(why);
  for (auto& slot : g_children)
    if (const pid_t child = slot.load(); child > 0) ::kill(child, SIGKILL);
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  ::raise(sig);
}

double monotonic_seconds() {  // clock_gettime is async-signal-safe
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

extern "C" void on_signal(int sig) {
  const int interrupted_errno = errno;  // the code the signal interrupted may be about to read it
  const double now = monotonic_seconds();
  if (double first = 0; !g_first_signal_at.compare_exchange_strong(first, now)) {
    // A second SIGINT, SIGTERM or SIGHUP (Ctrl-C pressed again): the user will not wait. Not a
    // copy of the first arriving within milliseconds of it (see kSameInterruptSeconds):
    // experiments under a study on a terminal got Ctrl-C from both, and stopped at once, their
    // staging folders left. SIGPIPE comes at every write to a closed pipe, and is no one's second
    // request.
    if (sig != SIGPIPE && now - first >= kSameInterruptSeconds)
      return stop_at_once(sig, "a second interrupt: stopping at once\n");
    errno = interrupted_errno;
    return;
  }
  g_signal = sig;
  request_stop();  // a solve in progress ends within a step (Status::Interrupted)
  // The flag is seen by our own loops only: inside a library that never returns to them (a peer
  // engine's step, OpenBLAS retrying an allocation forever under `ulimit -v`) the program would
  // run on, deaf to every further SIGTERM (`timeout` without -k waited forever).
  ::alarm(kStopGraceSeconds);  // armed once: a SIGPIPE at every later write must not put it off
  // Passed on to the children (kill is async-signal-safe): a Ctrl-C on a terminal reaches the
  // whole process group anyway, but a signal sent to this process alone must stop them too.
  for (auto& slot : g_children)
    if (const pid_t child = slot.load(); child > 0) ::kill(child, sig);
  errno = interrupted_errno;
}

static_assert(kStopGraceSeconds == 10, "the message below says 10 s");
extern "C" void on_stop_deadline(int) {
  stop_at_once(g_signal,
               "still running 10 s after the interrupt (inside a library that does not look "
               "at it): stopping at once\n");
}

// Holds a child's pid in a free slot while it is waited for.
class ChildSlot {
 public:
  explicit ChildSlot(pid_t pid) {
    for (auto& s : g_children) {
      pid_t free = 0;
      if (s.compare_exchange_strong(free, pid)) {
        slot_ = &s;
        return;
      }
    }
  }
  ~ChildSlot() {
    if (slot_) slot_->store(0);
  }
  ChildSlot(const ChildSlot&) = delete;
  ChildSlot& operator=(const ChildSlot&) = delete;

 private:
  std::atomic<pid_t>* slot_ = nullptr;
};

// This process's environment without the variables an MPI launcher sets (mpirun's OMPI_*, the
// PMI/PMIx of Slurm's srun): a child is a program of its own, not one more of our ranks, and
// would otherwise try to join this process's MPI job.
std::vector<char*> environment_for_child() {
  std::vector<char*> env;
  for (char** var = environ; *var != nullptr; ++var) {
    const std::string_view entry(*var);
    if (!entry.starts_with("OMPI_") && !entry.starts_with("PMI_") && !entry.starts_with("PMIX_"))
      env.push_back(*var);
  }
  env.push_back(nullptr);
  return env;
}

}  // namespace

sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&set, sig);
  return set;
}

void install_interrupt_handlers(const char* program) {
  g_program = program;
  struct sigaction deadline {};
  deadline.sa_handler = on_stop_deadline;
  sigemptyset(&deadline.sa_mask);
  sigaction(SIGALRM, &deadline, nullptr);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sa.sa_mask = stop_signals();  // one handler call at a time: a SIGTERM amid a SIGINT's waits for it
  sa.sa_flags = 0;              // no SA_RESTART: a blocking wait returns EINTR and the flag is seen
  // SIGPIPE: the reader of stdout has gone (`study | head`). Its default killed the study at once,
  // and the experiments it ran went on as orphans writing their folders. So did SIGHUP's (a closed
  // terminal, a supervisor's `kill -HUP`), but under `nohup` it is ignored, and stays so.
  for (const int sig : {SIGINT, SIGTERM, SIGPIPE}) sigaction(sig, &sa, nullptr);
  struct sigaction hangup {};
  if (sigaction(SIGHUP, nullptr, &hangup) == 0 && hangup.sa_handler != SIG_IGN)
    sigaction(SIGHUP, &sa, nullptr);
}

bool interrupted() { return g_signal != 0; }

void throw_if_interrupted() {
  if (interrupted()) throw Interrupted();
}

int run_process(const std::vector<std::string>& args, const std::filesystem::path& cwd,
                const std::filesystem::path& log) {
  throw_if_interrupted();
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  if (posix_spawn_file_actions_init(&actions) != 0)
    throw std::runtime_error("posix_spawn_file_actions_init failed");
  struct Cleanup {
    posix_spawn_file_actions_t* a;
    ~Cleanup() { posix_spawn_file_actions_destroy(a); }
  } cleanup{&actions};
  if (!cwd.empty() && posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str()) != 0)
    throw std::runtime_error("posix_spawn_file_actions_addchdir_np failed");
  if (!log.empty()) {
    if (posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                         0644) != 0 ||
        posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO) != 0)
      throw std::runtime_error("posix_spawn_file_actions_addopen failed");
  }
  pid_t pid = 0;
  std::vector<char*> env = environment_for_child();
  const int err = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), env.data());
  if (err != 0) throw std::runtime_error(fmt::format("cannot run {}: {}", args[0], std::strerror(err)));
  int status = 0;
  {
    const ChildSlot held(pid);
    if (interrupted()) ::kill(pid, g_signal);  // a signal between the spawn and the slot: not passed on
    while (::waitpid(pid, &status, 0) < 0)
      if (errno != EINTR)
        throw std::runtime_error(fmt::format("waiting for {}: {}", args[0], std::strerror(errno)));
  }
  // A child that finished (exit 0) before or despite the signal did its work (an experiment has
  // replaced its folder): that is reported; the caller's next check stops. Any other end after an
  // interrupt is the interrupt's.
  if (interrupted() && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) throw Interrupted();
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

void run_parallel(std::size_t count, long jobs, const std::function<void(std::size_t)>& body) {
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  std::exception_ptr failure;
  auto worker = [&] {
    for (std::size_t i; (i = next++) < count;) {
      try {
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> hold(lock);
        if (!failure) failure = std::current_exception();
        next = count;
        return;
      }
    }
  };
  std::vector<std::thread> threads;
  for (long j = 1; j < std::min<long>(jobs, static_cast<long>(count)); ++j) {
    try {
      threads.emplace_back(worker);
    } catch (const std::system_error&) {  // no more threads to be had: the ones started do the rest
      break;
    }
  }
  worker();
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

// The report a program prints must reach its reader: stdout is flushed at exit, so to a full disk
// the report was cut short and the program still exited 0.
int report_written(const char* name) {
  errno = 0;
  if (std::fflush(stdout) == 0 && std::ferror(stdout) == 0) return 0;
  fmt::print(stderr, "{}: cannot write its report to standard output: {}\n", name,
             errno != 0 ? std::strerror(errno) : "a write failed");
  return cli::kExitFailure;
}

int run_body(const char* name, int argc, char** argv, int (*body)(int, char**)) {
  try {
    return body(argc, argv);
  } catch (const Interrupted& stop) {
    fmt::print(stderr, "{}: interrupted; {}\n", name,
               stop.outcome.empty() ? "nothing written" : stop.outcome);
    return 128 + (g_signal != 0 ? static_cast<int>(g_signal) : SIGINT);
  } catch (const std::exception& e) {
    // A run the interrupt ended (Status::Interrupted) may surface as the experiment's own failure.
    if (interrupted()) {
      fmt::print(stderr, "{}: interrupted; nothing written\n", name);
      return 128 + static_cast<int>(g_signal);
    }
    fmt::print(stderr, "{}: {}\n", name, e.what());
    return dynamic_cast<const std::invalid_argument*>(&e) != nullptr ? cli::kExitBadInput : cli::kExitFailure;
  } catch (...) {
    fmt::print(stderr, "{}: unknown error\n", name);
    return cli::kExitFailure;
  }
}

}  // namespace

int guarded_main(const char* name, int argc, char** argv, int (*body)(int, char**)) {
  install_interrupt_handlers(name);
  const int code = run_body(name, argc, argv, body);
  return code != 0 ? code : report_written(name);
}

std::string first_line_of(const std::string& command) {
  std::string line;
  if (FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r")) {
    char buffer[512];
    if (std::fgets(buffer, sizeof buffer, pipe)) line = buffer;
    ::pclose(pipe);
  }
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return line;
}

}  // namespace contact
