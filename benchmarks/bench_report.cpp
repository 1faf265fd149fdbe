// bench_report — turns the benchmark run (Google Benchmark JSON of bench_integrators,
// bench_chain and bench_column, the SciPy peer's JSON lines, the study's timing) into Markdown: the machine,
// its load and the project's build type, one table per benchmark family (CPU time: median and range of the
// repetitions), and every target of the study with its verdict computed from the numbers. Usage: bench_report
// --build-type T --load L [--scipy P1.jsonl]... [--timing TIMING.json] RESULT.json...
// A case in several RESULT files (run_benchmarks.sh times P1 and the exact bounces in rounds, each
// round's P1 beside SciPy's, --scipy once a round in the same order) is pooled: the median of the
// runs' medians, the range of all their repetitions; and each P1 ratio to SciPy is the median of
// the rounds' ratios, each taken from measurements a few seconds apart. A machine whose speed drifts
// (this VM's by a third within minutes) then moves both sides of a ratio alike.
#include "contact_ode/analysis/fit.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

using nlohmann::json;

namespace {

// One benchmark case: its median row (or its only row) and the min and max rows when repeated,
// pooled over the runs that timed it (runs: each run's rows, in the order of the files).
struct Case {
  std::string family, variant;
  long arg = 0;
  json median, min, max;
  std::vector<json> runs, mins, maxes;
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

double num(const json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

// The pooled rows: the run whose median is the median of the runs' (the lower middle of an even
// count), the fastest minimum and the slowest maximum.
void pool(Case& c) {
  auto by_cpu = [](const json& a, const json& b) { return num(a, "cpu_time") < num(b, "cpu_time"); };
  std::vector<json> sorted = c.runs;
  std::stable_sort(sorted.begin(), sorted.end(), by_cpu);
  if (!sorted.empty()) c.median = sorted[(sorted.size() - 1) / 2];
  if (!c.mins.empty()) c.min = *std::min_element(c.mins.begin(), c.mins.end(), by_cpu);
  if (!c.maxes.empty()) c.max = *std::max_element(c.maxes.begin(), c.maxes.end(), by_cpu);
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[(v.size() - 1) / 2];
}

std::string verdict(bool ok) { return ok ? "**met**" : "**not met**"; }

// "Family/variant/arg/iterations:N/repeats:M_median" -> family, variant, arg, statistic.
void parse_name(std::string name, Case& c, std::string& stat) {
  if (const auto u = name.rfind('_'); u != std::string::npos && name.find("repeats:") < u) {
    stat = name.substr(u + 1);
    name.erase(u);
  }
  for (const char* tail : {"/repeats:", "/iterations:"})
    if (const auto it = name.find(tail); it != std::string::npos) name.erase(it);
  const auto s1 = name.find('/'), s2 = name.rfind('/');
  c.family = name.substr(0, s1);
  if (s1 != std::string::npos && s2 != s1) {
    c.variant = name.substr(s1 + 1, s2 - s1 - 1);
    c.arg = std::stol(name.substr(s2 + 1));
  } else if (s1 != std::string::npos) {
    c.variant = name.substr(s1 + 1);
  }
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A parse error names the file (and line) it is in.
json parse_json(const std::string& text, const std::string& where) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& ex) {
    throw std::runtime_error(where + ": " + ex.what());
  }
}

constexpr const char* kUsage =
    "usage: bench_report --build-type T --load L [--scipy P1.jsonl]... [--timing TIMING.json] RESULT.json...";

}  // namespace

int main(int argc, char** argv) try {
  std::string build_type = "?", load = "?", timing_path;
  std::vector<std::string> inputs, scipy_paths;  // --scipy: once a round of P1 (above)
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&]() -> std::string {
      if (a + 1 >= argc) throw std::invalid_argument(arg + ": needs a value");
      return argv[++a];
    };
    if (arg == "--build-type")
      build_type = value();
    else if (arg == "--load")
      load = value();
    else if (arg == "--scipy")
      scipy_paths.push_back(value());
    else if (arg == "--timing")
      timing_path = value();
    else if (arg == "-h" || arg == "--help")
      return std::cout << kUsage << "\n", 0;
    else if (arg.rfind("-", 0) == 0)
      throw std::invalid_argument(fmt::format("unknown option '{}'; {}", arg, kUsage));
    else
      inputs.push_back(arg);
  }
  if (inputs.empty()) throw std::invalid_argument(kUsage);
  std::vector<Case> cases;
  json context;
  for (const auto& path : inputs) {
    // Google Benchmark writes NaN (a counter's 0/0, e.g. its "cv" of a constant) unquoted, which
    // is not JSON: read as null.
    std::string text = read_text(path);
    for (const char* token : {": NaN", ": -NaN", ": Infinity", ": -Infinity"})
      for (auto at = text.find(token); at != std::string::npos; at = text.find(token, at))
        text.replace(at, std::strlen(token), ": null");
    const json j = parse_json(text, path);
    context = j["context"];
    for (const auto& b : j["benchmarks"]) {
      Case c;
      std::string stat;
      parse_name(b["name"], c, stat);
      if (!stat.empty() && stat != "median" && stat != "min" && stat != "max") continue;
      auto it = std::find_if(cases.begin(), cases.end(), [&](const Case& x) {
        return x.family == c.family && x.variant == c.variant && x.arg == c.arg;
      });
      if (it == cases.end()) it = cases.insert(cases.end(), c);
      (stat == "min" ? it->mins : stat == "max" ? it->maxes : it->runs).push_back(b);
    }
  }
  for (auto& c : cases) pool(c);
  auto find = [&](const std::string& family, const std::string& variant, long arg) -> const Case* {
    for (const auto& c : cases)
      if (c.family == family && c.variant == variant && c.arg == arg) return &c;
    return nullptr;
  };

  fmt::print(
      "# Benchmarks\n\nMachine: {}, {} CPUs at {} MHz; load average before the run: {}; the project built as "
      "{} (Google Benchmark's own library: {}); run {}. Times are CPU time per iteration: the median of "
      "the repetitions, with their range; a case timed in several runs (P1 and the exact bounces, in "
      "rounds that alternate with SciPy's P1) shows the median of the runs' medians and the range of "
      "all their repetitions.\n\n",
      cpu_model(), context.value("num_cpus", 0), context.value("mhz_per_cpu", 0), load, build_type,
      context.value("library_build_type", "?"), context.value("date", "?"));

  // One table per family: variant, argument, CPU time and every counter.
  std::map<std::string, std::vector<const Case*>> families;
  for (const auto& c : cases) families[c.family].push_back(&c);
  const std::vector<std::string> skip = {"name",
                                         "family_index",
                                         "per_family_instance_index",
                                         "run_name",
                                         "run_type",
                                         "repetitions",
                                         "repetition_index",
                                         "threads",
                                         "iterations",
                                         "real_time",
                                         "cpu_time",
                                         "time_unit",
                                         "error_occurred",
                                         "error_message",
                                         "aggregate_name",
                                         "aggregate_unit"};
  for (const auto& [family, list] : families) {
    std::vector<std::string> counters;
    for (const auto& [k, v] : list.front()->median.items())
      if (std::find(skip.begin(), skip.end(), k) == skip.end()) counters.push_back(k);
    std::string rule;
    for (std::size_t i = 0; i < counters.size() + 3; ++i) rule += "---|";
    fmt::print("## {}\n\n| variant | arg | CPU time | {} |\n|{}\n", family, fmt::join(counters, " | "), rule);
    for (const Case* c : list) {
      std::string cells;
      for (const auto& k : counters) cells += fmt::format(" {:.4g} |", num(c->median, k.c_str()));
      const std::string unit = c->median.value("time_unit", "");
      std::string time = c->median.value("error_occurred", false)
                             ? "failed: " + c->median.value("error_message", std::string())
                             : fmt::format("{:.4g} {}", num(c->median, "cpu_time"), unit);
      if (c->min.is_object() && c->max.is_object())
        time += fmt::format(" [{:.4g}, {:.4g}]", num(c->min, "cpu_time"), num(c->max, "cpu_time"));
      fmt::print("| {} | {} | {} |{}\n", c->variant, c->arg, time, cells);
    }
    fmt::print("\n");
  }

  fmt::print("## Targets\n\n");
  // P1 against SciPy, measured in the same run: CPU per solve and the first five apexes'
  // largest error against the tight reference (P1Reference).
  const Case* ref = find("P1Reference", "", 0);
  auto apex_error = [&](auto apex) {
    double worst = 0;
    for (int n = 1; n <= 5; ++n)
      worst = std::max(worst, std::abs(apex(n) - num(ref->median, fmt::format("apex_{}", n).c_str())));
    return worst;
  };
  if (ref && !scipy_paths.empty()) {
    // rounds[r][method]: SciPy's P1 in round r (one --scipy file each), set up as a numerical
    // analyst would (restarted at the switches, the analytic Jacobian: the target's peers); at its
    // defaults (one solve across the switches) under "defaults <method>".
    std::vector<std::map<std::string, json>> rounds;
    for (const auto& path : scipy_paths) {
      auto& round = rounds.emplace_back();
      std::istringstream lines(read_text(path));
      int number = 0;
      for (std::string line; std::getline(lines, line);)
        if (++number, !line.empty() && line[0] == '{') {
          const json p = parse_json(line, fmt::format("{} line {}", path, number));
          const std::string setup = p.value("setup", "tuned");
          round[(setup == "tuned" ? "" : setup + " ") + p.value("method", "")] = p;
        }
    }
    // CPU ratio of SciPy's `key` to P1 case c (the median over the rounds) and SciPy's apex error.
    const auto ratio_to_scipy = [&](const Case& c, const std::string& key) {
      std::vector<double> ratios;
      for (std::size_t r = 0; r < rounds.size(); ++r)
        ratios.push_back(rounds[r][key]["cpu_s"].get<double>() / (num(c.runs[r], "cpu_time") * 1e-3));
      const auto apexes = rounds.front()[key]["apexes"].get<std::vector<double>>();
      return std::pair{median_of(ratios),
                       apexes.size() < 5 ? std::nan("") : apex_error([&](int n) { return apexes[n - 1]; })};
    };
    // The target names four peers: a method missing from a SciPy round (not installed, failed) is a
    // comparison not made, never one won.
    std::vector<std::string> methods, unmeasured;
    for (const char* method : {"BDF", "Radau", "LSODA", "RK45"})
      (std::all_of(rounds.begin(), rounds.end(), [&](const auto& round) { return round.contains(method); })
           ? methods
           : unmeasured)
          .push_back(method);
    const std::string absent =
        unmeasured.empty() ? "" : fmt::format("; SciPy's {} not measured", fmt::join(unmeasured, ", "));
    const std::string pooled =
        rounds.size() > 1 ? fmt::format(" (medians of {} rounds, each beside SciPy's)", rounds.size()) : "";
    std::vector<std::string> who_meets, per_integrator;
    std::string defaults_line;
    for (const auto& c : cases) {
      if (c.family != "P1") continue;
      if (c.runs.size() != rounds.size())
        throw std::invalid_argument(
            fmt::format("P1/{} was timed in {} runs and SciPy in {}: give --scipy once for each P1 run, in "
                        "the same order",
                        c.variant, c.runs.size(), rounds.size()));
      const double ours = num(c.median, "cpu_time") * 1e-3;  // [s]; the benchmark reports ms
      const double err = apex_error([&](int n) { return num(c.median, fmt::format("apex_{}", n).c_str()); });
      bool all = unmeasured.empty();
      std::vector<std::string> parts, met, missed;
      for (const auto& method : methods) {
        const auto [ratio, their_err] = ratio_to_scipy(c, method);
        const bool ok = ratio >= 50 && err <= their_err;
        all = all && ok;
        const std::string against =
            fmt::format("{} {:.0f}x (apex error {:.1e} m against {:.1e} m)", method, ratio, err, their_err);
        parts.push_back(against);
        (ok ? met : missed).push_back(ok ? fmt::format("{} {:.0f}x", method, ratio) : against);
      }
      per_integrator.push_back(fmt::format(
          "  - {} ({:.3g} ms, apex error {:.1e} m): meets it against {}{}{}", c.variant, ours * 1e3, err,
          met.empty() ? std::string("none") : fmt::format("{}", fmt::join(met, ", ")),
          missed.empty() ? "" : fmt::format("; not {}", fmt::join(missed, ", ")), absent));
      if (c.variant == "cvode-bdf") {
        fmt::print(
            "- P1 (rtol 1e-6), CVODE BDF at {:.3g} ms per solve{}: {}{}; target >= 50x less CPU than each, "
            "apex error no worse: {}\n",
            ours * 1e3, pooled, fmt::join(parts, "; "), absent, verdict(all));
        // The peer as users get it, beside the peer tuned: no target, the fair comparison's other half.
        std::vector<std::string> at_defaults, missing;
        for (const char* method : {"BDF", "Radau", "LSODA", "RK45"})
          if (std::all_of(rounds.begin(), rounds.end(), [&](const auto& round) {
                return round.contains(fmt::format("defaults {}", method));
              })) {
            const auto [ratio, their_err] = ratio_to_scipy(c, fmt::format("defaults {}", method));
            at_defaults.push_back(fmt::format("{} {:.0f}x (apex error {:.1e} m against {:.1e} m)", method,
                                              ratio, err, their_err));
          } else {
            missing.push_back(method);
          }
        if (!at_defaults.empty())
          defaults_line = fmt::format(
              "- P1 against SciPy at its defaults (one solve_ivp across the switches, the Jacobian by "
              "differences; not a target), CVODE BDF: {}{}\n",
              fmt::join(at_defaults, "; "),
              missing.empty() ? "" : fmt::format("; SciPy's {} not measured", fmt::join(missing, ", ")));
      }
      if (all) who_meets.push_back(fmt::format("{} ({:.3g} ms)", c.variant, ours * 1e3));
    }
    fmt::print("- P1: integrators that meet it against all four SciPy methods: {}\n",
               who_meets.empty() ? std::string("none") : fmt::format("{}", fmt::join(who_meets, ", ")));
    fmt::print("{}\n{}", fmt::join(per_integrator, "\n"), defaults_line);
  }
  // Five apexes of the undamped ball at k = 1e6 within 1e-8 m in at most 500 right-hand sides.
  // The default (cvode-bdf) is judged at the loosest tolerance where it reaches 1e-8.
  std::vector<std::string> meets;
  double bdf_rhs = std::nan("");
  long bdf_rtol = 0;
  for (const auto& c : cases) {
    if (c.family != "ApexTarget" || !(num(c.median, "apex_error_m") <= 1e-8)) continue;
    const double rhs = num(c.median, "rhs_evals");
    if (c.variant == "cvode-bdf" && std::isnan(bdf_rhs)) {
      bdf_rhs = rhs;
      bdf_rtol = c.arg;
    }
    if (rhs <= 500)
      meets.push_back(c.arg == 0 ? fmt::format("{} ({:.0f} rhs, no tolerance)", c.variant, rhs)
                                 : fmt::format("{} at rtol 1e-{} ({:.0f} rhs)", c.variant, c.arg, rhs));
  }
  const std::string bdf =
      std::isnan(bdf_rhs)
          ? std::string("cvode-bdf reaches 1e-8 at no tolerance tried")
          : fmt::format("cvode-bdf (the default) first reaches it at rtol 1e-{} with {:.0f} rhs", bdf_rtol,
                        bdf_rhs);
  fmt::print(
      "- k = 1e6, five apexes within 1e-8 m in <= 500 rhs evaluations by the default method: {}; within "
      "500 rhs: {}: {}\n",
      bdf, meets.empty() ? std::string("none") : fmt::format("{}", fmt::join(meets, "; ")),
      verdict(bdf_rhs <= 500));
  if (const Case* e = find("ExactBounces", "", 0)) {
    const double rate = num(e->median, "impacts_per_s");
    const std::string runs = e->runs.size() > 1 ? fmt::format(" of {} runs' medians", e->runs.size()) : "";
    fmt::print("- event-driven closed form: {:.3g} impacts per second (median{}; target >= 1e7): {}\n", rate,
               runs, verdict(rate >= 1e7));
  }
  // The chain: every N ran, band and KLU linear in N to 1e5, and >= 100x dense at N = 1e3.
  long failed = 0, ran = 0;
  for (const auto& c : cases)
    if (c.family == "Chain") (c.median.value("error_occurred", false) ? failed : ran) += 1;
  fmt::print("- chain: {} cases ran, {} failed (target: every N of every solver): {}\n", ran, failed,
             verdict(failed == 0 && ran > 0));
  for (const char* solver : {"band", "klu"}) {
    // Linear to 1e5 is judged on all three sizes: a size that failed (no time) fails the target.
    std::vector<double> n, t;
    for (long N : {1000L, 10000L, 100000L})
      if (const Case* c = find("Chain", solver, N); c && std::isfinite(num(c->median, "time_per_sim_s"))) {
        n.push_back(static_cast<double>(N));
        t.push_back(num(c->median, "time_per_sim_s"));
      }
    if (n.size() == 3) {
      const double p = contact::fit_power_law(n, t).exponent;
      fmt::print(
          "- chain, {}: CPU per simulated second grows as N^{:.2f} from N = 1e3 to 1e5 (target: linear, "
          "exponent < 1.2): {}\n",
          solver, p, verdict(p < 1.2));
    } else {
      fmt::print("- chain, {}: timed at {} of N = 1e3, 1e4, 1e5 (target: linear to 1e5): {}\n", solver,
                 n.size(), verdict(false));
    }
    if (const Case* d = find("Chain", "dense", 1000), *s = find("Chain", solver, 1000); d && s) {
      const double speedup = num(d->median, "time_per_sim_s") / num(s->median, "time_per_sim_s");
      fmt::print("- chain, N = 1e3: {} is {:.0f}x faster than dense (target >= 100x): {}\n", solver, speedup,
                 verdict(speedup >= 100));
    }
  }
  // Not an issue target: each fixed-step method's cost per step on the column, from N = 100 to 1e3.
  std::vector<std::string> column;
  for (const auto& c : cases)
    if (c.family == "Column" && c.arg == 1000)
      if (const Case* small = find("Column", c.variant, 100);
          small && !c.median.value("error_occurred", false))
        column.push_back(fmt::format(
            "{} N^{:.2f}", c.variant,
            contact::fit_power_law({100, 1000}, {num(small->median, "cpu_time"), num(c.median, "cpu_time")})
                .exponent));
  if (!column.empty())
    fmt::print("- column (not a target; linear expected): CPU per step grows from N = 100 to 1e3 as {}\n",
               fmt::join(column, ", "));
  if (!timing_path.empty()) {
    const json t = parse_json(read_text(timing_path), timing_path);
    const double total = t.value("study_s", NAN) + t.value("paper_s", NAN);
    // Several runs (run_benchmarks.sh times three): the median run's, with the totals' range.
    std::string runs;
    if (t.contains("totals_s") && t["totals_s"].size() > 1) {
      const auto totals = t["totals_s"].get<std::vector<double>>();
      const auto [lo, hi] = std::minmax_element(totals.begin(), totals.end());
      runs = fmt::format(", the median of {} runs ({:.1f} to {:.1f} s)", totals.size(), *lo, *hi);
    }
    fmt::print(
        "- the study ({:.1f} s) and the paper ({:.1f} s) together {:.1f} s of wall time on {} cores{} "
        "(target <= 10 s): {}\n",
        t.value("study_s", NAN), t.value("paper_s", NAN), total, context.value("num_cpus", 0), runs,
        verdict(total <= 10));
    if (t.contains("fresh_build_s"))
      fmt::print("- a fresh Release build: {:.0f} s (target <= 240 s): {}\n",
                 t["fresh_build_s"].get<double>(), verdict(t["fresh_build_s"].get<double>() <= 240));
    else
      fmt::print(
          "- a fresh Release build: not measured in this run (scripts/run_benchmarks.sh --fresh-build)\n");
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "bench_report: " << e.what() << "\n";
  return 2;
}
