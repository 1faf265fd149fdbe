// Every executable's command line, from its own --help: every option that takes a value is given
// values no option accepts (not a number, not finite, empty, an empty list item) and must refuse
// each with exit code 2, one line on stderr naming the option, and nothing written. --out is
// given the paths no run may write to. Options are read from --help, so a new option is covered
// the day it is added.
#include "cli_fixture.hpp"
#include "study_manifest.hpp"

#include <regex>
#include <set>

namespace {

class CliBattery : public CliTest {
 protected:
  // The executables: every experiment of the manifest, the study runner and paper_numbers.
  static std::vector<std::string> executables() {
    std::set<std::string> names{"study", "paper_numbers"};
    for (const auto& e : contact::load_study_manifest(STUDY_MANIFEST).experiments) names.insert(e.exe);
    return {names.begin(), names.end()};
  }
  static std::string path(const std::string& exe) { return (fs::path(EXPERIMENTS_DIR) / exe).string(); }
  // What a program needs besides the option under test (the advisor needs a requirement).
  static std::string base_args(const std::string& exe) {
    return exe == "contact_advisor" ? " --max-penetration 1e-3" : "";
  }

  struct Option {
    std::string name, type;  // e.g. "--k", "FLOAT:in (0, inf)"
    bool free_text;          // TEXT with no check: any string is a value (paths, names)
  };
  // "  --k FLOAT:in (0, inf)=1e+06 ..." -> {"--k", "FLOAT:in (0, inf)"}; flags have no type.
  std::vector<Option> options(const std::string& exe) const {
    const Outcome help = run(path(exe), "--help");
    EXPECT_EQ(help.code, 0) << exe;
    std::vector<Option> out;
    const std::regex line(R"(^\s+(?:-\w,)?(--[a-z0-9-]+)(?: (\S+(?: [^=]*?)?))?(?:=.*)?$)");
    std::istringstream in(help.out);
    for (std::string l; std::getline(in, l);) {
      std::smatch m;
      if (!std::regex_match(l, m, line) || m[1] == "--help" || !m[2].matched) continue;
      const std::string type = m[2];
      out.push_back({m[1], type, type == "TEXT"});
    }
    return out;
  }
};

}  // namespace

TEST_F(CliBattery, EveryOptionRefusesValuesNoOptionAccepts) {
  // 4.9e-324 and 1e-400 are finite but below the smallest normal double, which strtod reports as
  // it does an overflow: refused by every option, and a number option says why (it said "not a
  // finite number").
  const std::vector<std::string> bad = {"nan",   "inf",  "-inf", "abc",      "",
                                        "1e999", "1,,2", "1,",   "4.9e-324", "1e-400"};
  for (const auto& exe : executables()) {
    const auto opts = options(exe);
    ASSERT_FALSE(opts.empty()) << exe << ": no options read from --help";
    for (const auto& o : opts) {
      if (o.free_text || o.name == "--out") continue;
      // Options taking N values ("FLOAT x 4" in CLI11's help) get the bad value N times.
      int count = 1;
      if (std::smatch m; std::regex_search(o.type, m, std::regex(R"(x (\d+))"))) count = std::stoi(m[1]);
      for (const auto& value : bad) {
        std::string args;
        for (int i = 0; i < count; ++i) args += " " + o.name + " '" + value + "'";
        const Outcome r = run(path(exe), base_args(exe) + args + " --out never");
        EXPECT_EQ(r.code, 2) << exe << args << ": " << r.err;
        EXPECT_NE(r.err.find(o.name), std::string::npos) << exe << args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << exe << args << ": " << r.err;
        EXPECT_TRUE(dir_is_empty()) << exe << args << " wrote files";
        if (value.find("e-") != std::string::npos && o.type.rfind("FLOAT", 0) == 0) {
          EXPECT_NE(r.err.find("below the smallest normal double"), std::string::npos)
              << exe << args << ": " << r.err;
        }
      }
    }
  }
}

TEST_F(CliBattery, OutRefusesPathsNoRunMayWriteTo) {
  std::ofstream(dir_ / "a_file") << "x";
  const std::string long_name(300, 'a');
  const std::vector<std::string> bad_out = {"", "a_file", "a_file/below", long_name, "."};
  for (const auto& exe : executables()) {
    if (exe == "paper_numbers") continue;  // its --out is a file, checked in its own test
    for (const auto& out : bad_out) {
      const Outcome r = run(path(exe), base_args(exe) + " --out '" + out + "'");
      EXPECT_EQ(r.code, 2) << exe << " --out '" << out << "': " << r.err;
      EXPECT_NE(r.err.find("--out"), std::string::npos) << exe << " --out '" << out << "': " << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1)
          << exe << " --out '" << out << "': " << r.err;
    }
    // Nothing but the file that was there.
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
    EXPECT_EQ(entries, 1u) << exe << " wrote into the test folder";
  }
}

// A default the help shows is a value its option accepts: the advisor's requirements showed
// "--max-penetration FLOAT:in (0, inf)=0" (0 there means "not given"), a default outside the
// range printed beside it. Every number option with a range and a shown default, in every program.
TEST_F(CliBattery, EveryDefaultShownIsAValueItsOptionAccepts) {
  const std::regex line(
      R"(^\s+(--[a-z0-9-]+) (?:FLOAT|INT):(?:integer )?in ([\[(])([^,]+), ([^\])]+)([\])])=(\S+).*$)");
  std::size_t checked = 0;
  for (const auto& exe : executables()) {
    std::istringstream help(run(path(exe), "--help").out);
    for (std::string l; std::getline(help, l);) {
      std::smatch m;
      if (!std::regex_match(l, m, line)) continue;
      const double lo = std::stod(m[3]), hi = std::stod(m[4]);
      std::string shown = m[6];  // one value, or a vector's "[0.3,0.2,0.1]"
      if (shown.front() == '[') shown = shown.substr(1, shown.find(']') - 1);
      std::istringstream values(shown);
      for (std::string v; std::getline(values, v, ',');) {
        const double value = std::stod(v);
        const bool above = m[2] == "[" ? value >= lo : value > lo,
                   below = m[5] == "]" ? value <= hi : value < hi;
        EXPECT_TRUE(above && below) << exe << ": " << l;
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 80u);  // the programs' tolerances, steps, stiffnesses, counts: 87 when written
}

// A list names each item once: "--balls 2,2" or "--method penalty,penalty" ran the same case twice
// (duplicate rows, figures and paper lookups), and "all" or "none" beside other names passed the
// check and failed later. Every list option of every program, from --help: its first default
// item (or first name) twice, and "all" with a name, are refused naming the option.
TEST_F(CliBattery, AListNamesEachItemOnce) {
  const std::regex numbers(R"(^\s+(--[a-z0-9-]+) TEXT:comma-separated, each .*?=([^,\s]+).*$)");
  const std::regex names(R"(^\s+(--[a-z0-9-]+) TEXT:comma-separated list of: all, ([a-z0-9-]+),.*$)");
  std::size_t checked = 0;
  for (const auto& exe : executables()) {
    std::istringstream help(run(path(exe), "--help").out);
    for (std::string l; std::getline(help, l);) {
      std::smatch m;
      std::vector<std::pair<std::string, std::string>> cases;  // value, what the refusal says
      if (std::regex_match(l, m, numbers))
        cases.emplace_back(m[2].str() + "," + m[2].str(), "gives " + m[2].str() + " twice");
      else if (std::regex_match(l, m, names))
        cases = {{m[2].str() + "," + m[2].str(), "names '" + m[2].str() + "' twice"},
                 {m[2].str() + ",all", "lists 'all', which stands alone"}};
      for (const auto& [value, says] : cases) {
        const Outcome r = run(path(exe), base_args(exe) + " " + m[1].str() + " " + value + " --out never");
        EXPECT_EQ(r.code, 2) << exe << " " << m[1] << " " << value << ": " << r.err;
        EXPECT_NE(r.err.find(m[1].str() + ": value '" + value + "' " + says), std::string::npos)
            << exe << " " << m[1] << " " << value << ": " << r.err;
        EXPECT_TRUE(dir_is_empty()) << exe << " wrote files";
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 20u);  // 25 when written: stack's --balls, energy_drift's steps, the method lists, ...
}

// A report cut short is a failure: written to a full disk (/dev/full), every program's help and
// tables were lost and it exited 0, stdout being flushed only at exit. Now exit 1 and a line on
// stderr; a run's results folder is still written whole (only the report was lost).
TEST_F(CliBattery, AReportThatCannotBeWrittenIsAFailure) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "this system has no /dev/full";
  const std::string to_full_disk = "sh -c 'exec \"$0\" \"$@\" >/dev/full'";
  for (const auto& exe : executables()) {
    const Outcome r = run(path(exe), "--help", to_full_disk);
    EXPECT_EQ(r.code, 1) << exe << ": " << r.err;
    EXPECT_NE(r.err.find(exe + ": cannot write its report to standard output"), std::string::npos)
        << exe << ": " << r.err;
  }
  const Outcome run_to_full_disk = run(path("zeno"), "--t-end 1 --out results", to_full_disk);
  EXPECT_EQ(run_to_full_disk.code, 1) << run_to_full_disk.err;
  EXPECT_TRUE(fs::exists(dir_ / "results" / "meta.json"));
  EXPECT_EQ(run(path("zeno"), "--t-end 1 --out results").code, 0);  // and without the full disk, 0
}
