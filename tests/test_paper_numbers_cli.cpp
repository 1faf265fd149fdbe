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
