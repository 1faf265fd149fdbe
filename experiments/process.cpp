#include "process.hpp"

#include "cli.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>

extern char** environ;

namespace contact {

namespace {

volatile std::sig_atomic_t g_signal = 0;
volatile pid_t g_child = 0;  // the child being waited for, to pass SIGTERM on

extern "C" void on_signal(int sig) {
  g_signal = sig;
  const pid_t child = g_child;
  // Passed on to the child (kill is async-signal-safe): a Ctrl-C on a terminal reaches the whole
  // process group anyway, but a signal sent to this process alone must stop the child too.
  if (child > 0) ::kill(child, sig);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocking wait returns EINTR and the flag is seen
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
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
  const int err = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  if (err != 0) throw std::runtime_error(fmt::format("cannot run {}: {}", args[0], std::strerror(err)));
  g_child = pid;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      g_child = 0;
      throw std::runtime_error(fmt::format("waiting for {}: {}", args[0], std::strerror(errno)));
    }
  }
  g_child = 0;
  throw_if_interrupted();
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

int guarded_main(const char* name, int argc, char** argv, int (*body)(int, char**)) {
  install_interrupt_handlers();
  try {
    return body(argc, argv);
  } catch (const Interrupted&) {
    fmt::print(stderr, "{}: interrupted; nothing written\n", name);
    return 128 + (g_signal != 0 ? static_cast<int>(g_signal) : SIGINT);
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "{}: {}\n", name, e.what());
    return cli::kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}: {}\n", name, e.what());
    return cli::kExitFailure;
  } catch (...) {
    fmt::print(stderr, "{}: unknown error\n", name);
    return cli::kExitFailure;
  }
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
