#include "output.hpp"

#include "sundials_integrators.hpp"
#include "fit.hpp"
#include "table.hpp"

#include <CLI/Version.hpp>
#include <Eigen/Core>
#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

#ifndef CONTACT_ODE_GIT_REVISION
#define CONTACT_ODE_GIT_REVISION "unknown"
#endif

namespace contact {

namespace fs = std::filesystem;

void OutputSet::add_table(const std::string& name, const Table& table) {
  add(name + ".csv", table.to_csv());
  add(name + ".md", table.to_markdown());
  add(name + ".tex", table.to_latex());
}

void OutputSet::write(const fs::path& dir) const {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot create {}: {}", dir.string(), ec.message()));
  for (const auto& [name, content] : files_) {
    const fs::path final_path = dir / name, tmp = dir / ("." + name + ".tmp");
    {
      std::ofstream out(tmp, std::ios::binary);
      out << content;
      if (!out.flush()) throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
    }
    fs::rename(tmp, final_path, ec);
    if (ec) throw std::runtime_error(fmt::format("cannot write {}: {}", final_path.string(), ec.message()));
  }
}

nlohmann::json library_versions() {
  return {
      {"sundials", sundials_version()},
      {"gsl", gsl_version_string()},
      {"eigen", fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
      {"fmt", fmt::format("{}.{}.{}", FMT_VERSION / 10000, FMT_VERSION / 100 % 100, FMT_VERSION % 100)},
      {"cli11", CLI11_VERSION},
      {"nlohmann_json", fmt::format("{}.{}.{}", NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                    NLOHMANN_JSON_VERSION_PATCH)},
      {"compiler", fmt::format("g++ {}", __VERSION__)},
  };
}

nlohmann::json run_metadata(const CLI::App& app, int argc, char** argv, double wall_time_s) {
  nlohmann::json options = nlohmann::json::object();
  for (const CLI::Option* opt : app.get_options()) {
    const std::string name = opt->get_single_name();
    if (name.empty() || name == "help") continue;
    if (opt->get_expected_min() == 0) {
      options[name] = opt->count() > 0;  // a flag
    } else {
      options[name] = opt->count() > 0 ? opt->as<std::string>() : opt->get_default_str();
    }
  }
  std::vector<std::string> command(argv, argv + argc);
  return {
      {"experiment", app.get_name()},
      {"options", options},
      {"command_line", command},
      {"git_revision", CONTACT_ODE_GIT_REVISION},
      {"libraries", library_versions()},
      {"wall_time_s", wall_time_s},
  };
}

int write_outputs(OutputSet& files, const CLI::App& app, int argc, char** argv,
                  std::chrono::steady_clock::time_point start, const fs::path& dir) {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  files.add("meta.json", run_metadata(app, argc, argv, wall).dump(2) + "\n");
  try {
    files.write(dir);
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}: {}\n", app.get_name(), e.what());
    return 1;
  }
  fmt::print("\nwrote {} files to {} ({:.2f} s)\n", files.files().size(), dir.string(), wall);
  return 0;
}

std::string check_output_dir(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    return fmt::format("--out: value '{}' exists and is not a directory; accepted: a directory path", dir.string());
  return {};
}

}  // namespace contact
