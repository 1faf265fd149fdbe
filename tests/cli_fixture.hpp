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

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("contact_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `prefix` goes before the program: environment settings, or a wrapper such as timeout.
  Outcome run(const std::string& exe, const std::string& args, const std::string& prefix = "") const {
    const std::string cmd =
        "cd '" + dir_.string() + "' && " + prefix + " '" + exe + "' " + args + " >stdout.txt 2>stderr.txt";
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
};
