// The commands an independent audit found hanging, crashing or answering wrong, each as a user
// types it: now each ends with the exit code and message the contract promises.
#include "cli_fixture.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <set>
#include <thread>

#include <unistd.h>

namespace {

class TrustCli : public CliTest {
 protected:
  static std::string exe(const std::string& name) { return (fs::path(EXPERIMENTS_DIR) / name).string(); }
  // No folder or file of a run left in the test folder but `keep`.
  void expect_only(const std::set<std::string>& keep) const {
    for (const auto& e : fs::directory_iterator(dir_))
      EXPECT_TRUE(keep.count(e.path().filename().string())) << "left behind: " << e.path();
  }
};

// A study manifest (manifest.json) of two shell scripts, "first" started before "second"; each
// writes its folder with a meta.json after `before` (first: the whole script, when given).
void write_shell_study(const fs::path& dir, const std::string& first, const std::string& before) {
  const std::string writes = "mkdir -p $1 && echo '{}' > $1/meta.json";
  const auto entry = [](const char* name, double cpu_s, const std::string& script) {
    return fmt::format(
        R"({{"name": "{}", "exe": "/bin/sh", "cpu_s": {}, "summary": "s", "outputs": {{}}, "tiny": [], "args": ["-c", "{}"]}})",
        name, cpu_s, script);
  };
  std::ofstream(dir / "manifest.json")
      << fmt::format(R"({{"title": "t", "experiments": [{}, {}]}})",
                     entry("first", 2, first.empty() ? writes : first), entry("second", 1, before + writes));
}
}  // namespace

// t_end / dt = 1e20 steps overflowed to 0 and reported success.
TEST_F(TrustCli, AStepCountBeyondTheRunLimitFailsTyped) {
  const Outcome r = run(exe("ball_drop"), "--method game-euler --t-end 1e4 --dt 1e-16 --out res");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("work-limit"), std::string::npos) << r.err;
  expect_only({});
}

// A 1e-9 m drop: with the tolerance scaled to it the elastic ball keeps its energy; with the
// study's 1e-10 m its bounces are unresolved and the run fails instead of losing 99 % of it.
TEST_F(TrustCli, ATinyDropIsResolvedOrRefusedNeverWrong) {
  Outcome r = run(exe("ball_drop"), "--method event-ode --e 1 --h0 1e-9 --t-end 1e-3 --out res");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = csv_rows(slurp(dir_ / "res" / "comparison.csv"));
  ASSERT_EQ(rows.size(), 2u);
  // max_energy_change_rel: CVODE at rtol 1e-8 over ~70 bounces keeps it to ~1e-6.
  EXPECT_LT(std::stod(rows[1][7]), 1e-5) << rows[1][7];
  r = run(exe("ball_drop"), "--method event-ode --e 1 --h0 1e-9 --atol 1e-10 --out res2");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unresolved"), std::string::npos) << r.err;
}

// A resting game ball used to add a record per frame (1e7 for 1e4 s, then bad_alloc).
TEST_F(TrustCli, ARestingGameBallIsOneRecord) {
  const Outcome r = run(exe("ball_drop"), "--method game-symplectic --t-end 1e4 --sample-dt 100 --out res");
  ASSERT_EQ(r.code, 0) << r.err;
  // ~22 bounces, then one resting contact (test_run_bounds derives the count).
  EXPECT_LT(csv_rows(slurp(dir_ / "res" / "contacts.csv")).size(), 40u);
}

TEST_F(TrustCli, CrashesAreNowMessages) {
  // Norm overflow: a quaternion of 1e200s is a fine orientation.
  Outcome r = run(exe("rigid_scenes"), "--quaternion 1e200 1e200 1e200 1e200 --scene off-centre --out rs");
  EXPECT_EQ(r.code, 0) << r.err;
  // A soft cradle spring: contacts of pi sqrt((m/2) / k) = pi sqrt(0.05 / 1e-3) = 22.2 s at a 1 us
  // step; used to run out of memory, then failed at the work limit when its turn came. Refused now
  // before the first run, with the step it needs: the widest gaps' runs span 1110.74 s (ten such
  // contacts per ball for five balls, and 1.5 cm of approach and gaps at 1 m/s), in 10 sweeps a step
  // for sequential impulses, so dt >= 1110.74 * 10 / 1e8 steps = 1.11e-4 s, rounded up as printed.
  r = run(exe("newton_cradle"), "--k 1e-3 --out nc");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--dt: value '1e-06'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("accepted --dt >= 0.000112"), std::string::npos) << r.err;
  // A dense 2e5 x 2e5 matrix: SUNDenseMatrix returned NULL, which was dereferenced (the refusal of
  // such a matrix is tested on solve(), RunBounds.ADenseJacobianBeyondFourGibIsAWorkLimit). The chain's size
  // is bounded now: 1e8 balls filled the machine's memory before that refusal was reached.
  r = run(exe("work_precision"), "--balls 100000 --problems chain --integrators cvode-bdf --out wp");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--balls: value '100000'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[2, 50]"), std::string::npos) << r.err;
  expect_only({"rs"});
}

TEST_F(TrustCli, MessagesNameTheRealCause) {
  // The advisor has no --atol: extreme inputs are refused in terms of its own options.
  Outcome r = run(exe("contact_advisor"), "--max-penetration 1e300 --out ca");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.find("--atol"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-penetration"), std::string::npos) << r.err;
  // Too few penalty bounces for --bounces 10 were reported as "k = 1000: success", then as an exit
  // 1. The penalty runs now take the span their slower bounces need, and at k = 1e3 a bounce's
  // restitution falls with its speed (gravity's share g / (w V) grows) until the spring holds the
  // ball for good: that row says in which contact, before the tenth apex; the stiffer rows compare.
  r = run(exe("convergence_k"), "--bounces 10 --out ck");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto ten = csv_rows(slurp(dir_ / "ck" / "convergence_k.csv"));
  ASSERT_EQ(ten.size(), 1 + 7u);
  EXPECT_EQ(ten[1].back().rfind("held in contact ", 0), 0u) << ten[1].back();
  for (std::size_t j = 2; j < ten.size(); ++j) EXPECT_EQ(ten[j].back(), "ok") << ten[j][0];
  // A k range narrower than a point per decade used to divide by zero (k = NaN).
  r = run(exe("convergence_k"), "--k-min 1e5 --k-max 1.0001e5 --out ck2");
  EXPECT_EQ(r.code, 0) << r.err;
  const auto k_rows = csv_rows(slurp(dir_ / "ck2" / "convergence_k.csv"));
  ASSERT_EQ(k_rows.size(), 3u);  // the header and both ends
  for (std::size_t j = 1; j < k_rows.size(); ++j)
    EXPECT_TRUE(std::isfinite(std::stod(k_rows[j][0]))) << k_rows[j][0];
  // A sweep into unstable territory says which runs failed.
  r = run(exe("ball_drop"), "--sweep --k-min 1e10 --k-max 1e16 --out sw");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("game-euler-spring: diverged"), std::string::npos) << r.err;
  // Empty list items are refused; meta.json keeps the whole list.
  r = run(exe("ball_drop"), "--method penalty, --out l1");
  EXPECT_EQ(r.code, 2) << r.err;
  r = run(exe("newton_cradle"), "--spacings 0,,1e-3 --out l2");
  EXPECT_EQ(r.code, 2) << r.err;
  r = run(exe("newton_cradle"), "--balls 3 --spacings 0,1e-3 --out l3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(dir_ / "l3" / "meta.json").find("\"spacings\": \"0,1e-3\""), std::string::npos);
}

// --out is replaced whole when it holds an earlier run, and any program's meta.json passed for one:
// ball_drop --out into zeno's results replaced them. Refused now, naming both programs; zeno's
// own next run still replaces its folder (chain_mpi's: ChainMpi.ReplacesOnlyItsOwnResults).
TEST_F(TrustCli, AProgramNeverReplacesAnotherProgramsResults) {
  Outcome r = run(exe("zeno"), "--t-end 1 --out z");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string zeno_meta = slurp(dir_ / "z" / "meta.json");
  r = run(exe("ball_drop"), "--t-end 0.1 --out z");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(
      r.err.find("--out: value 'z' holds the results of zeno (its meta.json says so), not of ball_drop"),
      std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(dir_ / "z" / "meta.json"), zeno_meta);
  EXPECT_TRUE(fs::exists(dir_ / "z" / "zeno.csv"));
  r = run(exe("zeno"), "--t-end 1 --out z");
  EXPECT_EQ(r.code, 0) << r.err;
}

// gnuplot ran through a shell with the scratch path in quotes.
TEST_F(TrustCli, AQuoteInTmpdirDoesNotBreakTheFigures) {
  fs::create_directories(dir_ / "it's");
  const Outcome r = run(exe("zeno"), "--out z", "TMPDIR=\"$PWD/it's\"");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "z" / "heights.png"));
  EXPECT_TRUE(fs::is_empty(dir_ / "it's")) << "scratch folders left behind";
}

// A TMPDIR where no scratch folder can be made (missing, or a file) is bad input, refused before any
// work with its value: it used to surface after the whole run, when the figures were drawn, as
// "filesystem error: temp_directory_path: No such file or directory" (exit 1).
TEST_F(TrustCli, AnUnusableTmpdirIsRefusedBeforeAnyWork) {
  std::ofstream(dir_ / "a_file") << "x";
  for (const char* tmpdir : {"missing", "a_file"}) {
    for (const char* program : {"zeno", "study"}) {
      const Outcome r = run(exe(program), "--out res", fmt::format("TMPDIR=\"$PWD/{}\"", tmpdir));
      EXPECT_EQ(r.code, 2) << program << " " << tmpdir << ": " << r.err;
      EXPECT_NE(
          r.err.find(fmt::format("{}: TMPDIR: value '{}/{}' is not a folder where a scratch folder can be "
                                 "made (",
                                 program, dir_.string(), tmpdir)),
          std::string::npos)
          << r.err;
      EXPECT_NE(r.err.find("accepted: an existing, writable folder"), std::string::npos) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_EQ(r.out, "") << program << ": it ran before refusing";
    }
  }
  expect_only({"a_file"});
}

// A name that is not UTF-8 (Latin-1's "é", the byte 0xE9: a Linux path is bytes) in --out or in
// the program's own path (a build in such a folder): the run did all its work and then failed
// writing meta.json ("[json.exception.type_error.316] invalid UTF-8 byte", exit 1). meta.json
// records the byte as U+FFFD now, and the study gathers its experiments' records the same way.
TEST_F(TrustCli, ANameThatIsNotUtf8IsWrittenAndRecorded) {
  const std::string latin1_e = "\xE9", replacement = "\xEF\xBF\xBD";
  const fs::path bin = dir_ / ("bin" + latin1_e);
  fs::create_directory_symlink(EXPERIMENTS_DIR, bin);
  Outcome r = run((bin / "zeno").string(), "--out \"$(printf 'caf\\351')\"");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto meta = nlohmann::json::parse(slurp(dir_ / ("caf" + latin1_e) / "meta.json"));
  EXPECT_EQ(meta["options"]["out"], "caf" + replacement);
  EXPECT_EQ(meta["command_line"][0], (dir_ / ("bin" + replacement) / "zeno").string());

  r = run((bin / "study").string(), "--tiny --only zeno --out \"$(printf 's\\351')\"");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto study = nlohmann::json::parse(slurp(dir_ / ("s" + latin1_e) / "study.json"));
  EXPECT_NE(study["experiments"][0]["command"].get<std::string>().find("--out s" + replacement + "/zeno"),
            std::string::npos)
      << study.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

// SIGINT or SIGTERM: exit 128 + N, no output, no staging or scratch folder left; a study keeps the
// results of an earlier run of an experiment it did not get to.
TEST_F(TrustCli, InterruptsLeaveNothingBehindAndKeepEarlierResults) {
  fs::create_directories(dir_ / "tmp");
  for (const char* sig : {"INT", "TERM"}) {
    const std::string out = fmt::format("res_{}", sig);
    const Outcome r = run(exe("ball_drop"), "--sweep --per-decade 40 --out " + out,
                          fmt::format("TMPDIR=\"$PWD/tmp\" timeout --preserve-status -s {} 0.5", sig));
    EXPECT_EQ(r.code, std::string(sig) == "INT" ? 130 : 143) << sig << ": " << r.err;
    EXPECT_NE(r.err.find("interrupted"), std::string::npos) << r.err;
  }
  EXPECT_TRUE(fs::is_empty(dir_ / "tmp")) << "gnuplot scratch folders left behind";
  expect_only({"tmp"});

  Outcome r = run(exe("study"), "--tiny --only newton_cradle --out res");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string before = slurp(dir_ / "res" / "newton_cradle" / "meta.json");
  // One job at a time, so that convergence_dt (~3 s of CPU, before newton_cradle in the schedule)
  // is running when the signal comes and newton_cradle is not begun; with a job per core both
  // started together, and newton_cradle (0.5 s) could finish first and rightly replace its results.
  r = run(exe("study"), "--jobs 1 --only convergence_dt,newton_cradle --out res",
          "timeout --preserve-status -s INT 1");
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_NE(r.err.find("study: interrupted; no experiment had finished; the others keep their earlier "
                       "results; index.md not written"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(dir_ / "res" / "newton_cradle" / "meta.json"), before)
      << "the earlier results were touched";
  EXPECT_FALSE(fs::exists(dir_ / "res" / "convergence_dt")) << "an interrupted experiment left a folder";
  for (const auto& e : fs::directory_iterator(dir_ / "res"))
    EXPECT_EQ(e.path().filename().string().find(".staging"), std::string::npos) << e.path();
}

// Ctrl-C on a terminal signals the whole foreground group: the study and the experiment it runs
// (here the study leads a group of its own, from setsid(1), and the group is signalled). The experiment
// got it twice, from the terminal and passed on by the study, took the copy for a second Ctrl-C
// and stopped at once ("convergence_dt: a second interrupt"), leaving its staging folder.
TEST_F(TrustCli, CtrlCOnATerminalStopsAStudyAndItsExperimentCleanly) {
  fs::create_directories(dir_ / "tmp");
  std::ofstream(dir_ / "ctrl_c.sh") << fmt::format(
      "setsid '{}' --jobs 1 --only convergence_dt,newton_cradle --out res & p=$!\n"
      "sleep 1; kill -INT -$p; wait $p\n",
      exe("study"));
  const Outcome r = run("/bin/sh", "ctrl_c.sh", "TMPDIR=\"$PWD/tmp\" timeout -s KILL 60");
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_EQ(r.err.find("second interrupt"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("convergence_dt: interrupted; nothing written"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("study: interrupted; no experiment had finished"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir_ / "tmp")) << "scratch folders left behind";
  expect_only({"ctrl_c.sh", "tmp"});
}

// SIGHUP (the terminal closed, a supervisor's `kill -HUP`) killed the study at once, and its
// experiment went on as an orphan, writing its folder after the study had gone. It stops both now
// as SIGTERM does (exit 129). The script names (and kills) an experiment left running here.
TEST_F(TrustCli, AHangupStopsAStudyAndItsExperiment) {
  fs::create_directories(dir_ / "tmp");
  std::ofstream(dir_ / "hup.sh") << fmt::format(
      "'{}' --jobs 1 --only convergence_dt,newton_cradle --out res & p=$!\n"
      "sleep 1; kill -HUP $p; wait $p; code=$?\n"
      "for d in /proc/[0-9]*; do\n"
      "  if [ \"$(readlink $d/cwd 2> /dev/null)\" = \"$PWD\" ] &&\n"
      "     [ \"$(cat $d/comm 2> /dev/null)\" = convergence_dt ]; then\n"
      "    echo \"left running: $d\" >&2; kill -KILL ${{d#/proc/}}\n"
      "  fi\n"
      "done\n"
      "exit $code\n",
      exe("study"));
  const Outcome r = run("/bin/sh", "hup.sh", "TMPDIR=\"$PWD/tmp\" timeout -s KILL 60");
  EXPECT_EQ(r.code, 128 + SIGHUP) << r.err;
  EXPECT_NE(r.err.find("study: interrupted; no experiment had finished"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("left running"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir_ / "tmp")) << "scratch folders left behind";
  expect_only({"hup.sh", "tmp"});
}

// Under nohup a hangup is ignored, as nohup asks: the run goes on and writes its results.
TEST_F(TrustCli, NohupKeepsARunThroughAHangup) {
  std::ofstream(dir_ / "nohup.sh") << fmt::format(
      "nohup '{}' --sweep --per-decade 40 --out res > out.txt 2>&1 & p=$!\n"
      "sleep 1; kill -HUP $p; wait $p\n",
      exe("ball_drop"));
  const Outcome r = run("/bin/sh", "nohup.sh");
  EXPECT_EQ(r.code, 0) << r.err << slurp(dir_ / "out.txt");
  EXPECT_TRUE(fs::exists(dir_ / "res" / "meta.json"));
}

// A study interrupted after some experiments finished says which have replaced their folders (it
// said "nothing written"), the one that finished as the signal came among them: a manifest whose
// first experiment writes its folder, interrupts the study and exits 0 (ignoring the interrupt
// the study passes on). Before, the study threw on the signal once that child had ended, and
// named no experiment (a run under load did so with real experiments).
TEST_F(TrustCli, AnInterruptedStudySaysWhichExperimentsFinished) {
  write_shell_study(dir_, "trap '' INT; mkdir -p $1 && echo '{}' > $1/meta.json && kill -INT $PPID", "");
  const Outcome r = run(exe("study"), "--manifest manifest.json --jobs 1 --out res");
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_NE(r.err.find("study: interrupted; finished before it, their folders replaced: first; the "
                       "others keep their earlier results; index.md not written"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "res" / "first" / "meta.json"));
  EXPECT_FALSE(fs::exists(dir_ / "res" / "second")) << "the study went on after the interrupt";
  EXPECT_FALSE(fs::exists(dir_ / "res" / "index.md"));
}

// A study whose reader has gone (`study | head`) stops like an interrupted one. SIGPIPE's default
// killed it at its first print after an experiment ended: the others went on as orphans, writing
// their folders, and its scratch folder of logs stayed in TMPDIR. Its stdout here is a pipe whose
// read end is closed before it starts (deterministic: the first write fails); the second
// experiment would write its folder after a second.
TEST_F(TrustCli, AStudyWhoseReaderHasGoneStopsItsExperiments) {
  write_shell_study(dir_, "", "sleep 1; ");
  fs::create_directories(dir_ / "tmp");
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  ::close(ends[0]);  // no reader
  const std::string cmd =
      fmt::format("cd '{}' && TMPDIR=tmp '{}' --manifest manifest.json --jobs 2 --out res >&{} 2>err.txt",
                  dir_.string(), exe("study"), ends[1]);
  const int status = std::system(cmd.c_str());
  ::close(ends[1]);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // the second's sleep, had it gone on
  const std::string err = slurp(dir_ / "err.txt");
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGPIPE) << err;
  EXPECT_NE(
      err.find("study: interrupted; finished before it, their folders replaced: first; the others keep their "
               "earlier results; index.md not written"),
      std::string::npos)
      << err;
  EXPECT_TRUE(fs::exists(dir_ / "res" / "first" / "meta.json"));
  EXPECT_FALSE(fs::exists(dir_ / "res" / "second")) << "the second experiment went on";
  EXPECT_TRUE(fs::is_empty(dir_ / "tmp")) << "the study's scratch folder of logs was left";
}

// An interrupt ends the solve in progress, not only the experiment between two solves: a
// 1000-ball cradle's first run was minutes long, and SIGINT at 1 s took until it ended (200 s
// more). Every integrator looks at the stop request at each step or right-hand side now; the
// outer KILL after 20 s bounds the test. The solve here is a penalty column of 1000 balls, one
// run of more than 40 s on this machine (the cradle takes 100 balls now, and a game step short
// enough to make its runs that long is refused before they start).
TEST_F(TrustCli, AnInterruptEndsTheSolveInProgress) {
  fs::create_directories(dir_ / "tmp");
  const Outcome r = run(exe("stack"), "--balls 1000 --methods penalty --out st",
                        "TMPDIR=\"$PWD/tmp\" timeout -s KILL 20 timeout --preserve-status -s INT 1");
  EXPECT_EQ(r.code, 130) << r.err;
  EXPECT_NE(r.err.find("interrupted; nothing written"), std::string::npos) << r.err;
  // ... and says why, in its words, not CVODE's for the callback the stop refused (CV_RTFUNC_FAIL).
  EXPECT_NE(r.err.find("penalty: interrupted at t = "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("CV_"), std::string::npos) << r.err;
  expect_only({"tmp"});
}

// A program deaf to the stop, as inside a library that never returns to the program's loops (a
// peer engine's step; OpenBLAS, which Siconos loads, retries a failed allocation forever under
// `ulimit -v`): here a study whose experiment ignores the interrupt the study passes on. SIGINT
// only raised the flag, and the study waited for it for ever, deaf to every further SIGINT or
// SIGTERM. `signals` is the shell that signals the study ($p), once its experiment has started.
class StuckStudy : public TrustCli {
 protected:
  struct Ended {
    Outcome outcome;
    bool experiment_alive;
  };
  Ended interrupt(const std::string& signals) const {
    const std::string pid_file = (dir_ / "stuck.pid").string();
    write_shell_study(dir_, fmt::format("trap '' INT TERM; echo $$ > {}; exec sleep 600", pid_file), "");
    std::ofstream(dir_ / "signal.sh") << fmt::format(
        "'{}' --manifest manifest.json --jobs 1 --out res & p=$!\n"
        "while [ ! -s stuck.pid ]; do sleep 0.1; done\n{}\nwait $p\n",
        exe("study"), signals);
    const Outcome r = run("/bin/sh", "signal.sh", "timeout -s KILL 60");
    const std::string pid = slurp(pid_file);
    if (pid.empty()) {  // the study ended before its experiment started: nothing of it to look for
      ADD_FAILURE() << "the experiment never started: " << r.err;
      return {r, false};
    }
    // Gone, or a zombie not yet reaped by whoever adopted it (the third field of stat: its state);
    // a SIGKILL takes effect soon after it is sent, not at once.
    const auto alive = [&] {
      const std::string stat = slurp(fs::path("/proc") / pid.substr(0, pid.find('\n')) / "stat");
      return !stat.empty() && stat.find(") Z ") == std::string::npos;
    };
    bool still = alive();
    for (int i = 0; still && i < 50; ++i, still = alive())
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (still) ::kill(std::stoi(pid), SIGKILL);
    return {r, still};
  }
};

TEST_F(StuckStudy, EndsByTheSignalTenSecondsAfterIt) {
  const Ended e = interrupt("kill -INT $p");
  EXPECT_EQ(e.outcome.code, 128 + SIGINT) << e.outcome.err;
  EXPECT_NE(e.outcome.err.find("study: still running 10 s after the interrupt (inside a library that does "
                               "not look at it): stopping at once"),
            std::string::npos)
      << e.outcome.err;
  EXPECT_FALSE(e.experiment_alive) << "the study's experiment was left running";
}

// The second a second or more after the first (kSameInterruptSeconds: 1 s), with a margin for the
// scheduling of the handler of the first.
TEST_F(StuckStudy, ASecondInterruptEndsItAtOnce) {
  const Ended e = interrupt("kill -TERM $p; sleep 2; kill -TERM $p");
  EXPECT_EQ(e.outcome.code, 128 + SIGTERM) << e.outcome.err;
  EXPECT_NE(e.outcome.err.find("study: a second interrupt: stopping at once"), std::string::npos)
      << e.outcome.err;
  EXPECT_EQ(e.outcome.err.find("still running"), std::string::npos) << e.outcome.err;
  EXPECT_FALSE(e.experiment_alive) << "the study's experiment was left running";
}

// A copy of the interrupt, 0.2 s after it, is that interrupt again, not a second one: a Ctrl-C on a
// terminal reaches the study's experiments from the terminal and from the study, and `timeout`
// signals the study and then its group; the copy stopped them at once ("a second interrupt"),
// their staging folders left (CI saw it once in InterruptsLeaveNothingBehindAndKeepEarlierResults).
// Deaf, this study ends by the deadline 10 s after the first.
TEST_F(StuckStudy, ACopyOfTheInterruptIsNotASecondOne) {
  const Ended e = interrupt("kill -TERM $p; sleep 0.2; kill -TERM $p");
  EXPECT_EQ(e.outcome.code, 128 + SIGTERM) << e.outcome.err;
  EXPECT_EQ(e.outcome.err.find("second interrupt"), std::string::npos) << e.outcome.err;
  EXPECT_NE(e.outcome.err.find("study: still running 10 s after the interrupt"), std::string::npos)
      << e.outcome.err;
  EXPECT_FALSE(e.experiment_alive) << "the study's experiment was left running";
}

// On a terminal (a pseudo-terminal from script(1), 16 columns wide) every progress line fits one
// row: "\r" returns to the start of the last row only, and a line that wrapped left its first row
// behind at every step ("ball_drop [1/2] penalty" is 23 characters).
TEST_F(TrustCli, ProgressFitsANarrowTerminal) {
  const std::string command =
      fmt::format("stty cols 16; env -u CI '{}' --method penalty,event-exact --out res", exe("ball_drop"));
  const Outcome r = run("script", fmt::format("-qec \"{}\" /dev/null", command));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  std::size_t lines = 0;
  for (std::size_t at = r.out.find("\033[K"); at != std::string::npos; at = r.out.find("\033[K", at + 1)) {
    const std::size_t begin = at + 3;
    const std::string line = r.out.substr(begin, r.out.find_first_of("\r\n", begin) - begin);
    if (!line.starts_with("ball_drop [")) continue;  // the clearing at the end, then the report
    EXPECT_LE(line.size(), 15u) << line;
    ++lines;
  }
  EXPECT_GE(lines, 2u) << "no progress shown:\n" << r.out;  // each run's, and how far it came
}

// A single run showed only its name, however long it took ("ball_drop [1/1] siconos" for the three
// minutes of --dt 1.6e-6 --t-end 20, as if it hung); its line now says how far it has come. A run
// of 3e7 fixed steps (2 s here) is redrawn several times; a run of microseconds never is, so its
// reported wall time is not the terminal's (a draw at each percent made the exact bounces' 46 us
// 0.72 ms on a terminal).
TEST_F(TrustCli, ALongRunShowsHowFarItHasCome) {
  const auto lines_of = [&](const std::string& method, const std::string& options) {
    const std::string command =
        fmt::format("env -u CI '{}' --method {} {} --out res", exe("ball_drop"), method, options);
    const Outcome r = run("script", fmt::format("-qec \"{}\" /dev/null", command));
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    std::vector<std::string> lines;
    const std::string start = "ball_drop [1/1] " + method + ": t = ";
    for (auto at = r.out.find(start); at != std::string::npos; at = r.out.find(start, at + 1))
      lines.push_back(r.out.substr(at, r.out.find('\r', at) - at));
    return lines;
  };
  const auto long_run = lines_of("game-symplectic", "--dt 1e-7");
  ASSERT_GE(long_run.size(), 2u);
  for (const auto& line : long_run) EXPECT_TRUE(line.ends_with(" s of 3 s")) << line;
  EXPECT_TRUE(lines_of("event-exact", "").empty());
}
