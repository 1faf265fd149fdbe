// paper_numbers: refuses a missing results folder, and fails (writing nothing) when a number the
// paper quotes is missing, rather than letting the paper build on a partial study.
#include "cli_fixture.hpp"

namespace {
class PaperNumbersCli : public CliTest {};
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
  fs::create_directories(dir_ / "r" / "k_sweep");
  std::ofstream(dir_ / "r" / "k_sweep" / "exponents.csv") << "law,duration_exponent\nhooke,-0.5\n";
  std::ofstream(dir_ / "r" / "k_sweep" / "meta.json") << R"({"git_revision": "abc", "libraries": {}})";
  std::ofstream(dir_ / "r" / "study.json") << R"({"complete_wall_time_s": 9, "cores": 2, "experiments": []})";
  std::ofstream(dir_ / "list.json")
      << R"({"numbers": [{"macro": "Dur", "file": "k_sweep/exponents.csv", "where": [["law", "hooke"]],)"
      << R"( "column": "duration_exponent"}]})";
  fs::create_directories(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "keep.txt") << "not paper_numbers'\n";
  const Outcome r = run(PAPER_NUMBERS_EXE, "--results r --numbers list.json --out mine/numbers.tex");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "mine" / "keep.txt"), "not paper_numbers'\n");
  EXPECT_NE(slurp(dir_ / "mine" / "numbers.tex").find("\\newcommand{\\Dur}{-0.5}"), std::string::npos);
}
