#include "study_manifest.hpp"

#include "output.hpp"

#include "contact_ode/analysis/table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace contact {

namespace fs = std::filesystem;

namespace {

using ordered_json = nlohmann::ordered_json;

// A plain name: one path component, so that an experiment's folder is inside --out ("", ".", ".."
// or "a/b" would put it elsewhere: "../x" wrote beside --out).
bool plain_name(const std::string& s) {
  return !s.empty() && s != "." && s != ".." && s.find('/') == std::string::npos;
}

// One experiment, every key checked; `bad` throws naming the experiment.
StudyExperiment parse_experiment(const ordered_json& e, const std::function<void(const std::string&)>& bad) {
  if (!e.is_object()) bad("is not an object; accepted: {\"name\", \"exe\", \"args\", ...}");
  const std::set<std::string> keys{"name", "exe", "args", "tiny", "cpu_s", "summary", "outputs"};
  for (const auto& [key, value] : e.items())
    if (!keys.count(key)) bad(fmt::format("key '{}' is not known; accepted: {}", key, fmt::join(keys, ", ")));
  for (const auto& key : keys)
    if (!e.contains(key)) bad(fmt::format("{}: missing", key));
  const auto strings = [&](const char* key) {
    const auto& v = e.at(key);
    if (!v.is_array() || !std::all_of(v.begin(), v.end(), [](const auto& a) { return a.is_string(); }))
      bad(fmt::format("{}: value {} is not accepted; accepted: a list of strings", key, v.dump()));
    return v.template get<std::vector<std::string>>();
  };
  const auto text = [&](const char* key) {
    if (!e.at(key).is_string())
      bad(fmt::format("{}: value {} is not accepted; accepted: a string", key, e.at(key).dump()));
    return e.at(key).template get<std::string>();
  };
  StudyExperiment x{text("name"), text("exe"), strings("args"), strings("tiny"), text("summary"), {}, 0.0};
  if (!plain_name(x.name))
    bad(fmt::format(
        "name: value '{}' is not accepted; accepted: a folder's plain name (no '/', not '.' or '..')",
        x.name));
  const auto& cpu = e.at("cpu_s");
  if (!cpu.is_number() || !std::isfinite(cpu.get<double>()) || cpu.get<double>() < 0)
    bad(fmt::format("cpu_s: value '{}' is out of range; accepted range [0, inf)",
                    cpu.is_number() ? fmt::format("{}", cpu.get<double>()) : cpu.dump()));
  x.cpu_s = cpu.get<double>();
  if (!e.at("outputs").is_object())
    bad(fmt::format("outputs: value {} is not accepted; accepted: an object, output file -> about it",
                    e.at("outputs").dump()));
  for (const auto& [file, o] : e.at("outputs").items()) {
    if (!stays_inside(file))
      bad(fmt::format("outputs: '{}' is not accepted; accepted: a path inside the experiment's folder",
                      file));
    if (!o.is_object() || !o.contains("about") || !o.at("about").is_string() ||
        (o.contains("columns") &&
         (!o.at("columns").is_array() || !std::all_of(o.at("columns").begin(), o.at("columns").end(),
                                                      [](const auto& c) { return c.is_string(); }))))
      bad(
          fmt::format("outputs: '{}': value {} is not accepted; accepted: {{\"about\": sentence, optional "
                      "\"columns\": [names]}}",
                      file, o.dump()));
    x.outputs.push_back({file, o.value("columns", std::vector<std::string>{}), o.at("about")});
  }
  return x;
}

}  // namespace

StudyManifest load_study_manifest(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("cannot read '{}'", path.string()));
  ordered_json j;  // ordered: outputs keep the manifest's order
  try {
    j = ordered_json::parse(in);
  } catch (const ordered_json::parse_error& ex) {
    throw std::runtime_error(fmt::format("'{}' is not JSON: {}", path.string(), ex.what()));
  }
  const auto whole = [&](const std::string& what) {
    throw std::runtime_error(fmt::format("'{}': {}", path.string(), what));
  };
  if (!j.is_object() || !j.contains("title") || !j.at("title").is_string() || !j.contains("experiments") ||
      !j.at("experiments").is_array() || j.at("experiments").empty())
    whole("not a study manifest; accepted: {\"title\": text, \"experiments\": [at least one]}");
  StudyManifest m{j.at("title"), {}};
  std::set<std::string> names;
  for (std::size_t i = 0; i < j.at("experiments").size(); ++i) {
    const auto& e = j.at("experiments")[i];
    const auto bad = [&](const std::string& what) {
      const bool named = e.is_object() && e.contains("name") && e.at("name").is_string();
      whole(
          fmt::format("experiment {} ('{}'): {}", i + 1, named ? e.at("name").get<std::string>() : "", what));
    };
    m.experiments.push_back(parse_experiment(e, bad));
    if (!names.insert(m.experiments.back().name).second)  // two runs into one folder
      bad("name: given to an experiment before it; accepted: each name once");
  }
  return m;
}

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Problems of one CSV: the header must hold every declared column; every row must be as wide as
// the header.
void check_csv(const std::string& text, const StudyOutput& o, std::vector<std::string>& problems) {
  std::vector<std::vector<std::string>> records;
  try {
    records = parse_csv(text);
  } catch (const std::runtime_error& ex) {
    problems.push_back(fmt::format("{}: {}", o.file, ex.what()));
    return;
  }
  const auto columns = records.empty() ? std::vector<std::string>{} : records.front();
  for (const auto& c : o.columns)
    if (std::find(columns.begin(), columns.end(), c) == columns.end())
      problems.push_back(
          fmt::format("{}: column '{}' missing (header: {})", o.file, c, fmt::join(columns, ",")));
  for (std::size_t row = 1; row < records.size(); ++row)
    if (records[row].size() != columns.size()) {
      problems.push_back(
          fmt::format("{}: row {} does not have the header's {} cells", o.file, row, columns.size()));
      return;
    }
  if (records.size() < 2) problems.push_back(fmt::format("{}: no rows", o.file));
}

}  // namespace

std::string missing_program(const StudyManifest& m, const fs::path& bin) {
  for (const auto& e : m.experiments)
    if (::access((bin / e.exe).c_str(), X_OK) != 0 || fs::is_directory(bin / e.exe))
      return fmt::format(
          "experiment '{}': exe: value '{}' is not a program in {}; accepted: a program built there, or the "
          "absolute path of one",
          e.name, e.exe, bin.string());
  return "";
}

std::vector<std::string> check_outputs(const StudyExperiment& e, const fs::path& dir) {
  std::vector<std::string> problems;
  for (const auto& o : e.outputs) {
    const fs::path p = dir / o.file;
    if (!fs::exists(p) || fs::file_size(p) == 0) {
      problems.push_back(fmt::format("{}: missing or empty", o.file));
      continue;
    }
    const std::string text = slurp(p), ext = p.extension().string();
    if (ext == ".csv") check_csv(text, o, problems);
    if (ext == ".png" && text.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0)
      problems.push_back(o.file + ": not a PNG");
    if (ext == ".png") {
      const fs::path pdf = fs::path(p).replace_extension(".pdf");  // every figure also as PDF, for the paper
      if (!fs::exists(pdf) || slurp(pdf).compare(0, 5, "%PDF-") != 0)
        problems.push_back(o.file + ": no PDF beside it");
    }
  }
  if (!fs::exists(dir / "meta.json") || !nlohmann::json::accept(slurp(dir / "meta.json")))
    problems.emplace_back("meta.json: missing or not JSON");
  return problems;
}

int add_runs(nlohmann::json& record, const std::vector<std::string>& gathered) {
  std::vector<nlohmann::json> runs;
  for (const auto& part : gathered)
    for (auto& run : nlohmann::json::parse(part)) runs.push_back(std::move(run));
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a["index"] < b["index"]; });
  int failures = 0;
  for (const auto& run : runs) {
    failures += run["record"]["ok"].get<bool>() ? 0 : 1;
    record["experiments"].push_back(run["record"]);
  }
  return failures;
}

std::string interrupted_outcome(const nlohmann::json& runs) {
  std::vector<std::string> finished;
  for (const auto& run : runs)
    if (run["record"]["ok"].get<bool>()) finished.push_back(run["record"]["name"].get<std::string>());
  return fmt::format("{}; the others keep their earlier results; index.md not written",
                     finished.empty() ? std::string("no experiment had finished")
                                      : fmt::format("finished before it, their folders replaced: {}",
                                                    fmt::join(finished, ", ")));
}

namespace {

// The record of experiment `name` in a study.json's list, or null.
const nlohmann::json* record_of(const nlohmann::json& record, const std::string& name) {
  for (const auto& r : record.at("experiments"))
    if (r.at("name") == name) return &r;
  return nullptr;
}

}  // namespace

void keep_earlier_runs(const StudyManifest& m, nlohmann::json& record, const fs::path& results) {
  nlohmann::json earlier;
  try {
    std::ifstream in(results / "study.json");
    earlier = nlohmann::json::parse(in);
    if (earlier.value("tiny", false) != record.value("tiny", false)) return;  // other settings
    nlohmann::json merged = nlohmann::json::array();
    for (const auto& e : m.experiments)
      if (const auto* now = record_of(record, e.name))
        merged.push_back(*now);
      else if (const auto* before = record_of(earlier, e.name);
               before && before->value("ok", false) && check_outputs(e, results / e.name).empty()) {
        merged.push_back(*before);
        merged.back()["earlier"] = true;
      }
    record["experiments"] = merged;
    if (!record.contains("complete_wall_time_s") && earlier.contains("complete_wall_time_s"))
      record["complete_wall_time_s"] = earlier.at("complete_wall_time_s");
  } catch (const nlohmann::json::exception&) {
    // no earlier study.json, or not one of ours: this run's record alone
  }
}

std::string foreign_study_files(const fs::path& out) {
  std::error_code ec;
  const fs::path record = out / "study.json", index = out / "index.md";
  if (fs::exists(record, ec)) {
    std::ifstream in(record);
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);  // discarded on a parse error
    if (j.is_object() && j.contains("experiments")) return "";
  }
  for (const fs::path& f : {record, index})
    if (fs::exists(f, ec))
      return fmt::format(
          "--out: value '{}' holds a {} that no study wrote; accepted: a folder without "
          "index.md and study.json, or an earlier study's results",
          out.string(), f.filename().string());
  return "";
}

double complete_wall_time(const nlohmann::json& study, const fs::path& file) {
  if (!study.contains("complete_wall_time_s"))
    throw std::runtime_error(
        fmt::format("{}: no run of every experiment recorded; run `study` without --only", file.string()));
  return study.at("complete_wall_time_s").get<double>();
}

std::string study_index(const StudyManifest& m, const nlohmann::json& record, const fs::path& results) {
  std::string s = fmt::format("# {}\n\n", m.title);
  const auto& runs = record.at("experiments");
  const auto earlier = static_cast<std::size_t>(
      std::count_if(runs.begin(), runs.end(), [](const auto& r) { return r.value("earlier", false); }));
  s += fmt::format("{} experiments{}", runs.size(),
                   record.value("tiny", false) ? " (smoke-test settings)" : "");
  if (earlier > 0)
    s += fmt::format("; {} run now in {:.1f} s of wall time on {} cores, {} kept from an earlier run",
                     runs.size() - earlier, record.at("wall_time_s").get<double>(), record.value("cores", 0u),
                     earlier);
  else
    s += fmt::format(" in {:.1f} s of wall time on {} cores", record.at("wall_time_s").get<double>(),
                     record.value("cores", 0u));
  s += " (per-experiment times and commands in [study.json](study.json); each experiment's options, "
       "versions and revision in its `meta.json`). Rebuild everything with `bash scripts/run_study.sh`.\n\n";
  for (const auto& e : m.experiments) {
    const auto* run = record_of(record, e.name);
    if (!run) continue;
    s += fmt::format("## {}\n\n{}{}\n\n", e.name,
                     run->value("earlier", false) ? "(From an earlier run.) " : "", e.summary);
    for (const auto& o : e.outputs) {
      const fs::path f = fs::path(e.name) / o.file;
      const fs::path md = fs::path(f).replace_extension(".md"), pdf = fs::path(f).replace_extension(".pdf");
      if (f.extension() == ".png")
        s += fmt::format("- [{}]({}) ([PDF]({})): {}.\n", o.file, f.string(), pdf.string(), o.about);
      else if (f.extension() == ".csv" && fs::exists(results / md))
        s += fmt::format("- [{}]({}) ([Markdown]({})): {}.\n", o.file, f.string(), md.string(), o.about);
      else
        s += fmt::format("- [{}]({}): {}.\n", o.file, f.string(), o.about);
    }
    s += "\n";
  }
  return s;
}

}  // namespace contact
