// paper_numbers — the single numbers the paper quotes, read from the study's results and written
// as LaTeX macros (\newcommand{\Name}{value}), so that no result in the text is typed by hand.
// Each macro names the CSV, the row (column = value pairs; numbers compared numerically) and the
// column it comes from. A missing file, row or column is an error: the paper must not build on a
// partial study.
// Usage: paper_numbers --results DIR --out FILE.  Exit codes: 0, 1 a number is missing, 2 bad input.
#include "cli.hpp"
#include "contact_ode/analysis/table.hpp"
#include "output.hpp"
#include "process.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

using namespace contact;
namespace fs = std::filesystem;

namespace {

using Row = std::map<std::string, std::string>;

std::vector<Row> read_csv(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", path.string()));
  std::string line;
  std::getline(in, line);
  const auto header = split_csv_line(line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    const auto cells = split_csv_line(line);
    Row row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

bool cell_matches(const std::string& cell, const std::string& wanted) {
  if (cell == wanted) return true;
  try {  // numbers: "0.001" matches "1e-3"
    std::size_t a = 0, b = 0;
    const double x = std::stod(cell, &a), y = std::stod(wanted, &b);
    return a == cell.size() && b == wanted.size() && std::abs(x - y) <= 1e-12 * std::abs(y);
  } catch (const std::exception&) {
    return false;
  }
}

struct Number {
  std::string macro, file;
  std::vector<std::pair<std::string, std::string>> where;
  std::string column, format;
  bool last = false;  // the last matching row (the finest step of a sweep) instead of the first
};

std::string lookup(const fs::path& results, const Number& n) {
  const Row* found = nullptr;
  const auto rows = read_csv(results / n.file);
  for (const auto& row : rows) {
    bool all = true;
    for (const auto& [col, val] : n.where) all = all && row.count(col) && cell_matches(row.at(col), val);
    if (all) found = &row;
    if (all && !n.last) break;
  }
  if (!found) {
    std::string where;
    for (const auto& [col, val] : n.where) where += fmt::format(" {}={}", col, val);
    throw std::runtime_error(fmt::format("{}: no row with{}", n.file, where));
  }
  if (!found->count(n.column)) throw std::runtime_error(fmt::format("{}: no column '{}'", n.file, n.column));
  const std::string& cell = found->at(n.column);
  return n.format.empty() ? cell : fmt::format(fmt::runtime(n.format), std::stod(cell));
}

// Numbers in scientific notation read better as a x 10^b in the text.
std::string latex_number(const std::string& s) {
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  const int exponent = std::stoi(s.substr(e + 1));
  return fmt::format("\\ensuremath{{{}\\times10^{{{}}}}}", s.substr(0, e), exponent);
}

const std::vector<Number>& numbers() {
  static const std::vector<Number> list = {
      {"PenExpHooke", "k_sweep/exponents.csv", {{"law", "hooke"}}, "penetration_exponent", "{:.3f}"},
      {"DurExpHooke", "k_sweep/exponents.csv", {{"law", "hooke"}}, "duration_exponent", "{:.3f}"},
      {"DurExpClamped",
       "k_sweep/exponents.csv",
       {{"law", "kelvin-voigt-clamped"}},
       "duration_exponent",
       "{:.3f}"},
      {"ConvKTimeExp",
       "convergence_k/rates.csv",
       {{"quantity", "impact_time_error"}},
       "fitted_exponent",
       "{:.3f}"},
      {"ConvKApexExp",
       "convergence_k/rates.csv",
       {{"quantity", "apex_height_error"}},
       "fitted_exponent",
       "{:.3f}"},
      {"ZenoTime", "zeno/zeno.csv", {{"method", "event-exact"}}, "zeno_time_s", "{:.3f}"},
      {"ZenoExactContacts", "zeno/zeno.csv", {{"method", "event-exact"}}, "contacts", ""},
      {"ZenoExactRest", "zeno/zeno.csv", {{"method", "event-exact"}}, "rest_time_s", "{:.3f}"},
      {"ZenoGameContacts", "zeno/zeno.csv", {{"method", "game-symplectic"}}, "contacts", ""},
      {"ZenoPenaltyLowest", "zeno/zeno.csv", {{"method", "penalty"}}, "min_height_m", "{:.4f}"},
      {"DriftEulerRate",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "game-euler"}, {"value", "1e-3"}},
       "drift_rate_per_s",
       "{:.2e}"},
      {"DriftEulerFinal",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "game-euler"}, {"value", "1e-3"}},
       "final_energy_error_rel",
       "{:.2f}"},
      {"DriftEulerFineFinal",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "game-euler"}, {"value", "1e-4"}},
       "final_energy_error_rel",
       "{:.3f}"},
      {"DriftEulerSpringFinal",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "game-euler-spring"}, {"value", "1e-3"}},
       "final_energy_error_rel",
       "{:.0f}"},
      {"DriftSymplecticMax",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "game-symplectic"}, {"value", "1e-3"}},
       "max_abs_energy_error_rel",
       "{:.1e}"},
      {"DriftPenaltyFinal",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "penalty"}, {"value", "1e-8"}},
       "final_energy_error_rel",
       "{:.1e}"},
      {"DriftEventOdeFinal",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "event-ode"}, {"value", "1e-8"}},
       "final_energy_error_rel",
       "{:.1e}"},
      {"DriftExactMax",
       "energy_drift/drift.csv",
       {{"system", "ball"}, {"method", "event-exact"}},
       "max_abs_energy_error_rel",
       "{:.1e}"},
      {"DriftProjectionRubber",
       "energy_drift/drift.csv",
       {{"system", "rubber-steel"}, {"method", "game-symplectic-projection"}, {"value", "1e-4"}},
       "final_energy_error_rel",
       "{:.1f}"},
      {"OrderRkFourUnlocated",
       "convergence_dt/orders.csv",
       {{"integrator", "rk4"}},
       "fixed_order_unlocated",
       "{:.2f}"},
      {"OrderRkFourLocated",
       "convergence_dt/orders.csv",
       {{"integrator", "rk4"}},
       "fixed_order_located",
       "{:.2f}"},
      {"OrderRkfUnlocated",
       "convergence_dt/orders.csv",
       {{"integrator", "gsl-rkf45"}},
       "fixed_order_unlocated",
       "{:.2f}"},
      {"OrderRkfLocated",
       "convergence_dt/orders.csv",
       {{"integrator", "gsl-rkf45"}},
       "fixed_order_located",
       "{:.2f}"},
      {"BdfRhsUnlocated",
       "convergence_dt/orders.csv",
       {{"integrator", "cvode-bdf"}},
       "rhs_evals_tightest_unlocated",
       ""},
      {"BdfRhsLocated",
       "convergence_dt/orders.csv",
       {{"integrator", "cvode-bdf"}},
       "rhs_evals_tightest_located",
       ""},
      {"CradleLinearLast",
       "newton_cradle/velocities.csv",
       {{"method", "penalty-linear"}, {"spacing_m", "0"}},
       "v4_mps",
       "{:.3f}"},
      {"CradleLinearStriker",
       "newton_cradle/velocities.csv",
       {{"method", "penalty-linear"}, {"spacing_m", "0"}},
       "v0_mps",
       "{:.3f}"},
      {"CradleLinearShare",
       "newton_cradle/velocities.csv",
       {{"method", "penalty-linear"}, {"spacing_m", "0"}},
       "last_ball_energy_share",
       "{:.3f}"},
      {"CradleHertzLast",
       "newton_cradle/velocities.csv",
       {{"method", "penalty-hertz"}, {"spacing_m", "0"}},
       "v4_mps",
       "{:.3f}"},
      {"CradleHertzShare",
       "newton_cradle/velocities.csv",
       {{"method", "penalty-hertz"}, {"spacing_m", "0"}},
       "last_ball_energy_share",
       "{:.3f}"},
      {"CradleGameContacts",
       "newton_cradle/velocities.csv",
       {{"method", "game"}, {"spacing_m", "0"}},
       "contacts",
       ""},
      {"WedgePenaltySpeed",
       "rigid_scenes/observables.csv",
       {{"scene", "wedge"}, {"method", "penalty"}, {"quantity", "upper_speed_mps"}},
       "value",
       "{:.3f}"},
      {"WedgeEventUpper",
       "rigid_scenes/observables.csv",
       {{"scene", "wedge"}, {"method", "event-ode"}, {"quantity", "upper_speed_mps"}},
       "value",
       "{:.3f}"},
      {"WedgeEventLower",
       "rigid_scenes/observables.csv",
       {{"scene", "wedge"}, {"method", "event-ode"}, {"quantity", "lower_speed_mps"}},
       "value",
       "{:.3f}"},
      {"WedgeProjectionL",
       "rigid_impacts/conservation.csv",
       {{"scene", "wedge"}, {"method", "game-symplectic-projection"}, {"value", "1e-4"}},
       "angular_momentum_error_rel",
       "{:.1e}"},
      {"SpinPenaltyL",
       "rigid_impacts/conservation.csv",
       {{"scene", "spinning-box"}, {"method", "penalty"}, {"value", "1e-6"}},
       "angular_momentum_error_rel",
       "{:.1e}"},
      {"WpBdfRhs",
       "work_precision/work_precision.csv",
       {{"problem", "ball"}, {"paradigm", "penalty"}, {"integrator", "cvode-bdf"}, {"value", "1e-6"}},
       "rhs_evals",
       ""},
      {"WpBdfError",
       "work_precision/work_precision.csv",
       {{"problem", "ball"}, {"paradigm", "penalty"}, {"integrator", "cvode-bdf"}, {"value", "1e-6"}},
       "error",
       "{:.1e}"},
      {"WpEventRhs",
       "work_precision/work_precision.csv",
       {{"problem", "ball"}, {"paradigm", "event"}, {"integrator", "cvode-bdf"}, {"value", "1e-6"}},
       "rhs_evals",
       ""},
      {"WpEventError",
       "work_precision/work_precision.csv",
       {{"problem", "ball"}, {"paradigm", "event"}, {"integrator", "cvode-bdf"}, {"value", "1e-6"}},
       "error",
       "{:.1e}"},
      {"WpGameError",
       "work_precision/work_precision.csv",
       {{"problem", "ball"}, {"paradigm", "game"}},
       "error",
       "{:.1e}",
       true},
      {"WpGameDt",
       "work_precision/work_precision.csv",
       {{"problem", "ball"}, {"paradigm", "game"}},
       "value",
       "{:.2e}",
       true},
      {"AdvisorK", "contact_advisor/advice.csv", {{"quantity", "k_lin"}}, "value", "{:.3g}"},
      {"AdvisorZeta", "contact_advisor/advice.csv", {{"quantity", "zeta"}}, "value", "{:.3f}"},
      {"AdvisorEulerDt", "contact_advisor/advice.csv", {{"quantity", "euler_max_dt"}}, "value", "{:.2e}"},
      {"AdvisorSymplecticDt",
       "contact_advisor/advice.csv",
       {{"quantity", "symplectic_max_dt"}},
       "value",
       "{:.2e}"},
  };
  return list;
}

// The first line a command prints (tool versions, the machine), escaped for LaTeX text.
std::string first_line(const std::string& command) {
  std::string line;
  if (FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r")) {
    char buffer[512];
    if (std::fgets(buffer, sizeof buffer, pipe)) line = buffer;
    ::pclose(pipe);
  }
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  if (line.empty()) return "not found";
  std::string tex;
  for (char c : line) {
    if (std::string("&%$#_{}").find(c) != std::string::npos) tex += '\\';
    if (c == '~' || c == '^' || c == '\\') {
      tex += "{}";
      continue;
    }
    tex += c;
  }
  return tex;
}

}  // namespace

int program(int argc, char** argv) {
  std::string results = "results", out = "results/paper/numbers.tex";
  cli::Options app("paper_numbers",
                   "Writes the numbers the paper quotes, from the study's results, as LaTeX macros.");
  app.add("--results", results, "the study's results folder", cli::existing_folder());
  app.add("--out", out, "the macro file to write");
  if (const int code = app.parse(argc, argv); code >= 0) return code;
  std::string tex = "% Generated by paper_numbers from the study's results: do not edit.\n";
  try {
    for (const auto& n : numbers())
      tex += fmt::format("\\newcommand{{\\{}}}{{{}}}\n", n.macro, latex_number(lookup(results, n)));
    // The run: how long the study took, where, with which libraries.
    std::ifstream study(fs::path(results) / "study.json"), meta(fs::path(results) / "k_sweep" / "meta.json");
    if (!study || !meta)
      throw std::runtime_error("study.json or k_sweep/meta.json missing: run the study first");
    const auto s = nlohmann::json::parse(study), m = nlohmann::json::parse(meta);
    tex += fmt::format("\\newcommand{{\\StudyWallTime}}{{{:.0f}}}\n", s.at("wall_time_s").get<double>());
    tex += fmt::format("\\newcommand{{\\StudyCores}}{{{}}}\n", s.at("cores").get<unsigned>());
    tex += fmt::format("\\newcommand{{\\StudyExperiments}}{{{}}}\n", s.at("experiments").size());
    tex += fmt::format("\\newcommand{{\\GitRevision}}{{\\texttt{{{}}}}}\n",
                       m.at("git_revision").get<std::string>());
    const std::pair<const char*, const char*> tools[] = {
        {"ToolCmake", "cmake --version"},
        {"ToolGnuplot", "gnuplot --version"},
        {"ToolPdftex", "pdflatex --version"},
        {"ToolLatexmk", "latexmk --version | grep -m1 Version"},
        {"MachineCpu", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'"},
        {"MachineKernel", "uname -srm"},
    };
    for (const auto& [macro, command] : tools)
      tex += fmt::format("\\newcommand{{\\{}}}{{{}}}\n", macro, first_line(command));
    for (const auto& [lib, version] : m.at("libraries").items()) {
      std::string name = "Version";
      bool upper = true;
      for (char c : lib) {
        if (c == '_') {
          upper = true;
          continue;
        }
        if (std::isdigit(static_cast<unsigned char>(c))) continue;  // macro names are letters only
        name += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
        upper = false;
      }
      tex += fmt::format("\\newcommand{{\\{}}}{{{}}}\n", name, version.get<std::string>());
    }
  } catch (const std::exception& ex) {
    std::cerr << "paper_numbers: " << ex.what() << "\n";
    return cli::kExitFailure;
  }
  OutputSet files;
  files.add(fs::path(out).filename().string(), tex);
  try {
    files.write(fs::path(out).parent_path().empty() ? fs::path(".") : fs::path(out).parent_path());
  } catch (const std::exception& ex) {
    std::cerr << "paper_numbers: " << ex.what() << "\n";
    return cli::kExitFailure;
  }
  return 0;
}

int main(int argc, char** argv) { return contact::guarded_main("paper_numbers", argc, argv, program); }
