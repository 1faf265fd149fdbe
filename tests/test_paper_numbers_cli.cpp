// paper_numbers: refuses a missing results folder, and fails (writing nothing) when a number the
// paper quotes is missing, rather than letting the paper build on a partial study.
#include "cli_fixture.hpp"

#include <fmt/format.h>

namespace {
class PaperNumbersCli : public CliTest {
 protected:
  // A minimal study: the run's record and one experiment's meta.json, with `csv` as
  // k_sweep/exponents.csv; `numbers` is the list's entries.
  Outcome run_on(const std::string& csv, const std::string& numbers, const std::string& out) const {
    fs::create_directories(dir_ / "r" / "k_sweep");
    std::ofstream(dir_ / "r" / "k_sweep" / "exponents.csv") << csv;
    std::ofstream(dir_ / "r" / "k_sweep" / "meta.json") << R"({"git_revision": "abc", "libraries": {}})";
    std::ofstream(dir_ / "r" / "study.json")
        << R"({"complete_wall_time_s": 9, "cores": 2, "experiments": []})";
    std::ofstream(dir_ / "list.json") << R"({"numbers": [)" << numbers << "]}";
    return run(PAPER_NUMBERS_EXE, "--results r --numbers list.json --out " + out);
  }
};
}  // namespace

TEST_F(PaperNumbersCli, BadInputIsRefused) {
  expect_refused(PAPER_NUMBERS_EXE, {{"--results nowhere", "--results", "nowhere", "exist"}});
}

TEST_F(PaperNumbersCli, MissingNumberFailsWithoutWriting) {
  fs::create_directories(dir_ / "r" / "k_sweep");
  std::ofstream(dir_ / "r" / "k_sweep" / "exponents.csv") << "law,penetration_exponent\nhooke,-0.5\n";
  const Outcome r = run(PAPER_NUMBERS_EXE, "--results r --out r/paper/numbers.tex");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("k_sweep/exponents.csv: no column 'duration_exponent'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "r" / "paper" / "numbers.tex"));
}

// The macro file is written into its folder beside what that folder holds. paper_numbers used to
// swap in a new folder holding numbers.tex alone in place of --out's folder: `--out /tmp/n.tex`
// deleted everything in /tmp (found so, by running it). A minimal study: one quoted number, the
// run's record and one experiment's meta.json.
TEST_F(PaperNumbersCli, WritesTheFileBesideWhatItsFolderHolds) {
  fs::create_directories(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "keep.txt") << "not paper_numbers'\n";
  const Outcome r = run_on("law,duration_exponent\nhooke,-0.5\n",
                           R"({"macro": "Dur", "file": "k_sweep/exponents.csv", "where": [["law", "hooke"]],)"
                           R"( "column": "duration_exponent"})",
                           "mine/numbers.tex");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "mine" / "keep.txt"), "not paper_numbers'\n");
  EXPECT_NE(slurp(dir_ / "mine" / "numbers.tex").find("\\newcommand{\\Dur}{-0.5}"), std::string::npos);
}

// A number is the first row that matches every condition, or the last with "last" (the finest
// step of a sweep); a condition on a number matches the same number written otherwise (1e-3 and
// 0.001) and no other (1.0000001e-3, a row before it); "scale" and "format" apply; a number in
// scientific notation is typeset as a x 10^b.
TEST_F(PaperNumbersCli, EachMacroIsTheRowItsConditionsName) {
  const auto entry = [](const std::string& macro, const std::string& where, const std::string& extra) {
    return fmt::format(
        R"({{"macro": "{}", "file": "k_sweep/exponents.csv", "where": [{}], "column": "error"{}}})", macro,
        where, extra);
  };
  const std::vector<std::string> numbers = {
      entry("First", R"(["paradigm", "game"])", ""),
      entry("Last", R"(["paradigm", "game"])", R"(, "last": true)"),
      entry("AtDt", R"(["paradigm", "game"], ["dt", "1e-3"])", ""),
      entry("Scaled", R"(["paradigm", "event"])", R"(, "scale": 1e3, "format": "{:.1f}")"),
      entry("Tiny", R"(["paradigm", "event"], ["dt", "2e-3"])", "")};
  const Outcome r = run_on(
      "paradigm,dt,error\ngame,0.0010000001,1\ngame,0.001,2\ngame,1e-4,3\nevent,1e-3,0.25\nevent,0.002,1.5e-"
      "07\n",
      fmt::format("{}", fmt::join(numbers, ", ")), "numbers.tex");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string tex = slurp(dir_ / "numbers.tex");
  for (const char* macro :
       {"\\newcommand{\\First}{1}\n", "\\newcommand{\\Last}{3}\n", "\\newcommand{\\AtDt}{2}\n",
        "\\newcommand{\\Scaled}{250.0}\n", "\\newcommand{\\Tiny}{\\ensuremath{1.5\\times10^{-7}}}\n"})
    EXPECT_NE(tex.find(macro), std::string::npos) << macro << " not in\n" << tex;
}
