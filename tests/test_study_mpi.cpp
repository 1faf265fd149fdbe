// The study under mpirun: two ranks deal the experiments out between them and write what a serial
// run writes — every CSV the same cell for cell but the wall-time columns, and the same index.
#include "cli_fixture.hpp"

#include <set>

namespace {
class StudyMpi : public CliTest {};

// Every CSV under `root`, relative path -> rows with the wall-clock columns left out.
std::map<std::string, std::vector<contact::CsvRecord>> tables(const fs::path& root) {
  std::map<std::string, std::vector<contact::CsvRecord>> out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".csv") continue;
    auto rows = contact::read_csv(entry.path());
    for (auto& row : rows)
      std::erase_if(row, [](const auto& cell) { return cell.first.find("wall") != std::string::npos; });
    out[fs::relative(entry.path(), root).string()] = rows;
  }
  return out;
}
}  // namespace

TEST_F(StudyMpi, TwoRanksWriteWhatOneProcessWrites) {
  const std::string only = "--tiny --only ball_drop,zeno,k_sweep,contact_laws,method_orders";
  const Outcome serial = run(STUDY_EXE, only + " --out serial");
  ASSERT_EQ(serial.code, 0) << serial.err;
  // As root, Open MPI wants both variables; --oversubscribe: more ranks than cores is fine.
  const Outcome mpi =
      run(STUDY_EXE, only + " --out mpi",
          "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " MPIEXEC " --oversubscribe -np 2");
  ASSERT_EQ(mpi.code, 0) << mpi.err;
  const auto a = tables(dir_ / "serial"), b = tables(dir_ / "mpi");
  ASSERT_GE(a.size(), 10u);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [file, rows] : a) {
    ASSERT_TRUE(b.count(file)) << file;
    EXPECT_EQ(rows, b.at(file)) << file;
  }
  // The index lists the same experiments in the same order; only its total time differs.
  auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (line.find("of wall time") == std::string::npos) out.push_back(line);
    return out;
  };
  EXPECT_EQ(lines(slurp(dir_ / "serial" / "index.md")), lines(slurp(dir_ / "mpi" / "index.md")));
  EXPECT_NE(slurp(dir_ / "mpi" / "study.json").find("\"ranks\": 2"), std::string::npos);
}
