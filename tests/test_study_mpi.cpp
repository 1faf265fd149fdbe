// The study under mpirun: two ranks deal the experiments out between them and write what a serial
// run writes — every CSV the same cell for cell but the wall-time columns, and the same index.
// A sweeping experiment under mpirun deals its own cases out, and writes what it writes alone.
#include "cli_fixture.hpp"

#include <set>

namespace {
class StudyMpi : public CliTest {};

// As root, Open MPI wants both variables; --oversubscribe: more ranks than cores is fine.
constexpr const char* kMpirun =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " MPIEXEC " --oversubscribe -np ";

// Every CSV under `root`, relative path -> rows with the timing (wall-clock and CPU) columns and
// figures left out. A figure's data (NAME-data.csv: gnuplot's blocks, no header) by its records.
std::map<std::string, std::vector<contact::CsvRecord>> tables(const fs::path& root) {
  std::map<std::string, std::vector<contact::CsvRecord>> out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    // Timing figures (stack's cost: CPU time against n) differ between any two runs.
    if (entry.path().extension() != ".csv" || entry.path().filename() == "cost-data.csv") continue;
    const std::string name = entry.path().filename().string();
    std::vector<contact::CsvRecord> rows;
    if (name.ends_with("-data.csv")) {
      for (const auto& record : contact::parse_csv(slurp(entry.path()))) {
        auto& row = rows.emplace_back();
        for (std::size_t i = 0; i < record.size(); ++i) row[std::to_string(i)] = record[i];
      }
    } else {
      rows = contact::read_csv(entry.path());
    }
    for (auto& row : rows)
      std::erase_if(row, [](const auto& cell) {
        return cell.first.find("wall") != std::string::npos || cell.first.find("cpu") != std::string::npos;
      });
    out[fs::relative(entry.path(), root).string()] = rows;
  }
  return out;
}
}  // namespace

TEST_F(StudyMpi, TwoRanksWriteWhatOneProcessWrites) {
  const std::string only = "--tiny --only ball_drop,zeno,k_sweep,contact_laws,method_orders";
  const Outcome serial = run(STUDY_EXE, only + " --out serial");
  ASSERT_EQ(serial.code, 0) << serial.err;
  const Outcome mpi = run(STUDY_EXE, only + " --out mpi", std::string(kMpirun) + "2");
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

// Every sweeping experiment's cases (k_sweep's (law, k), convergence_dt's (integrator, location,
// step), ball_drop --sweep's (k, method), stability_map's (k, scheme, w dt), energy_drift's and
// rigid_impacts' (system, method, setting), method_orders' (method, dt), stack's (n, method),
// rigid_scenes' (scene, method) and newton_cradle's (method, spacing); stack's event-ode failures among them,
// rows whichever rank ran them) dealt over three ranks (uneven shares): the tables are the serial run's, cell
// for cell but CPU times, since each case is the same computation wherever it runs; rank 0 alone writes.
TEST_F(StudyMpi, ASweepsCasesOverRanksGiveTheSerialTables) {
  const std::vector<std::pair<std::string, std::string>> sweeps = {
      {K_SWEEP_EXE, "--k-min 1e3 --k-max 1e5"},
      {CONVERGENCE_DT_EXE, "--integrators rk4,cvode-bdf --halvings 2 --tol-min 1e-5 --heights 2"},
      {BALL_DROP_EXE, "--sweep --k-min 1e3 --k-max 1e5 --per-decade 1 --t-end 1"},
      {STABILITY_MAP_EXE, "--points 7"},
      {ENERGY_DRIFT_EXE, "--bounces 3 --dts 1e-3 --rtols 1e-6 --rigid-dts 1e-4 --rigid-rtols 1e-6"},
      {METHOD_ORDERS_EXE, "--halvings 2"},
      {RIGID_IMPACTS_EXE, "--dts 1e-4 --rtols 1e-6 --scene snooker,wedge"},
      {STACK_EXE, "--balls 1,2 --t-end 0.2 --methods penalty,game-symplectic,event-ode"},
      {RIGID_SCENES_EXE, "--scene snooker,cradle --method penalty,game-symplectic,event-ode"},
      {NEWTON_CRADLE_EXE, "--balls 3 --spacings 0,1e-4"}};
  for (const auto& [exe, args] : sweeps) {
    const std::string name = fs::path(exe).filename().string();
    const Outcome serial = run(exe, args + " --out " + name + "-serial");
    ASSERT_EQ(serial.code, 0) << serial.err;
    const Outcome mpi = run(exe, args + " --out " + name + "-mpi", std::string(kMpirun) + "3");
    ASSERT_EQ(mpi.code, 0) << mpi.err;
    const auto a = tables(dir_ / (name + "-serial")), b = tables(dir_ / (name + "-mpi"));
    ASSERT_GE(a.size(), 2u) << name;
    EXPECT_EQ(a, b) << name;
    EXPECT_NE(slurp(dir_ / (name + "-mpi") / "meta.json").find("\"mpi_ranks\": 3"), std::string::npos);
  }
}

// A case failing on a rank other than 0 fails the whole run once every rank has finished (no
// rank waits forever), with the case's message and exit code (1 failure, 2 bad input), and
// nothing written; without a failure the three ranks' squares arrive in case order.
TEST_F(StudyMpi, ACaseFailingOnAnotherRankFailsTheRun) {
  const std::string mpirun = std::string(kMpirun) + "3";
  const Outcome ok = run(SHARE_PROBE_EXE, "--cases 7 --out ok", mpirun);
  ASSERT_EQ(ok.code, 0) << ok.err;
  const auto rows = contact::read_csv(dir_ / "ok" / "squares.csv");
  ASSERT_EQ(rows.size(), 7u);
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(std::stod(rows[i].at("square")), double(i * i));
  for (const auto& [flags, code] : {std::pair{"--fail 4", 1}, {"--fail 5 --bad-input", 2}}) {
    const Outcome bad = run(SHARE_PROBE_EXE, std::string("--cases 7 --out bad ") + flags, mpirun);
    EXPECT_EQ(bad.code, code) << flags << bad.err;
    EXPECT_NE(bad.err.find("failed on purpose"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad")) << flags;
  }
}
