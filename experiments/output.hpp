#pragma once
// Results of an experiment are gathered in memory and written only once the experiment has
// succeeded, each file to a temporary name and then renamed into place: a failed or refused run
// leaves no file, and a reader never sees a half-written one.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>

namespace contact {

class Table;

class OutputSet {
 public:
  void add(const std::string& name, std::string content) { files_[name] = std::move(content); }
  // name.csv, name.md and name.tex.
  void add_table(const std::string& name, const Table& table);
  // Creates `dir` and writes every file; throws std::runtime_error naming the path on failure.
  void write(const std::filesystem::path& dir) const;
  const std::map<std::string, std::string>& files() const { return files_; }

 private:
  std::map<std::string, std::string> files_;
};

// meta.json: the experiment, every option with its value, the command line, the git revision,
// the library and compiler versions, and the wall time.
nlohmann::json run_metadata(const CLI::App& app, int argc, char** argv, double wall_time_s);

// The versions of the libraries the project links, e.g. {"SUNDIALS": "6.4.1", ...}.
nlohmann::json library_versions();

// Checks before running that --out can be created as a directory; returns an error line or "".
std::string check_output_dir(const std::filesystem::path& dir);

// The end every experiment shares: adds meta.json (wall time since `start`), writes everything to
// `dir`, prints where. Returns the exit code: 0, or 1 (with the reason on stderr) if writing failed.
int write_outputs(OutputSet& files, const CLI::App& app, int argc, char** argv,
                  std::chrono::steady_clock::time_point start, const std::filesystem::path& dir);

}  // namespace contact
