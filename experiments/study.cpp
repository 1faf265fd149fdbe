// study — runs every experiment of the study (experiments/study.json) into one results folder,
// checks that each left every output it declares (CSV columns included), and writes index.md
// (a link and a sentence per table and figure) and study.json (what ran, how long it took); after
// --only, both keep the other experiments of an earlier run whose outputs are still complete.
// --tiny runs the smoke-test arguments instead of the defaults. Started by mpirun (or srun) it
// deals the experiments out over the ranks, costliest first (the manifest's cpu_s), the j-th to rank
// j mod size; each writes its own folders, and rank 0 gathers what ran and writes index.md and
// study.json, as a serial run does.
// --jobs N runs N experiments at a time (default: one per core), each child's output kept in a
// log and printed whole when it ends, so that two experiments' lines never interleave.
// Exit codes: 0, 1 an experiment failed or an output is missing, 2 bad input, 128 + an interrupt's signal.
#include "cli.hpp"
#include "output.hpp"
#include "process.hpp"
#include "ranks.hpp"
#include "study_manifest.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <thread>

using namespace contact;
namespace fs = std::filesystem;

int program(int argc, char** argv) {
  const Ranks ranks(argc, argv);
  std::string out = "results", manifest_path = CONTACT_ODE_STUDY_MANIFEST, only;
  bool tiny = false;
  long jobs = std::max(1u, std::thread::hardware_concurrency());
  cli::Options app("study", "Runs every experiment of the study into one folder and writes its index.md.");
  app.add("--out", out, "results folder");
  app.add("--manifest", manifest_path, "the study's manifest", cli::existing_file());
  app.add_flag("--tiny", tiny, "run the smoke-test settings (seconds, for tests)");
  app.add("--only", only, "run only these experiments, comma-separated (default: all)");
  app.add("--jobs", jobs, "experiments run at a time (default: the cores)", cli::integer_in(1, 64));
  if (const int code = app.parse(argc, argv); code >= 0) return code;
  StudyManifest manifest;
  const fs::path bin = fs::read_symlink("/proc/self/exe").parent_path();
  try {
    manifest = load_study_manifest(manifest_path);
    if (const auto err = missing_program(manifest, bin); !err.empty())
      throw std::runtime_error(fmt::format("'{}': {}", manifest_path, err));
  } catch (const std::exception& ex) {
    std::cerr << "study: --manifest: " << ex.what() << "\n";
    return cli::kExitBadInput;
  }
  std::vector<std::string> names;
  for (const auto& e : manifest.experiments) names.push_back(e.name);
  const auto only_list =
      !app.given("--only") ? std::vector<std::string>{} : cli::split_list(only);  // absent: all
  for (const auto& name : only_list)
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::cerr << fmt::format("study: --only: value '{}' is not an experiment; accepted: {}\n", name,
                               fmt::join(names, ", "));
      return cli::kExitBadInput;
    }
  // The study writes into --out (each experiment replaces its own folder), so a folder that
  // holds other files is fine; it must be a writable folder whose index.md and study.json, if
  // any, are an earlier study's.
  if (auto err = check_output_dir(out, ""); !err.empty() || !(err = foreign_study_files(out)).empty()) {
    std::cerr << "study: " << err << "\n";
    return cli::kExitBadInput;
  }
  require_scratch_location();  // the logs' folder, and every experiment's figures
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json record = {{"tiny", tiny}, {"experiments", nlohmann::json::array()}};
  nlohmann::json mine = nlohmann::json::array();  // this rank's runs: {"index", "record", "ok"}
  // The chosen experiments, costliest first (longest-processing-time order: the last job to start
  // is a short one, so the jobs end together), dealt round-robin over the ranks.
  std::vector<std::size_t> chosen, queue;  // queue: this rank's
  for (std::size_t index = 0; index < manifest.experiments.size(); ++index)
    if (only_list.empty() ||
        std::find(only_list.begin(), only_list.end(), manifest.experiments[index].name) != only_list.end())
      chosen.push_back(index);
  std::stable_sort(chosen.begin(), chosen.end(), [&](std::size_t a, std::size_t b) {
    return manifest.experiments[a].cpu_s > manifest.experiments[b].cpu_s;
  });
  for (std::size_t j = 0; j < chosen.size(); ++j)
    if (static_cast<int>(j % static_cast<std::size_t>(ranks.size())) == ranks.rank())
      queue.push_back(chosen[j]);
  const bool quiet = jobs > 1;  // children's output to logs, printed whole
  const ScratchDir logs_dir{quiet ? make_scratch_dir("contact_study")
                                  : fs::path()};  // removed however it ends
  const fs::path& logs = logs_dir.path;
  std::mutex lock;  // guards `mine` and the terminal
  // Each experiment is one process on one core: OpenBLAS's worker threads, which spin between calls
  // (sched_yield), would take CPU from the other jobs. A user's own setting stands.
  setenv("OPENBLAS_NUM_THREADS", "1", 0);
  try {
    run_parallel(queue.size(), jobs, [&](std::size_t q) {
      const std::size_t index = queue[q];
      const auto& e = manifest.experiments[index];
      // The experiment replaces its folder only if it succeeds: earlier results stay until then.
      const fs::path dir = fs::path(out) / e.name, log = quiet ? logs / (e.name + ".log") : fs::path();
      std::vector<std::string> cmd{(bin / e.exe).string()};
      for (const auto& a : tiny ? e.tiny : e.args) cmd.push_back(a);
      cmd.insert(cmd.end(), {"--out", dir.string()});
      if (!quiet) fmt::print("\n== {} ==\n", e.name);
      std::fflush(stdout);
      const auto t0 = std::chrono::steady_clock::now();
      const int code = run_process(cmd, {}, log);  // throws Interrupted after a Ctrl-C: the study stops
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::vector<std::string> problems =
          code == 0 ? check_outputs(e, dir) : std::vector<std::string>{fmt::format("exit code {}", code)};
      const std::lock_guard<std::mutex> hold(lock);
      mine.push_back({{"index", index},  // recorded first: a print may fail (stdout's reader gone)
                      {"record",
                       {{"name", e.name},
                        {"command", fmt::format("{}", fmt::join(cmd, " "))},
                        {"wall_time_s", seconds},
                        {"ok", problems.empty()}}}});
      if (quiet) fmt::print("\n== {} ({:.1f} s) ==\n{}", e.name, seconds, read_text(log));
      std::fflush(stdout);
      for (const auto& p : problems) std::cerr << fmt::format("study: {}: {}\n", e.name, p);
    });
  } catch (...) {  // Interrupted, or a print the interrupt cut short (SIGPIPE)
    if (!interrupted()) throw;
    throw Interrupted{interrupted_outcome(mine)};  // say which experiments finished before it
  }
  // Rank 0 gathers every rank's runs and lists them in the manifest's order.
  const auto gathered = ranks.gather(json_text(mine));
  if (ranks.rank() != 0) return 0;
  const int failures = add_runs(record, gathered);
  const std::size_t ran = record["experiments"].size();
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record["wall_time_s"] = total;
  if (ran == manifest.experiments.size()) record["complete_wall_time_s"] = total;
  record["cores"] = std::thread::hardware_concurrency();
  record["ranks"] = ranks.size();
  record["jobs"] = jobs;
  if (failures > 0) {
    std::cerr << fmt::format("study: {} experiment(s) failed; index.md not written\n", failures);
    return cli::kExitFailure;
  }
  if (ran < manifest.experiments.size()) keep_earlier_runs(manifest, record, out);
  OutputSet files;
  files.add("index.md", study_index(manifest, record, out));
  files.add("study.json", json_text(record, 2) + "\n");
  files.write_into(out);
  fmt::print("\nstudy: {} experiment(s) in {:.1f} s; index in {}\n", ran, total,
             (fs::path(out) / "index.md").string());
  return 0;
}

int main(int argc, char** argv) { return contact::guarded_main("study", argc, argv, program); }
