#include "scipy_peer.hpp"

#include "output.hpp"
#include "process.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace contact {

std::vector<ScipyRun> run_scipy_peer(const ScipyDrop& d) {
  const ScratchDir scratch{make_scratch_dir("contact_scipy")};
  const std::filesystem::path log = scratch.path / "log";
  std::vector<std::string> argv = {CONTACT_ODE_PYTHON_EXE,
                                   CONTACT_ODE_SCIPY_PEER,
                                   "--methods",
                                   fmt::format("{}", fmt::join(d.methods, ",")),
                                   "--rtols",
                                   fmt::format("{}", fmt::join(d.rtols, ","))};
  for (const auto& [flag, value] : {std::pair{"--atol-ratio", d.atol_ratio},
                                    {"--m", d.m},
                                    {"--g", d.g},
                                    {"--k", d.k},
                                    {"--c", d.c},
                                    {"--h0", d.h0},
                                    {"--v0", d.v0},
                                    {"--t-end", d.t_end},
                                    {"--repeats", static_cast<double>(d.repeats)},
                                    {"--budget", d.budget_s}})
    argv.insert(argv.end(), {flag, fmt::format("{}", value)});
  if (!std::filesystem::exists(CONTACT_ODE_PYTHON_EXE))
    throw ScipyPeerMissing(fmt::format("{} (python3)", CONTACT_ODE_PYTHON_EXE));
  const int code = run_process(argv, {}, log);
  const std::string out = read_text(log);
  if (code == 3) throw ScipyPeerMissing("SciPy for " CONTACT_ODE_PYTHON_EXE " (python3-scipy)");
  if (code != 0) throw std::runtime_error(fmt::format("the SciPy peer failed (exit {}):\n{}", code, out));
  std::vector<ScipyRun> runs;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] != '{') continue;
    const auto j = nlohmann::json::parse(line);
    runs.push_back({j.at("method"), j.at("rtol"), j.at("atol"), j.at("y"), j.at("v"),
                    j.at("apexes").get<std::vector<double>>(), j.at("nfev"), j.at("njev"), j.at("cpu_s"),
                    j.at("cpu_min_s"), j.at("cpu_max_s"), j.at("repeats")});
  }
  if (runs.size() != d.methods.size() * d.rtols.size())
    throw std::runtime_error(fmt::format("the SciPy peer printed {} results, expected {}:\n{}", runs.size(),
                                         d.methods.size() * d.rtols.size(), out));
  return runs;
}

std::vector<ScoredScipyRun> scipy_on_ball(const Problem& ball, double k, const std::vector<double>& rtols,
                                          int repeats, double budget_s) {
  std::vector<ScoredScipyRun> scored;
  for (const ScipyRun& p : run_scipy_peer(
           {.k = k, .t_end = ball.t_end, .rtols = rtols, .repeats = repeats, .budget_s = budget_s})) {
    RunResult r;  // the peer's final state, as a run
    r.samples.push_back({.t = ball.t_end, .y = Vector{{p.y, p.v}}, .energy = 0, .dissipated = 0});
    scored.push_back({p, ball.error(r, false), ball.error(r, true)});
  }
  return scored;
}

}  // namespace contact
