// The N-ball chain distributed over MPI ranks (chain_mpi): one rank and two ranks solve the same
// ODE as the serial CVODE with the band solver (switches unlocated, as the distributed run),
// each to its tolerance: rtol 1e-8 gives solutions 2e-7 m/s apart after the pulse has crossed
// 50 balls (measured between 1 and 2 ranks); 1e-5 allows for the error's growth along the
// chain's 150 contacts. Momentum is exact whatever the partition (each contact's forces are equal
// and opposite, summed on whichever rank holds each ball).
#include "cli_fixture.hpp"
#include "contact_ode/analysis/references.hpp"
#include "contact_ode/integrators/penalty.hpp"
#include "contact_ode/models/ball_chain.hpp"
#include "contact_ode/models/scene_registry.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {
class ChainMpi : public CliTest {
 protected:
  std::vector<double> velocities(int ranks) const {
    const std::string out = "np" + std::to_string(ranks);
    const Outcome r =
        run(CHAIN_MPI_EXE, "--balls 50 --t-end 0 --out " + out,
            "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " MPIEXEC " --oversubscribe -np " +
                std::to_string(ranks));
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<double> v;
    for (const auto& row : contact::read_csv(dir_ / out / "velocities.csv"))
      v.push_back(std::stod(row.at("v_mps")));
    // Energy is conserved by the undamped chain: rtol 1e-8 over 150 contacts keeps it to 1e-6
    // (measured 9e-8), what the tolerance allows with room for the error's growth along the chain.
    EXPECT_LT(std::abs(energy_error(out)), 1e-6) << ranks;
    return v;
  }
  double energy_error(const std::string& out) const {
    return std::stod(contact::read_csv(dir_ / out / "stats.csv").at(0).at("energy_error_rel"));
  }
};
}  // namespace

// chain_mpi replaced any folder holding a stats.csv, which ball_drop's results hold too. It now
// leaves a meta.json naming itself, replaces a folder only when that names it, and refuses
// another program's results (here a zeno run's), naming both.
TEST_F(ChainMpi, ReplacesOnlyItsOwnResults) {
  for (int i = 0; i < 2; ++i) {
    const Outcome r = run(CHAIN_MPI_EXE, "--balls 4 --out c");
    ASSERT_EQ(r.code, 0) << r.err;
  }
  EXPECT_NE(slurp(dir_ / "c" / "meta.json").find("\"experiment\": \"chain_mpi\""), std::string::npos);
  std::filesystem::create_directories(dir_ / "z");
  std::ofstream(dir_ / "z" / "meta.json") << R"({"experiment": "zeno"})";
  std::ofstream(dir_ / "z" / "stats.csv") << "kept\n";
  const Outcome r = run(CHAIN_MPI_EXE, "--balls 4 --out z");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("holds the results of zeno (its meta.json says so), not of chain_mpi"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(dir_ / "z" / "stats.csv"), "kept\n");
}

// A tolerance that allows anything (atol 1e300: every step passes the error test) gave a
// "successful" run with any answer, its energy 1e11 times E0 (the stats' energy error said what it
// was worth); such a gain ends a run as diverged now (RunRecorder), and no output is written.
TEST_F(ChainMpi, ATolerancePermittingAnyAnswerEndsDiverged) {
  const Outcome r =
      run(CHAIN_MPI_EXE, "--balls 4 --atol 1e300 --out loose",
          "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " MPIEXEC " --oversubscribe -np 2");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("diverged"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("energy"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "loose" / "stats.csv"));
}

// Rank 0 alone records the samples: a failure of its recorder (here its first sample, past the
// run's sample bound) returned on rank 0 while the other ranks went on into the integrator's next
// reduction and waited there for ever (chain_mpi samples at t = 0 and t_end only, and mpiexec ends
// a job whose rank 0 exits non-zero, so only a library caller met it). Every rank now returns the
// same status at the same time.
TEST_F(ChainMpi, ARecorderFailureOnRankZeroEndsTheRunOnEveryRank) {
  const Outcome r = run(DISTRIBUTED_PROBE_EXE, "",
                        "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 60 " MPIEXEC
                        " --oversubscribe -np 2");
  ASSERT_EQ(r.code, 0) << r.err;  // 124: a rank waited until the timeout
  EXPECT_NE(r.out.find("rank 0: work-limit at t = 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rank 1: work-limit at t = 0"), std::string::npos) << r.out;
}

// The default span was the pulse through the whole chain, which grows with the chain (three pair
// contacts per ball), so its cost grew as N^2: the README's `--balls 100000` ran to t = 210 s,
// days on two cores (0.05 s takes 93 s). It is now the ball-chain scene's span, as every other
// entry point runs that scene, whatever the number of balls; 0 still asks for the pulse through
// the chain (the test above).
TEST_F(ChainMpi, ByDefaultAnyChainRunsTheScenesSpan) {
  for (const int balls : {4, 300}) {
    const std::string out = "span" + std::to_string(balls);
    ASSERT_EQ(run(CHAIN_MPI_EXE, "--balls " + std::to_string(balls) + " --out " + out).code, 0);
    EXPECT_EQ(std::stod(contact::read_csv(dir_ / out / "stats.csv").at(0).at("t_end_s")),
              contact::ball_chain_scene().t_end)
        << balls;
  }
}

// Every program a test runs is told to keep Open MPI's session directory in the test's own (an
// MPI program, even a singleton, creates one in MPI_Init): two tests' programs started at once
// raced for the shared one under ctest -j2 and one failed (ToleranceOutOfRangeIsRefused in CI:
// "A call to mkdir was unable to create the desired directory ... File exists").
TEST_F(ChainMpi, EachTestKeepsOpenMpisSessionDirectoryToItself) {
  const Outcome r = run("sh", "-c 'printf %s \"$OMPI_MCA_orte_tmpdir_base\"'");
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(r.out, mpi_dir_.string());
  EXPECT_TRUE(fs::is_directory(r.out)) << r.out;
  EXPECT_EQ(run(CHAIN_MPI_EXE, "--balls 4 --t-end 0 --out tiny").code, 0);
}

// --rtol took [0, 1], where every other experiment takes (0, 1): rtol 1 'succeeded' with an
// energy error of 7e73 and rtol 0 ran for minutes. Refused like the others' (a bad input, serial).
TEST_F(ChainMpi, ToleranceOutOfRangeIsRefused) {
  expect_refused(CHAIN_MPI_EXE,
                 {{"--rtol 1", "--rtol", "'1'", "(0, 1)"}, {"--rtol 0", "--rtol", "'0'", "(0, 1)"}});
}

// Every rank parses the command line, and every rank printed the help (three times on three
// ranks) and a refusal (as many times as ranks got to it before mpiexec ended the job). Rank 0
// alone prints them now; the exit codes are as before.
TEST_F(ChainMpi, OneRankSpeaksForAllOfThemAboutTheCommandLine) {
  const auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  const std::string three = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 60 " MPIEXEC
                            " --oversubscribe -np 3";
  const Outcome help = run(CHAIN_MPI_EXE, "--help", three);
  EXPECT_EQ(help.code, 0) << help.err;
  EXPECT_EQ(count(help.out, "Usage: chain_mpi"), 1u) << help.out;
  const Outcome refused = run(CHAIN_MPI_EXE, "--balls 1 --out none", three);
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_EQ(count(refused.err, "chain_mpi: --balls: value '1' is not a whole number in [2, 100000000]"), 1u)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "none"));
}

TEST_F(ChainMpi, OneAndTwoRanksAgreeWithTheSerialBandSolver) {
  using namespace contact;
  const BallChainParams p{.n = 50, .law = Hooke{1e6}};
  const double t_end = p.approach / p.v0 + 3.0 * 50 * hooke_contact(p.m / 2, 1e6, p.v0, 0.0).duration;
  PenaltyOptions serial{.locate_switches = false};
  serial.integrator.rtol = 1e-8;
  serial.integrator.atol = 1e-12;
  serial.integrator.max_steps = 10'000'000;
  serial.integrator.linear_solver = LinearSolverKind::Band;
  const RunResult ref = run_penalty(BallChain(p), serial, {.t_end = t_end, .sample_dt = t_end});
  ASSERT_TRUE(ref.ok()) << ref.message;
  const auto one = velocities(1), two = velocities(2);
  ASSERT_EQ(one.size(), 50u);
  ASSERT_EQ(two.size(), 50u);
  double momentum1 = 0, momentum2 = 0;
  for (std::size_t b = 0; b < 50; ++b) {
    const double v = ref.samples.back().y[static_cast<Eigen::Index>(2 * b + 1)];
    EXPECT_NEAR(one[b], v, 1e-5) << b;
    EXPECT_NEAR(two[b], v, 1e-5) << b;
    momentum1 += one[b];
    momentum2 += two[b];
  }
  EXPECT_NEAR(momentum1, 1.0, 1e-9);
  EXPECT_NEAR(momentum2, 1.0, 1e-9);
  // The pulse has dispersed along the chain: the result is not the trivial exchange.
  EXPECT_GT(std::abs(one[0]), 1e-2);
}

// --out is replaced whole, so it is checked first like every experiment's: a folder holding
// anything but an earlier run's results (stats.csv) is refused, and what it holds stays. It was
// replaced unchecked: `chain_mpi --out .` deleted the current folder's files.
TEST_F(ChainMpi, AnOutFolderOfOtherFilesIsRefusedAndKept) {
  fs::create_directories(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "keep.txt") << "kept\n";
  const Outcome r = run(CHAIN_MPI_EXE, "--balls 4 --out mine");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--out: value 'mine'"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "mine" / "keep.txt"), "kept\n");
  // An earlier run's folder is replaced, as before.
  ASSERT_EQ(run(CHAIN_MPI_EXE, "--balls 4 --out fresh").code, 0);
  EXPECT_EQ(run(CHAIN_MPI_EXE, "--balls 4 --out fresh").code, 0);
}

// A solver failure names the time CVODE reached and CVODE's own message. At k = 1e-300 the balls
// pass through one another (the springs are nothing) and CVODE's error test fails at t ~ 3e122 s;
// the run said "at t = 0 s" (the time was read before CVode set it) with only CVODE's flag name,
// while CVODE printed its message raw on stderr.
TEST_F(ChainMpi, ASolverFailureNamesTheTimeReachedAndCvodesMessage) {
  const Outcome r = run(CHAIN_MPI_EXE, "--balls 10 --k 1e-300 --t-end 0 --out soft");
  ASSERT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(r.err.find("[CVODE ERROR]"), std::string::npos) << r.err;
  const auto ours = r.err.find("at t = "), cvodes = r.err.find("At t = ");
  ASSERT_NE(ours, std::string::npos) << r.err;
  ASSERT_NE(cvodes, std::string::npos) << r.err;
  const double reached = std::stod(r.err.substr(ours + 7)), cvode_t = std::stod(r.err.substr(cvodes + 7));
  EXPECT_GT(reached, 0.0) << r.err;
  EXPECT_NEAR(reached, cvode_t, 1e-5 * cvode_t) << r.err;  // CVODE prints six digits
  EXPECT_FALSE(fs::exists(dir_ / "soft"));
}

// SIGINT stops the run within a few steps: exit 130, nothing written. The whole run was one
// CVode call that looked at no interrupt (a 1000-ball run went on for its 26 s; at k = 1e-300,
// for hours of steps that no longer advanced t); the outer KILL after 20 s bounds the test.
TEST_F(ChainMpi, AnInterruptStopsTheRunWithinAFewSteps) {
  const Outcome r = run(CHAIN_MPI_EXE, "--balls 1000 --t-end 0 --out stopped",
                        "timeout -s KILL 20 timeout --preserve-status -s INT 1");
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_NE(r.err.find("interrupted"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "stopped"));
}

// A chain that cannot fit in the machine's memory is refused before the run starts: 1e8 balls on
// one rank needs ~1.5e11 bytes (about 1.5 kB per ball) and filled this 24 GB machine until the kernel
// killed it. (A machine of over 160 GB would run it: skipped there.)
TEST_F(ChainMpi, AChainBeyondTheMachinesMemoryIsRefusedFirst) {
  if (static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE)) > 1.6e11)
    GTEST_SKIP() << "this machine has the memory for 1e8 balls";
  const Outcome r = run(CHAIN_MPI_EXE, "--balls 100000000 --out huge");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--balls: value '100000000' needs about 1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("GB of memory where a process may use"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "huge"));
}

namespace {
// The significant digits a number is printed with ("0.0002600" and "1.235e+05": 4).
std::size_t significant_digits(const std::string& shown) {
  std::string digits;
  for (char c : shown.substr(0, shown.find_first_of("eE")))
    if (std::isdigit(static_cast<unsigned char>(c)) && (c != '0' || !digits.empty())) digits += c;
  return digits.size();
}
}  // namespace

// benchmarks/scaling_mpi.sh read the solve's wall time as stats.csv's last column; once
// energy_error_rel followed it, SCALING.md's table held -0.0000 s and -nan efficiencies. A small
// chain, once per case: every median a positive time, every efficiency a positive number. The
// medians were printed to 4 decimals, a 0.26 ms solve as 0.0003 (one digit, the efficiencies
// computed from those), and the efficiencies to 2, a two-rank solve slowed by a loaded machine
// to 0.0025 as 0.00 (the test's old flake): the medians carry 4 significant digits, the
// efficiencies 3, and each efficiency is the one its row's and the one-rank row's medians give,
// to 5e-3 of it for its rounding and 1.1e-3 for theirs (each median to half a unit of its
// fourth digit, 5e-4 of it; a ratio of two to 1.0005e-3).
TEST_F(ChainMpi, TheScalingScriptTabulatesTheSolvesWallTime) {
  const std::string build = std::filesystem::path(CHAIN_MPI_EXE).parent_path().parent_path().string();
  const Outcome r = run("bash", "'" + std::string(SCALING_SCRIPT) + "' '" + build + "' scaling.md",
                        "REPEATS=1 N=200 N_PER_RANK=100 T_END=0.002");
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream md(dir_ / "scaling.md");
  int rows = 0;
  double one_rank = 0;  // the kind's one-rank median, the row before its others
  for (std::string line; std::getline(md, line);) {
    if (line.rfind("| strong |", 0) != 0 && line.rfind("| weak |", 0) != 0) continue;
    ++rows;
    std::vector<std::string> cells;  // "", kind, ranks, balls, time, efficiency, ""
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 6u) << line;
    const double median = std::stod(cells[4]);
    EXPECT_GT(median, 0.0) << line;
    EXPECT_EQ(significant_digits(cells[4]), 4u) << line;
    EXPECT_EQ(significant_digits(cells[5]), 3u) << line;
    const double efficiency = std::stod(cells[5]);
    EXPECT_TRUE(std::isfinite(efficiency) && efficiency > 0) << line;
    const int ranks = std::stoi(cells[2]);
    if (ranks == 1) one_rank = median;
    const double expected = cells[1] == " strong " ? one_rank / (ranks * median) : one_rank / median;
    EXPECT_NEAR(efficiency, expected, 6.1e-3 * expected) << line;
  }
  EXPECT_EQ(rows, 4);  // strong and weak, on one rank and two
}
