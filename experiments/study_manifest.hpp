#pragma once
// The study's manifest (experiments/study.json): every experiment, its arguments (the study's and
// the smoke test's), and every output it must leave, with a CSV's required columns and one
// sentence for the index. One source for the study runner, its index and the smoke test.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace contact {

struct StudyOutput {
  std::string file;                  // relative to the experiment's folder
  std::vector<std::string> columns;  // CSV: columns the header must contain
  std::string about;                 // one sentence for index.md
};

struct StudyExperiment {
  std::string name;  // its folder under the results
  std::string exe;   // the executable, next to `study`
  std::vector<std::string> args, tiny;
  std::string summary;
  std::vector<StudyOutput> outputs;
  // CPU seconds of its default run on the reference machine: the study starts the costliest first
  // so that its jobs end together. A scheduling hint (a stale one costs time, never a result).
  double cpu_s = 0.0;
};

struct StudyManifest {
  std::string title;
  std::vector<StudyExperiment> experiments;
};

// Throws std::runtime_error naming the file and what is wrong with it: not JSON, a key unknown,
// missing or of the wrong kind, a name that is not a folder's plain name or is given twice, no
// experiment, an output outside the experiment's folder, a cost out of range.
StudyManifest load_study_manifest(const std::filesystem::path& path);

// "" when every experiment's program (exe: a name in `bin`, next to study, or an absolute path) is
// an executable; else the refusal naming the first that is not.
std::string missing_program(const StudyManifest& manifest, const std::filesystem::path& bin);

// What is wrong with an experiment's folder: a declared output missing or empty, a CSV whose
// header lacks a declared column or whose rows differ in width from it, a PNG or PDF without its
// signature, a meta.json that does not parse. Empty when all is well.
std::vector<std::string> check_outputs(const StudyExperiment& experiment, const std::filesystem::path& dir);

// The runs' records {"index", "record": {"name", ..., "ok"}}, from every rank, appended to
// record["experiments"] in the manifest's order. Returns how many failed.
int add_runs(nlohmann::json& record, const std::vector<std::string>& gathered);

// What a study interrupted after `runs` (its records, as above) leaves behind: the experiments
// that finished before the signal have replaced their folders, the others keep earlier results.
std::string interrupted_outcome(const nlohmann::json& runs);

// A run of some experiments (study --only) keeps, from the folder's earlier study.json of the same
// settings, the record of every other experiment whose outputs are still complete (marked
// "earlier"), so that index.md and study.json describe the whole folder, not the last few runs;
// and the wall time of the last run of every experiment ("complete_wall_time_s", the paper's).
void keep_earlier_runs(const StudyManifest& manifest, nlohmann::json& record,
                       const std::filesystem::path& results);

// "" unless `out` holds an index.md or a study.json that no study wrote (a study.json without its
// record of experiments, or an index.md without a study.json): the study writes both into --out
// and would overwrite them. Otherwise the refusal, naming --out, the file and what is accepted.
std::string foreign_study_files(const std::filesystem::path& out);

// The wall time of the study's last run of every experiment, from its study.json (`file`, for the
// message); throws std::runtime_error if it only holds runs of a few (study --only).
double complete_wall_time(const nlohmann::json& study, const std::filesystem::path& file);

// results/index.md: per experiment its summary and a link with one sentence per output (tables
// to their Markdown rendering when `results` holds one, with the CSV beside), and the run's record.
std::string study_index(const StudyManifest& manifest, const nlohmann::json& record,
                        const std::filesystem::path& results);

}  // namespace contact
