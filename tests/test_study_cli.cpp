// The study runner and the smoke test of every experiment: each, run with its tiny settings,
// leaves every output its manifest entry declares, CSVs with their declared columns, figures as
// PNG and PDF; index.md links them all.
#include "cli_fixture.hpp"
#include "study_manifest.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <set>

using namespace contact;

namespace {
class StudyCli : public CliTest {};
// The manifest's entry for experiment `name`, or null.
nlohmann::json entry_named(const nlohmann::json& manifest, const std::string& name) {
  for (const auto& e : manifest.at("experiments"))
    if (e.at("name") == name) return e;
  return nullptr;
}
}  // namespace

TEST_F(StudyCli, EveryExperimentLeavesItsDeclaredOutputsAndTheIndexLinksThem) {
  const StudyManifest manifest = load_study_manifest(STUDY_MANIFEST);
  ASSERT_GE(manifest.experiments.size(), 14u);
  const Outcome r = run(STUDY_EXE, "--tiny --out s");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string index = slurp(dir_ / "s" / "index.md");
  for (const auto& e : manifest.experiments) {
    EXPECT_TRUE(fs::is_directory(dir_ / "s" / e.name)) << e.name;
    const auto problems = check_outputs(e, dir_ / "s" / e.name);
    EXPECT_TRUE(problems.empty()) << e.name << ": " << (problems.empty() ? "" : problems.front());
    for (const auto& o : e.outputs)
      EXPECT_NE(index.find("(" + e.name + "/" + o.file + ")"), std::string::npos) << e.name << "/" << o.file;
  }
  EXPECT_TRUE(nlohmann::json::accept(slurp(dir_ / "s" / "study.json")));
}

// Rerunning one experiment (--only) replaced index.md and study.json with that experiment alone,
// though the folder still held every other's results (and the paper quoted that run's time as the
// study's). The others of an earlier run with the same settings stay, marked, while their outputs
// are complete; the run of every experiment keeps its wall time for the paper.
TEST_F(StudyCli, RerunningSomeExperimentsKeepsTheOthersOfTheFolder) {
  ASSERT_EQ(run(STUDY_EXE, "--tiny --only zeno,contact_advisor --out s").code, 0);
  ASSERT_EQ(run(STUDY_EXE, "--tiny --only contact_advisor --out s").code, 0);
  auto study = [&] { return nlohmann::json::parse(slurp(dir_ / "s" / "study.json")); };
  std::string index = slurp(dir_ / "s" / "index.md");
  EXPECT_NE(index.find("2 experiments (smoke-test settings); 1 run now"), std::string::npos) << index;
  EXPECT_NE(index.find("## zeno\n\n(From an earlier run.)"), std::string::npos) << index;
  EXPECT_NE(index.find("(zeno/zeno.csv)"), std::string::npos) << index;
  ASSERT_EQ(study().at("experiments").size(), 2u);
  EXPECT_FALSE(study().contains("complete_wall_time_s"));  // no run of all 20
  // An experiment whose outputs are no longer complete is not listed.
  fs::remove(dir_ / "s" / "zeno" / "zeno.csv");
  ASSERT_EQ(run(STUDY_EXE, "--tiny --only contact_advisor --out s").code, 0);
  EXPECT_EQ(slurp(dir_ / "s" / "index.md").find("## zeno"), std::string::npos);
  EXPECT_EQ(study().at("experiments").size(), 1u);
}

// The study writes index.md and study.json into --out, a folder that may hold other files: one of
// those names that no study wrote is refused (exit 2) and kept. The study overwrote them: `study
// --out ~/notes` replaced the notes' own index.md. An earlier study's folder is written as before.
TEST_F(StudyCli, AnIndexNoStudyWroteIsRefusedAndKept) {
  for (const char* name : {"index.md", "study.json"}) {
    const fs::path mine = dir_ / (std::string("mine_") + name);
    fs::create_directories(mine);
    std::ofstream(mine / name) << "my own\n";
    const Outcome r = run(STUDY_EXE, "--tiny --only contact_advisor --out " + mine.filename().string());
    EXPECT_EQ(r.code, 2) << name << ": " << r.err;
    EXPECT_NE(r.err.find("holds a " + std::string(name) + " that no study wrote"), std::string::npos)
        << r.err;
    EXPECT_EQ(slurp(mine / name), "my own\n") << name;
    EXPECT_FALSE(fs::exists(mine / "contact_advisor")) << name;  // refused before any work
  }
  ASSERT_EQ(run(STUDY_EXE, "--tiny --only contact_advisor --out s").code, 0);
  EXPECT_EQ(run(STUDY_EXE, "--tiny --only contact_advisor --out s").code, 0);
}

// The check is not vacuous: a missing column, a short row, a long row, a table without rows, a
// figure without its PDF and a missing file are each reported.
TEST_F(StudyCli, OutputCheckReportsEveryKindOfDefect) {
  StudyExperiment e{"x",
                    "x",
                    {},
                    {},
                    "",
                    {{"t.csv", {"a", "b"}, ""},
                     {"long.csv", {"a"}, ""},
                     {"empty.csv", {"a"}, ""},
                     {"f.png", {}, ""},
                     {"gone.csv", {}, ""}}};
  std::ofstream(dir_ / "t.csv") << "a,c\n1\n";
  std::ofstream(dir_ / "long.csv") << "a\n1\n2,3\n";
  std::ofstream(dir_ / "empty.csv") << "a\n";
  std::ofstream(dir_ / "f.png") << "\x89PNG\r\n\x1a\n....";
  std::ofstream(dir_ / "meta.json") << "{}";
  const auto problems = check_outputs(e, dir_);
  auto reported = [&](const std::string& what) {
    return std::any_of(problems.begin(), problems.end(),
                       [&](const std::string& p) { return p.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(reported("column 'b' missing"));
  EXPECT_TRUE(reported("row 1 does not have the header's 2 cells"));
  EXPECT_TRUE(reported("long.csv: row 2 does not have the header's 1 cells"));
  EXPECT_TRUE(reported("empty.csv: no rows"));
  EXPECT_TRUE(reported("f.png: no PDF"));
  EXPECT_TRUE(reported("gone.csv: missing"));
  EXPECT_EQ(problems.size(), 6u);
}

TEST_F(StudyCli, BadInputIsRefused) {
  expect_refused(STUDY_EXE, {
                                {"--only ball_drop,moon", "--only", "'moon'", "ball_drop"},
                                {"--manifest nowhere.json", "--manifest", "nowhere.json", "exist"},
                            });
}

// The study started its experiments in the manifest's order, so that its two longest
// (convergence_dt, work_precision, listed late) ran last and one core idled for a second at the
// end. It starts the costliest first now (the manifest's cpu_s), and still lists them in the
// manifest's order. One job at a time shows the start order; a hint out of range is refused.
TEST_F(StudyCli, TheCostliestExperimentStartsFirstAndTheIndexKeepsTheManifestOrder) {
  auto manifest = nlohmann::json::parse(slurp(STUDY_MANIFEST));
  const nlohmann::json advisor = entry_named(manifest, "contact_advisor");
  ASSERT_FALSE(advisor.is_null());
  auto write = [&](double cheap_s, double dear_s) {
    nlohmann::json cheap = advisor, dear = advisor;
    cheap["name"] = "cheap";
    cheap["cpu_s"] = cheap_s;
    dear["name"] = "dear";
    dear["cpu_s"] = dear_s;
    manifest["experiments"] = {cheap, dear};
    std::ofstream(dir_ / "m.json") << manifest.dump();
  };
  write(0.1, 9.0);
  const Outcome r = run(STUDY_EXE, "--tiny --jobs 1 --manifest m.json --out s");
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_NE(r.out.find("== cheap =="), std::string::npos) << r.out;
  EXPECT_LT(r.out.find("== dear =="), r.out.find("== cheap ==")) << r.out;
  const std::string index = slurp(dir_ / "s" / "index.md");
  ASSERT_NE(index.find("## dear"), std::string::npos) << index;
  EXPECT_LT(index.find("## cheap"), index.find("## dear")) << index;
  fs::remove_all(dir_ / "s");
  write(-1.0, 9.0);
  const Outcome bad = run(STUDY_EXE, "--tiny --manifest m.json --out s");
  EXPECT_EQ(bad.code, 2);
  for (const char* part : {"--manifest", "'cheap'", "cpu_s", "'-1'", "[0, inf)"})
    EXPECT_NE(bad.err.find(part), std::string::npos) << part << " in: " << bad.err;
}

// A manifest is checked whole before any experiment runs, and one that is not a manifest is refused
// (exit 2) naming the experiment, its key, the value and what is accepted, with nothing written. A
// name "../esc" used to write its folder beside --out (exit 0); a name given twice ran two
// experiments into one folder; a missing program failed only after the others had run; an empty
// list wrote an index of nothing; a key of the wrong kind gave the JSON library's message alone.
TEST_F(StudyCli, AManifestThatIsNotOneIsRefusedBeforeAnyWork) {
  auto manifest = nlohmann::json::parse(slurp(STUDY_MANIFEST));
  const nlohmann::json advisor = entry_named(manifest, "contact_advisor");
  ASSERT_FALSE(advisor.is_null());
  const auto with = [&](const char* key, const nlohmann::json& value) {
    nlohmann::json e = advisor;
    e[key] = value;
    return e;
  };
  const auto list = [](auto... e) { return nlohmann::json::array({e...}); };
  const std::vector<std::pair<nlohmann::json, std::string>> cases = {
      {list(with("name", "../esc")),
       "experiment 1 ('../esc'): name: value '../esc' is not accepted; accepted: a folder's plain name"},
      {list(with("name", "")), "experiment 1 (''): name: value '' is not accepted"},
      {list(with("name", "..")), "experiment 1 ('..'): name: value '..' is not accepted"},
      {list(with("exe", "")), "experiment 'contact_advisor': exe: value '' is not a program in "},
      {list(advisor, advisor), "experiment 2 ('contact_advisor'): name: given to an experiment before it"},
      {list(with("exe", "nosuch")), "experiment 'contact_advisor': exe: value 'nosuch' is not a program in "},
      {list(), "not a study manifest; accepted: {\"title\": text, \"experiments\": [at least one]}"},
      {list(with("tinny", list())), "experiment 1 ('contact_advisor'): key 'tinny' is not known"},
      {list(with("args", list(1))), "args: value [1] is not accepted; accepted: a list of strings"},
      {list(with("outputs", {{"/tmp/advice.csv", {{"about", "a"}}}})),
       "outputs: '/tmp/advice.csv' is not accepted"},
      {list(with("outputs", {{"../advice.csv", {{"about", "a"}}}})),
       "outputs: '../advice.csv' is not accepted; accepted: a path inside the experiment's folder"},
      {list(with("outputs", {{"advice.csv", {{"columns", "k_lin"}, {"about", "a"}}}})),
       "outputs: 'advice.csv': value"},
      {list(with("cpu_s", "1")), "cpu_s: value '\"1\"' is out of range; accepted range [0, inf)"}};
  for (const auto& [experiments, message] : cases) {
    manifest["experiments"] = experiments;
    std::ofstream(dir_ / "m.json") << manifest.dump();
    const Outcome r = run(STUDY_EXE, "--tiny --jobs 1 --manifest m.json --out s/out");
    EXPECT_EQ(r.code, 2) << experiments.dump();
    EXPECT_NE(r.err.find("study: --manifest: '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << experiments.dump() << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "s")) << experiments.dump();
  }
}

// A program that exists but cannot start (its interpreter missing) fails the study with the
// system's reason, exit 1, not as an interrupt: the study turns an exception into the interrupt's
// message only after a signal (a print cut short by SIGPIPE).
TEST_F(StudyCli, AProgramThatCannotStartFailsTheStudyNamingIt) {
  std::ofstream(dir_ / "broken.sh") << "#!/nonexistent/interpreter\n";
  fs::permissions(dir_ / "broken.sh", fs::perms::owner_all);
  std::ofstream(dir_ / "m.json") << fmt::format(
      R"({{"title": "t", "experiments": [{{"name": "broken", "exe": "{}", "args": [], "tiny": [], "cpu_s": 1,
      "summary": "s", "outputs": {{}}}}]}})",
      (dir_ / "broken.sh").string());
  const Outcome r = run(STUDY_EXE, "--manifest m.json --jobs 1 --out s");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("study: cannot run " + (dir_ / "broken.sh").string() + ": No such file or directory"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("interrupted"), std::string::npos) << r.err;
}

// A new experiment without its cost would run last (cpu_s 0) however long it takes, and the study
// would end on it alone: every entry carries the hint.
TEST(StudyManifestTest, EveryExperimentCarriesItsSchedulingHint) {
  for (const auto& e : load_study_manifest(STUDY_MANIFEST).experiments) EXPECT_GT(e.cpu_s, 0.0) << e.name;
}

// Each experiment is a recipe: the skeleton (experiment.hpp) and the libraries hold everything
// shared, so that no experiment's file grows past 150 lines.
TEST(StudyManifestTest, EveryExperimentIsAShortRecipe) {
  const StudyManifest manifest = load_study_manifest(STUDY_MANIFEST);
  const fs::path folder = fs::path(STUDY_MANIFEST).parent_path();
  std::set<std::string> files = {"paper_numbers.cpp", "study.cpp"};
  for (const auto& e : manifest.experiments) files.insert(e.exe + ".cpp");
  for (const auto& file : files) {
    std::ifstream in(folder / file);
    ASSERT_TRUE(in) << file;
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    EXPECT_LE(lines, 150u) << file;
  }
}

// index.md tells a reader what each experiment did from its manifest summary; a number there is a
// default of the experiment and has to stay one. convergence_dt's said "five drop heights" long
// after its default became three.
TEST_F(StudyCli, TheSummariesStateTheDefaultsTheExperimentsRunWith) {
  struct Claim {
    std::string experiment, option, pattern;  // pattern's group 1: the number the summary states
  };
  const std::vector<Claim> claims = {
      {"ball_drop", "--m", R"(\(([0-9.e]+) kg)"},
      {"ball_drop", "--h0", R"(from ([0-9.e]+) m)"},
      {"ball_drop", "--e", R"(e = ([0-9.e]+))"},
      {"ball_drop", "--k", R"(k = ([0-9.e]+) N/m)"},
      {"ball_drop_sweep", "--k-min", R"(k from ([0-9.e]+) to)"},
      {"ball_drop_sweep", "--k-max", R"(to ([0-9.e]+) N/m)"},
      {"energy_drift", "--bounces", R"(over ([0-9]+) undamped bounces)"},
      {"convergence_dt", "--heights", R"(over ([a-z]+) drop heights)"},
  };
  const std::map<std::string, double> words = {{"two", 2}, {"three", 3}, {"four", 4}, {"five", 5},
                                               {"six", 6}, {"seven", 7}, {"ten", 10}};
  auto number = [&](const std::string& s) { return words.count(s) ? words.at(s) : std::stod(s); };
  const StudyManifest manifest = load_study_manifest(STUDY_MANIFEST);
  for (const auto& c : claims) {
    const auto e = std::find_if(manifest.experiments.begin(), manifest.experiments.end(),
                                [&](const auto& x) { return x.name == c.experiment; });
    ASSERT_NE(e, manifest.experiments.end()) << c.experiment;
    std::smatch said, help_default;
    ASSERT_TRUE(std::regex_search(e->summary, said, std::regex(c.pattern)))
        << c.pattern << " in " << e->summary;
    const Outcome help = run((fs::path(STUDY_EXE).parent_path() / e->exe).string(), "--help");
    ASSERT_EQ(help.code, 0) << e->exe;
    // An option the entry's arguments set is the value it runs with; --help shows the default.
    double runs_with = std::nan("");
    for (std::size_t i = 0; i + 1 < e->args.size(); ++i)
      if (e->args[i] == c.option) runs_with = std::stod(e->args[i + 1]);
    if (std::isnan(runs_with)) {
      ASSERT_TRUE(
          std::regex_search(help.out, help_default, std::regex("\\n  " + c.option + " [^\\n]*=([^ \\n]+)")))
          << c.option << " in " << help.out;
      runs_with = std::stod(help_default[1]);
    }
    EXPECT_EQ(number(said[1]), runs_with) << c.experiment << " " << c.option << ": " << e->summary;
  }
}
