#include "study_manifest.hpp"

#include "contact_ode/analysis/table.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace contact {

namespace fs = std::filesystem;

StudyManifest load_study_manifest(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("cannot read '{}'", path.string()));
  try {
    const auto j = nlohmann::ordered_json::parse(in);  // ordered: outputs keep the manifest's order
    StudyManifest m{j.at("title").get<std::string>(), {}};
    for (const auto& e : j.at("experiments")) {
      StudyExperiment x{e.at("name"), e.at("exe"), e.at("args"), e.at("tiny"), e.at("summary"), {}};
      for (const auto& [file, o] : e.at("outputs").items())
        x.outputs.push_back({file, o.value("columns", std::vector<std::string>{}), o.at("about")});
      m.experiments.push_back(std::move(x));
    }
    return m;
  } catch (const nlohmann::ordered_json::exception& ex) {
    throw std::runtime_error(fmt::format("'{}' is not a valid study manifest: {}", path.string(), ex.what()));
  }
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
  std::istringstream in(text);
  std::string header;
  std::getline(in, header);
  const auto columns = split_csv_line(header);
  for (const auto& c : o.columns)
    if (std::find(columns.begin(), columns.end(), c) == columns.end())
      problems.push_back(fmt::format("{}: column '{}' missing (header: {})", o.file, c, header));
  long row = 1;
  for (std::string line; std::getline(in, line); ++row)
    if (split_csv_line(line).size() != columns.size()) {
      problems.push_back(
          fmt::format("{}: row {} does not have the header's {} cells", o.file, row, columns.size()));
      return;
    }
  if (row == 1) problems.push_back(fmt::format("{}: no rows", o.file));
}

}  // namespace

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

std::string study_index(const StudyManifest& m, const nlohmann::json& record, const fs::path& results) {
  std::string s = fmt::format("# {}\n\n", m.title);
  s += fmt::format(
      "{} experiments{} in {:.1f} s of wall time on {} cores (per-experiment times and commands in "
      "[study.json](study.json); each experiment's options, versions and revision in its `meta.json`). "
      "Rebuild everything with `bash scripts/run_study.sh`.\n\n",
      record.at("experiments").size(), record.value("tiny", false) ? " (smoke-test settings)" : "",
      record.at("wall_time_s").get<double>(), record.value("cores", 0u));
  for (const auto& e : m.experiments) {
    bool ran = false;
    for (const auto& r : record.at("experiments")) ran = ran || r.at("name") == e.name;
    if (!ran) continue;
    s += fmt::format("## {}\n\n{}\n\n", e.name, e.summary);
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
