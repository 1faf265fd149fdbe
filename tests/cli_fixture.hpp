#pragma once
// A temporary working directory per test and a way to run an experiment executable in it,
// capturing its exit code, stdout and stderr: the experiments' command-line contract is tested
// the way a user meets it.
#include "contact_ode/analysis/table.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

struct Outcome {
  int code;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The cells of each line of a CSV text written by Table::to_csv.
inline std::vector<std::vector<std::string>> csv_rows(const std::string& csv) {
  std::vector<std::vector<std::string>> out;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) out.push_back(contact::split_csv_line(line));
  return out;
}

// The rows of a CSV text (header first) as maps from column to cell.
inline std::vector<std::map<std::string, std::string>> csv_table(const std::string& csv) {
  const auto rows = csv_rows(csv);
  std::vector<std::map<std::string, std::string>> out;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < rows[0].size() && c < rows[r].size(); ++c) row[rows[0][c]] = rows[r][c];
    out.push_back(row);
  }
  return out;
}

// The README shows programs' output as printed. Its text from the line after the first ``` that
// follows `marker` to the closing ```, and the program's output, are compared line by line: a
// "wrote N files" line up to its folder, and in the Markdown table the cells of the columns named
// in `times` (wall times, different on every run) skipped. A sample that the program no longer
// prints fails here.
inline void expect_readme_sample(const std::string& readme, const std::string& marker, const std::string& out,
                                 const std::vector<std::string>& times) {
  const auto at = readme.find(marker);
  ASSERT_NE(at, std::string::npos) << marker;
  const auto start = readme.find('\n', readme.find("```", at)) + 1;
  const std::string sample = readme.substr(start, readme.find("```", start) - start);
  auto lines = [](const std::string& text) {
    std::vector<std::string> v;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      v.push_back(line.rfind("wrote ", 0) == 0 ? line.substr(0, line.find(" to ")) : line);
    return v;
  };
  auto cells = [](const std::string& row) {  // a table row's cells, trimmed
    std::vector<std::string> v;
    std::istringstream in(row);
    for (std::string c; std::getline(in, c, '|');) {
      const auto b = c.find_first_not_of(' '), e = c.find_last_not_of(' ');
      v.push_back(b == std::string::npos ? "" : c.substr(b, e - b + 1));
    }
    return v;
  };
  const auto want = lines(sample), got = lines(out);
  ASSERT_EQ(want.size(), got.size()) << "README sample:\n" << sample << "\nprinted:\n" << out;
  std::vector<std::string> header;
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (want[i].rfind("|", 0) != 0) {
      EXPECT_EQ(want[i], got[i]) << "line " << i + 1;
      continue;
    }
    const auto w = cells(want[i]), g = cells(got[i]);
    if (header.empty()) header = w;
    ASSERT_EQ(w.size(), g.size()) << "line " << i + 1 << ": " << got[i];
    for (std::size_t c = 0; c < w.size(); ++c)
      if (c >= header.size() || std::find(times.begin(), times.end(), header[c]) == times.end()) {
        EXPECT_EQ(w[c], g[c]) << "line " << i + 1 << ", column " << c << ": " << got[i];
      }
  }
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("contact_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Open MPI's session directory, private to the test. Shared (/tmp/ompi.<host>.<uid>), two MPI
    // programs that ctest started at once raced to create it and one failed in MPI_Init ("A call
    // to mkdir was unable to create the desired directory ... File exists": Open MPI issue 8510,
    // a ChainMpi test in CI). Short (mkdtemp in /tmp): PMIx puts sockets in it, whose paths are
    // limited to 107 characters.
    std::string pattern = (fs::temp_directory_path() / "contact_mpi_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr) << pattern;
    mpi_dir_ = pattern;
  }
  void TearDown() override {
    fs::remove_all(dir_);
    // A singleton's Open MPI helper may still be removing its tree when the program has exited:
    // entries vanish under remove_all, which then fails; it is tried again, for at most a second.
    for (int attempt = 0; attempt < 20; ++attempt) {
      std::error_code error;
      fs::remove_all(mpi_dir_, error);
      if (!error) break;
      ::usleep(50'000);
    }
  }

  // `prefix` goes before the program: environment settings, or a wrapper such as timeout.
  Outcome run(const std::string& exe, const std::string& args, const std::string& prefix = "") const {
    const std::string cmd = "cd '" + dir_.string() + "' && OMPI_MCA_orte_tmpdir_base='" + mpi_dir_.string() +
                            "' " + prefix + " '" + exe + "' " + args + " >stdout.txt 2>stderr.txt";
    const int status = std::system(cmd.c_str());
    Outcome r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "stdout.txt"),
              slurp(dir_ / "stderr.txt")};
    fs::remove(dir_ / "stdout.txt");
    fs::remove(dir_ / "stderr.txt");
    return r;
  }
  bool dir_is_empty() const { return fs::is_empty(dir_); }

  // One refused input: the arguments, and what the one-line message must name.
  struct BadInput {
    std::string args, option, value, accepted;
  };
  // Each case: exit code 2, the option, the value and the accepted range named on one line, and
  // nothing written.
  void expect_refused(const std::string& exe, const std::vector<BadInput>& cases) const {
    for (const auto& c : cases) {
      const Outcome r = run(exe, c.args + " --out results");
      EXPECT_EQ(r.code, 2) << c.args;
      EXPECT_NE(r.err.find(c.option), std::string::npos) << c.args << ": " << r.err;
      EXPECT_NE(r.err.find(c.value), std::string::npos) << c.args << ": " << r.err;
      EXPECT_NE(r.err.find(c.accepted), std::string::npos) << c.args << ": " << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": one line, got " << r.err;
      EXPECT_TRUE(dir_is_empty()) << c.args << " wrote files";
    }
  }

  fs::path dir_;
  fs::path mpi_dir_;  // Open MPI's session directory (SetUp)
};
