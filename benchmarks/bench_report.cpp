// bench_report — turns Google Benchmark JSON (bench_integrators, bench_chain) into Markdown:
// the machine, one table per benchmark family, and each target of the study checked from the
// measured numbers. Usage: bench_report RESULT.json [...] > benchmarks.md
#include "contact_ode/analysis/fit.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

using nlohmann::json;

namespace {

struct Row {
  std::string family, variant;
  long arg = 0;
  json data;
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

double num(const json& j, const char* key) { return j.contains(key) ? j[key].get<double>() : std::nan(""); }

std::string verdict(bool ok) { return ok ? "**met**" : "**not met**"; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: bench_report RESULT.json [...]\n";
    return 2;
  }
  std::vector<Row> rows;
  json context;
  for (int a = 1; a < argc; ++a) {
    std::ifstream in(argv[a]);
    if (!in) {
      std::cerr << "bench_report: cannot read " << argv[a] << "\n";
      return 2;
    }
    const json j = json::parse(in);
    context = j["context"];
    for (const auto& b : j["benchmarks"]) {
      std::string name = b["name"];
      // "Family/variant/arg/iterations:N": the last part is Google Benchmark's, not ours.
      if (const auto it = name.find("/iterations:"); it != std::string::npos) name.erase(it);
      const auto s1 = name.find('/'), s2 = name.rfind('/');
      Row r{name.substr(0, s1), "", 0, b};
      if (s1 != std::string::npos && s2 != s1) {
        r.variant = name.substr(s1 + 1, s2 - s1 - 1);
        r.arg = std::stol(name.substr(s2 + 1));
      } else if (s1 != std::string::npos) {
        r.variant = name.substr(s1 + 1);
      }
      rows.push_back(r);
    }
  }
  auto find = [&](const std::string& family, const std::string& variant, long arg) -> const json* {
    for (const auto& r : rows)
      if (r.family == family && r.variant == variant && r.arg == arg) return &r.data;
    return nullptr;
  };

  fmt::print("# Benchmarks\n\nMachine: {}, {} CPUs at {} MHz; library build: {}; run {}.\n\n", cpu_model(),
             context.value("num_cpus", 0), context.value("mhz_per_cpu", 0),
             context.value("library_build_type", "?"), context.value("date", "?"));

  // One table per family: variant, argument, time and every counter.
  std::map<std::string, std::vector<const Row*>> families;
  for (const auto& r : rows) families[r.family].push_back(&r);
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
                                         "error_message"};
  for (const auto& [family, list] : families) {
    std::vector<std::string> counters;
    for (const auto& [k, v] : list.front()->data.items())
      if (std::find(skip.begin(), skip.end(), k) == skip.end()) counters.push_back(k);
    fmt::print(
        "## {}\n\n| variant | arg | time | {} |\n|---|---|---|{}\n", family, fmt::join(counters, " | "),
        std::string(counters.size(), ' ') + [&] {
          std::string s;
          for (std::size_t i = 0; i < counters.size(); ++i) s += "---|";
          return s;
        }());
    for (const Row* r : list) {
      std::string cells;
      for (const auto& c : counters) cells += fmt::format(" {:.4g} |", num(r->data, c.c_str()));
      const std::string time =
          r->data.value("error_occurred", false)
              ? "failed: " + r->data.value("error_message", std::string())
              : fmt::format("{:.4g} {}", num(r->data, "real_time"), r->data.value("time_unit", ""));
      fmt::print("| {} | {} | {} |{}\n", r->variant, r->arg, time, cells);
    }
    fmt::print("\n");
  }

  fmt::print("## Targets\n\n");
  // 1. CVODE BDF right-hand sides against SciPy's BDF on the same ball drop.
  if (const json* lo = find("BallDrop", "cvode-bdf", 2), *hi = find("BallDrop", "cvode-bdf", 8); lo && hi) {
    const double a = num(*lo, "rhs_evals"), b = num(*hi, "rhs_evals");
    fmt::print(
        "- CVODE BDF penalty ball drop, rhs evaluations at k = 1e2 and 1e8: {:.0f} and {:.0f} "
        "(SciPy BDF, measured elsewhere: 549 and 888): {}\n",
        a, b, verdict(a < 549 && b < 888));
  }
  if (const json* k3 = find("BallDrop", "cvode-bdf", 3), *k10 = find("BallDrop", "cvode-bdf", 10);
      k3 && k10) {
    const double ratio = num(*k10, "steps_per_contact") / num(*k3, "steps_per_contact");
    fmt::print("- CVODE BDF steps per contact, k = 1e10 over k = 1e3: {:.2f} (target <= 1.5): {}\n", ratio,
               verdict(ratio <= 1.5));
  }
  // 2. Five apexes within 1e-8 of the exact penalty solution in at most 1500 rhs evaluations.
  std::vector<std::string> meets;
  for (const auto& r : rows)
    if (r.family == "ApexTarget" && num(r.data, "apex_error_m") <= 1e-8 && num(r.data, "rhs_evals") <= 1500)
      meets.push_back(fmt::format("{} at rtol 1e-{} ({:.0f} rhs, error {:.1e} m)", r.variant, r.arg,
                                  num(r.data, "rhs_evals"), num(r.data, "apex_error_m")));
  fmt::print("- k = 1e6, first five apexes within 1e-8 m with <= 1500 rhs evaluations: {}{}\n",
             meets.empty() ? "no integrator" : fmt::format("{}", fmt::join(meets, "; ")),
             meets.empty() ? " **not met**" : "");
  if (const json* e = find("ExactBounces", "", 0)) {
    const double rate = num(*e, "impacts_per_s");
    fmt::print("- event-driven closed form: {:.3g} impacts per second (target >= 1e6): {}\n", rate,
               verdict(rate >= 1e6));
  }
  // 3. The chain: linear growth in N for band and KLU, and the speed-up over dense at N = 1e3.
  for (const char* solver : {"band", "klu"}) {
    std::vector<double> n, t;
    for (long N : {1000L, 10000L, 100000L})
      if (const json* j = find("Chain", solver, N)) {
        n.push_back(static_cast<double>(N));
        t.push_back(num(*j, "time_per_sim_s"));
      }
    if (n.size() >= 2) {
      const double p = contact::fit_power_law(n, t).exponent;
      fmt::print(
          "- chain, {}: time per simulated second grows as N^{:.2f} from N = 1e3 to 1e5 (target: linear): "
          "{}\n",
          solver, p, verdict(p < 1.2));
    }
    if (const json* d = find("Chain", "dense", 1000), *s = find("Chain", solver, 1000); d && s) {
      const double speedup = num(*d, "time_per_sim_s") / num(*s, "time_per_sim_s");
      fmt::print("- chain, N = 1e3: {} is {:.0f}x faster than dense (target >= 100x): {}\n", solver, speedup,
                 verdict(speedup >= 100));
    }
  }
  return 0;
}
