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
  // --out is a file: a folder, or a path ending in '/', was written at ("cannot write d/: Success",
  // exit 1: the rename's error lost to the clean-up's).
  fs::create_directories(dir_ / "r" / "k_sweep");
  fs::create_directories(dir_ / "folder");
  for (const std::string out : {"folder", "new/", "''"}) {
    const Outcome r = run(PAPER_NUMBERS_EXE, "--results r --out " + out);
    EXPECT_EQ(r.code, 2) << out;
    EXPECT_NE(r.err.find("paper_numbers: --out: value '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("accepted: the path of a file"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "new")) << out;
  }
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

// The list is checked whole before any result is read, and an entry that is not one is refused
// (exit 2) naming it, its key, the value and what is accepted, with nothing written. An empty
// [column, value] pair used to be read past its end (a segfault); a number for a value, a format
// that cannot print a number or a missing key ended in a library's bare exception (exit 1); a macro
// with a digit, one defined twice, or a format with LaTeX's % wrote a file the paper cannot build.
TEST_F(PaperNumbersCli, AnEntryThatIsNotOneIsRefusedBeforeAnyResultIsRead) {
  const auto entry = [](const std::string& fields) {
    return fmt::format(
        R"({{"macro": "Dur", "file": "k_sweep/exponents.csv", "column": "duration_exponent", {}}})", fields);
  };
  const std::string hooke = R"("where": [["law", "hooke"]])";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {entry(R"("where": [["law", "hooke"], []])"), "entry 1 ('Dur'): where: value [[\"law\",\"hooke\"],[]]"},
      {entry(R"("where": [["law", 1]])"),
       "entry 1 ('Dur'): where: value [[\"law\",1]] is not accepted; accepted: "
       "a list of [column, value] string pairs"},
      {entry(hooke + R"(, "format": "{:d}")"), "entry 1 ('Dur'): format: value '{:d}' cannot print a number"},
      {entry(hooke + R"(, "format": "{:.1f}%")"),
       "format: value '{:.1f}%' prints '1.0%', which LaTeX cannot typeset as it is"},
      {entry(hooke + R"(, "scale": "1e3")"),
       "scale: value \"1e3\" is not accepted; accepted: a finite number"},
      {entry(hooke + R"(, "last": "yes")"), "last: value \"yes\" is not accepted; accepted: true or false"},
      {entry(hooke + R"(, "formt": "{:.2f}")"), "key 'formt' is not known; accepted: macro, file, where"},
      {R"({"macro": "Dur", "file": "k_sweep/exponents.csv", "where": []})",
       "entry 1 ('Dur'): column: missing"},
      {entry(R"("last": true)"), "entry 1 ('Dur'): where: missing"},
      {entry(hooke) + ", " + entry(hooke), "entry 2 ('Dur'): macro: defined by an entry before it"},
      {R"({"macro": "Dur2", "file": "k_sweep/exponents.csv", "where": [], "column": "x"})",
       "macro: value 'Dur2' is not accepted; accepted: letters only"},
      {R"({"macro": "Dur", "file": "../exponents.csv", "where": [], "column": "x"})",
       "file: value '../exponents.csv' is not accepted; accepted: a relative path under the results folder"},
      {"1", "entry 1 (''): is not an object"},
      {"{", "list.json' is not JSON: [json.exception.parse_error.101] parse error at line 1"}};
  for (const auto& [numbers, message] : cases) {
    const Outcome r = run_on("law,duration_exponent\nhooke,-0.5\n", numbers, "numbers.tex");
    EXPECT_EQ(r.code, 2) << numbers;
    EXPECT_NE(r.err.find("paper_numbers: --numbers: '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << numbers << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "numbers.tex")) << numbers;
  }
}

// A quoted cell that is empty, NaN or infinite is a failed run's, not a number for the paper: the
// run fails naming the file, the row and the cell, writing nothing (NaN used to be printed as
// "nan"). A text cell is quoted as text, LaTeX's specials escaped (one with an e used to be read
// as a mantissa and exponent, and failed with "stoi").
TEST_F(PaperNumbersCli, ACellThatIsNotAFiniteNumberFailsTheRun) {
  const std::string entry =
      R"({"macro": "Dur", "file": "k_sweep/exponents.csv", "where": [["law", "hooke"]], "column": "d")";
  for (const std::string cell : {"nan", "", "inf", "-0.5x"}) {
    const Outcome r =
        run_on("law,d\nhooke," + cell + "\n", entry + R"(, "format": "{:.3f}"})", "numbers.tex");
    EXPECT_EQ(r.code, 1) << cell;
    EXPECT_NE(r.err.find("k_sweep/exponents.csv: column 'd' on the row with law=hooke holds '" + cell +
                         "', not a finite number"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "numbers.tex")) << cell;
  }
  const Outcome text = run_on("law,d\nhooke,event_exact & 10%\n", entry + "}", "numbers.tex");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(slurp(dir_ / "numbers.tex").find("\\newcommand{\\Dur}{event\\_exact \\& 10\\%}\n"),
            std::string::npos)
      << slurp(dir_ / "numbers.tex");
}
