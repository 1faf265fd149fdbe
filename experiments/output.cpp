#include "output.hpp"

#include "contact_ode/analysis/fit.hpp"
#include "contact_ode/analysis/table.hpp"
#include "contact_ode/integrators/integrator.hpp"
#include "process.hpp"

#include <fmt/format.h>
#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <unistd.h>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace contact {

const char* git_revision();  // generated at build time (cmake/git_revision.cmake)

namespace fs = std::filesystem;

void OutputSet::add_table(const std::string& name, const Table& table) {
  add(name + ".csv", table.to_csv());
  add(name + ".md", table.to_markdown());
  add(name + ".tex", table.to_latex());
}

namespace {

void write_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
  if (!out.flush()) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
}

// Blocks the stop signals while alive, so that a swap of folders is not cut in half; a signal
// that arrives meanwhile is delivered (and its flag raised) when it ends.
struct SignalsHeld {
  sigset_t old{};
  SignalsHeld() {
    const sigset_t set = stop_signals();
    sigprocmask(SIG_BLOCK, &set, &old);
  }
  ~SignalsHeld() { sigprocmask(SIG_SETMASK, &old, nullptr); }
};

std::string sibling_name(const fs::path& dir, const char* what) {
  return fmt::format(".{}.{}-{}", dir.filename().string(), what, ::getpid());
}

}  // namespace

fs::path make_scratch_dir(const std::string& stem) {
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path(ec);
  std::string pattern = (tmp / (stem + "_XXXXXX")).string();
  if (!ec && ::mkdtemp(pattern.data()) != nullptr) return pattern;
  const int err = errno;
  const std::string why = ec ? ec.message() : std::strerror(err);
  // A folder that is missing, not a folder or not writable is the setting's fault (bad input); a
  // full disk or too many open files is the run's (exit 1).
  if (!ec && err != ENOENT && err != ENOTDIR && err != EACCES && err != EROFS)
    throw std::runtime_error(fmt::format("cannot make a scratch folder in {}: {}", tmp.string(), why));
  const char* tmpdir = std::getenv("TMPDIR");
  throw std::invalid_argument(
      tmpdir != nullptr
          ? fmt::format(
                "TMPDIR: value '{}' is not a folder where a scratch folder can be made ({}); accepted: "
                "an existing, writable folder",
                tmpdir, why)
          : fmt::format("cannot make a scratch folder in {} ({}); set TMPDIR to an existing, writable folder",
                        tmp.string(), why));
}

void require_scratch_location() { const ScratchDir probe{make_scratch_dir("contact_probe")}; }

ScratchDir::~ScratchDir() {
  std::error_code ec;
  if (!path.empty()) fs::remove_all(path, ec);
}

void OutputSet::write(const fs::path& dir_in, const std::string& program) const {
  throw_if_interrupted();
  // (An empty program is check_output_dir's folder written into, never one replaced whole.)
  if (program.empty())
    throw std::logic_error("OutputSet::write: the program whose results it replaces is empty");
  // Checked again here, whatever the caller checked: replacing a folder that is not an earlier
  // run's results would delete what it holds (paper_numbers once replaced --out's whole folder).
  if (const std::string refusal = check_output_dir(dir_in, program); !refusal.empty())
    throw std::runtime_error(refusal);
  if (!figures_.empty())
    throw std::logic_error(fmt::format("{} figure(s) queued but not drawn (draw_figures)", figures_.size()));
  std::error_code ec;
  const fs::path target = results_folder(dir_in, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot resolve {}: {}", dir_in.string(), ec.message()));
  fs::create_directories(target.parent_path(), ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot create {}: {}", target.parent_path().string(), ec.message()));
  ScratchDir staging{target.parent_path() / sibling_name(target, "staging")};
  fs::create_directory(staging.path, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot create {}: {}", staging.path.string(), ec.message()));
  for (const auto& [name, content] : files_) write_file(staging.path / name, content);
  throw_if_interrupted();
  const SignalsHeld held;
  ScratchDir previous;
  if (fs::exists(target, ec)) {
    previous.path = target.parent_path() / sibling_name(target, "previous");
    fs::rename(target, previous.path, ec);
    if (ec) {
      previous.path.clear();
      throw std::runtime_error(fmt::format("cannot replace {}: {}", target.string(), ec.message()));
    }
  }
  fs::rename(staging.path, target, ec);
  if (ec) {
    if (!previous.path.empty()) {
      std::error_code back;
      fs::rename(previous.path, target, back);  // keep the earlier results
      if (!back) previous.path.clear();
    }
    throw std::runtime_error(fmt::format("cannot write {}: {}", target.string(), ec.message()));
  }
  staging.path.clear();  // it is the results now; `previous` goes with its owner
}

void OutputSet::write_into(const fs::path& dir) const {
  throw_if_interrupted();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot create {}: {}", dir.string(), ec.message()));
  const SignalsHeld held;
  for (const auto& [name, content] : files_) {
    const fs::path final_path = dir / name, tmp = dir / ("." + name + ".tmp");
    write_file(tmp, content);
    fs::rename(tmp, final_path, ec);
    if (ec) {
      std::error_code ignored;  // the rename's error is the one to tell (it said "Success")
      fs::remove(tmp, ignored);
      throw std::runtime_error(fmt::format("cannot write {}: {}", final_path.string(), ec.message()));
    }
  }
}

namespace {

std::string library_versions_json() {
  return nlohmann::json{
      {"sundials", sundials_version()},
      {"gsl", gsl_version_string()},
      {"eigen", fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
      {"fmt", fmt::format("{}.{}.{}", FMT_VERSION / 10000, FMT_VERSION / 100 % 100, FMT_VERSION % 100)},
      {"cli11", CLI11_VERSION},
      {"nlohmann_json", fmt::format("{}.{}.{}", NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                    NLOHMANN_JSON_VERSION_PATCH)},
      {"compiler", fmt::format("g++ {}", __VERSION__)},
  }
      .dump();  // ASCII: version numbers and the compiler's
}

// The program whose results `dir` holds, by its meta.json: "" when there is none, or it names none.
std::string owner_of(const fs::path& dir) {
  std::ifstream in(dir / "meta.json");
  if (!in) return "";
  const nlohmann::json meta = nlohmann::json::parse(in, nullptr, false);
  if (!meta.is_object() || !meta.contains("experiment") || !meta["experiment"].is_string()) return "";
  return meta["experiment"].get<std::string>();
}

}  // namespace

std::string run_meta_json(const std::string& program, const std::string& options_json,
                          const std::vector<std::string>& command_line, double wall_time_s, int ranks) {
  return json_text(
             nlohmann::json{
                 {"experiment", program},
                 {"options", nlohmann::json::parse(options_json)},
                 {"command_line", command_line},
                 {"git_revision", git_revision()},
                 {"libraries", nlohmann::json::parse(library_versions_json())},
                 {"wall_time_s", wall_time_s},
                 {"mpi_ranks", ranks},
             },
             2) +
         "\n";
}

std::string json_text(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

bool stays_inside(const fs::path& p) {
  return !p.empty() && !p.is_absolute() && std::find(p.begin(), p.end(), fs::path("..")) == p.end();
}

fs::path results_folder(const fs::path& dir, std::error_code& ec) {
  fs::path abs = fs::absolute(dir, ec).lexically_normal();
  if (ec) return {};
  if (abs.filename().empty()) abs = abs.parent_path();  // "a/." normalises to "a/"
  // A link to a folder (results -> /data/results) stands for the folder: replacing the link by a
  // new folder beside it left the link's target with the old results and the link gone.
  if (fs::is_symlink(abs, ec) && fs::is_directory(abs, ec)) return fs::canonical(abs, ec);
  ec.clear();
  return abs;
}

std::string check_output_dir(const fs::path& dir, const std::string& program) {
  auto refuse = [&](const std::string& why) {
    return fmt::format("--out: value '{}' {}; accepted: {}", dir.string(), why,
                       program.empty() ? "a writable folder"
                                       : fmt::format("a new folder, an empty one, or an earlier --out of "
                                                     "{} (it is replaced whole)",
                                                     program));
  };
  if (dir.empty()) return refuse("is empty");
  std::error_code ec;
  const fs::path abs = results_folder(dir, ec);
  if (ec) return refuse(ec.message());
  if (fs::is_symlink(abs, ec) && !fs::exists(abs, ec))
    return refuse(fmt::format("is a link to nothing ({})", fs::read_symlink(abs, ec).string()));
  // The staging folder beside it adds ".NAME.staging-PID": every name must leave room for it.
  for (const auto& part : abs)
    if (part.string().size() > 200) return refuse("has a name longer than 200 characters");
  if (abs.string().size() > 3000) return refuse("is longer than 3000 characters");
  // The nearest existing ancestor must be a writable folder (a file there means "under a file").
  fs::path existing = abs;
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  if (!fs::is_directory(existing, ec))
    return refuse(existing == abs ? "exists and is not a folder"
                                  : fmt::format("lies under the file {}", existing.string()));
  if (existing != abs && ::access(existing.c_str(), W_OK | X_OK) != 0)
    return refuse(fmt::format("cannot be created: {} is not writable", existing.string()));
  if (existing == abs && !program.empty()) {
    if (::access(abs.parent_path().c_str(), W_OK | X_OK) != 0)
      return refuse(fmt::format("cannot be replaced: {} is not writable", abs.parent_path().string()));
    if (!fs::is_empty(abs, ec)) {
      if (const std::string owner = owner_of(abs); owner.empty())
        return refuse("is a folder that is not empty and holds no meta.json of an earlier run");
      else if (owner != program)
        return refuse(
            fmt::format("holds the results of {} (its meta.json says so), not of {}", owner, program));
    }
  }
  const fs::path here = fs::current_path(ec);
  if (abs == here || here.string().rfind(abs.string() + "/", 0) == 0)
    return refuse("is the current folder or holds it");
  return {};
}

}  // namespace contact
