#include "experiment.hpp"

#include "contact_ode/integrators/run_result.hpp"
#include "process.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>
#include <stdexcept>

namespace contact {

const char* git_revision();  // generated at build time (cmake/git_revision.cmake)

Experiment::Experiment(std::string name, std::string description, std::string default_out)
    : cli::Options(std::move(name), std::move(description)), out_(std::move(default_out)) {
  add("--out", out_, "output directory (replaced whole when the run succeeds)");
}

int Experiment::run_body(int argc, char** argv, const std::function<void(OutputSet&)>& body) {
  if (const int code = parse(argc, argv); code >= 0) return code;
  if (const auto err = check_output_dir(out_); !err.empty()) {
    std::cerr << program() << ": " << err << "\n";
    return cli::kExitBadInput;
  }
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs;
  body(outputs);  // exceptions go to guarded_main: exit 2 for bad input, 1 otherwise
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json meta = {
      {"experiment", program()},
      {"options", nlohmann::json::parse(values_json())},
      {"command_line", std::vector<std::string>(argv, argv + argc)},
      {"git_revision", git_revision()},
      {"libraries", nlohmann::json::parse(library_versions_json())},
      {"wall_time_s", wall},
  };
  outputs.add("meta.json", meta.dump(2) + "\n");
  try {
    outputs.write(out_);
  } catch (const std::exception& e) {
    std::cerr << program() << ": " << e.what() << "\n";
    return cli::kExitFailure;
  }
  fmt::print("\nwrote {} files to {} ({:.2f} s)\n", outputs.files().size(), out_, wall);
  return 0;
}

namespace {
std::string failure(const RunResult& r, const std::string& what) {
  return fmt::format("{}: {} at t = {:.9g} s: {}", what, to_string(r.status), r.t_reached, r.message);
}
}  // namespace

RunResult require(RunResult r, const std::string& what) {
  if (!r.ok()) throw std::runtime_error(failure(r, what));
  return r;
}

bool report(const RunResult& r, const std::string& what) {
  if (!r.ok()) std::cerr << failure(r, what) << "\n";
  return r.ok();
}

}  // namespace contact
