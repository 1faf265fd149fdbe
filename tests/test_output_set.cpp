// An experiment's OutputSet: one gnuplot run draws all of an experiment's figures (draw_figures),
// each from gnuplot's defaults whatever the figure before it set, every queued figure gets its four
// files, and a failure names the figure that failed, with gnuplot's message; and write() never
// replaces a folder that is not an earlier run's results.
#include "figure.hpp"
#include "output.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

namespace {

using contact::Figure;
using contact::OutputSet;

TEST(FigureBatch, NoSettingCarriesOverFromTheFigureBefore) {
  OutputSet out;
  // The second figure's y values are all negative: a log scale carried over from the first would
  // leave it nothing to draw, which gnuplot refuses ("all points y value undefined").
  contact::render({"first", "1,1\n10,100\n", "set logscale y\nplot 'data.csv' using 1:2 with lines"}, out);
  contact::render({"second", "1,-1\n2,-3\n", "plot 'data.csv' using 1:2 with lines"}, out);
  ASSERT_NO_THROW(contact::draw_figures(out));
  for (const char* name : {"first", "second"})
    for (const char* suffix : {".png", ".pdf", ".gp", "-data.csv"})
      EXPECT_TRUE(out.files().contains(std::string(name) + suffix)) << name << suffix;
  EXPECT_EQ(out.files().at("second-data.csv"), "1,-1\n2,-3\n");
  EXPECT_EQ(out.files().at("second.png").substr(1, 3), "PNG");
  EXPECT_EQ(out.take_figures().size(), 0u);  // drawn, nothing left queued
}

TEST(FigureBatch, AFailureNamesTheFigureThatFailed) {
  OutputSet out;
  contact::render({"fine", "1,1\n2,2\n", "plot 'data.csv' using 1:2 with lines"}, out);
  contact::render({"broken", "1,1\n", "plot 'data.csv' using 1:2 with nonsense"}, out);
  try {
    contact::draw_figures(out);
    FAIL() << "a gnuplot error was not reported";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gnuplot failed for broken"), std::string::npos) << what;
    EXPECT_NE(what.find("nonsense"), std::string::npos) << what;  // gnuplot's own message
  }
}

// A convergence panel whose every run failed: its series hold no point, or only errors a log axis
// cannot show (NaN, inf, 0). gnuplot skipped each block and then refused to autoscale a log axis on
// nothing ("logscaled axis must have positive range"), which ended convergence_dt at --k 1e300
// with no output; the panel now says there is nothing to draw, and so does one such series beside
// a drawn one by being left out.
TEST(FigureBatch, AConvergencePanelWithoutAPointIsDrawnEmpty) {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  const std::vector<contact::NamedPoints> failed = {{"no run", {}},
                                                    {"failed runs", {{1e-3, nan}, {2e-3, inf}, {4e-3, 0.0}}}};
  auto mixed = failed;
  mixed.push_back({"drawn", {{1e-3, 1e-6}, {2e-3, 4e-6}}});
  OutputSet out;
  contact::render(contact::convergence_figure("empty", "dt", "error", failed, {1, 2}), out);
  contact::render(contact::convergence_figure("mixed", "dt", "error", mixed, {1, 2}), out);
  ASSERT_NO_THROW(contact::draw_figures(out));
  EXPECT_NE(out.files().at("empty.gp").find("nothing to draw"), std::string::npos);
  EXPECT_EQ(out.files().at("mixed-data.csv"), "0.001,1e-06\n0.002,4e-06\n\n\n");  // the drawn series alone
  EXPECT_EQ(out.files().at("empty.png").substr(1, 3), "PNG");
}

TEST(FigureBatch, AnUndrawnFigureIsNotWrittenSilentlyAway) {
  OutputSet out;
  contact::render({"pending", "1,1\n", "plot 'data.csv' using 1:2"}, out);
  const contact::ScratchDir scratch{contact::make_scratch_dir("figure_batch")};
  EXPECT_THROW(out.write(scratch.path / "results", "probe"), std::logic_error);
}

}  // namespace

namespace {

// OutputSet::write replaces its folder whole, so it checks the folder itself, whatever its caller
// did: a folder holding anything but an earlier run's results (its meta.json naming the program)
// is never replaced.
TEST(OutputSetWrite, NeverReplacesAFolderOfOtherFiles) {
  const contact::ScratchDir scratch{contact::make_scratch_dir("output_set")};
  const auto mine = scratch.path / "mine";
  std::filesystem::create_directories(mine);
  std::ofstream(mine / "keep.txt") << "kept\n";
  OutputSet out;
  out.add("meta.json", R"({"experiment": "probe"})"
                       "\n");
  EXPECT_THROW(out.write(mine, "probe"), std::runtime_error);
  EXPECT_TRUE(std::filesystem::exists(mine / "keep.txt"));
  // An earlier run's folder (its meta.json names the program) is replaced.
  out.write(scratch.path / "earlier", "probe");
  std::ofstream(scratch.path / "earlier" / "stale.txt") << "stale\n";
  out.write(scratch.path / "earlier", "probe");
  EXPECT_FALSE(std::filesystem::exists(scratch.path / "earlier" / "stale.txt"));
  EXPECT_TRUE(std::filesystem::exists(scratch.path / "earlier" / "meta.json"));
}

// Any folder holding a meta.json passed for an earlier run, whichever program wrote it:
// `ball_drop --out results/zeno` replaced zeno's results, though the refusal's own words promised
// "an earlier --out of this program". Another program's results, or a meta.json that names no
// program, are refused, naming both programs.
TEST(OutputSetWrite, NeverReplacesAnotherProgramsResults) {
  const contact::ScratchDir scratch{contact::make_scratch_dir("output_set")};
  OutputSet zeno;
  zeno.add("meta.json", R"({"experiment": "zeno"})"
                        "\n");
  zeno.write(scratch.path / "zeno", "zeno");
  OutputSet drop;
  drop.add("meta.json", R"({"experiment": "ball_drop"})"
                        "\n");
  try {
    drop.write(scratch.path / "zeno", "ball_drop");
    ADD_FAILURE() << "ball_drop replaced zeno's results";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(
        std::string(e.what()).find("holds the results of zeno (its meta.json says so), not of ball_drop"),
        std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("an earlier --out of ball_drop"), std::string::npos) << e.what();
  }
  std::string kept;
  std::getline(std::ifstream(scratch.path / "zeno" / "meta.json"), kept);
  EXPECT_EQ(kept, R"({"experiment": "zeno"})");
  for (const char* meta : {"{}", "[1, 2]", "not json", R"({"experiment": 3})"}) {
    const auto dir = scratch.path / "odd";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "meta.json") << meta;
    EXPECT_NE(contact::check_output_dir(dir, "ball_drop").find("holds no meta.json of an earlier run"),
              std::string::npos)
        << meta;
    EXPECT_EQ(contact::check_output_dir(dir, ""), "") << meta;  // written into, not replaced
  }
}

}  // namespace

// A --out that is a link to a folder (results -> /data/results) stands for that folder: its
// results are replaced there and the link stays. The link used to be replaced by a new folder in
// its place, the target keeping the old results. A link to nothing is refused, naming its target.
TEST(OutputSetWrite, ALinkToAFolderIsReplacedWhereItPoints) {
  namespace fs = std::filesystem;
  const contact::ScratchDir scratch{contact::make_scratch_dir("output_set")};
  OutputSet out;
  out.add("meta.json", R"({"experiment": "probe"})"
                       "\n");
  out.write(scratch.path / "data", "probe");
  std::ofstream(scratch.path / "data" / "stale.txt") << "stale\n";
  fs::create_directory_symlink(scratch.path / "data", scratch.path / "link");
  for (const char* given : {"link", "link/"}) {
    out.write(scratch.path / given, "probe");
    EXPECT_TRUE(fs::is_symlink(scratch.path / "link")) << given;
    EXPECT_TRUE(fs::exists(scratch.path / "data" / "meta.json")) << given;
    EXPECT_FALSE(fs::exists(scratch.path / "data" / "stale.txt")) << given;
  }
  fs::create_directory_symlink(scratch.path / "gone", scratch.path / "dangling");
  EXPECT_NE(contact::check_output_dir(scratch.path / "dangling", "probe")
                .find("is a link to nothing (" + (scratch.path / "gone").string() + ")"),
            std::string::npos);
  EXPECT_THROW(out.write(scratch.path / "dangling", "probe"), std::runtime_error);
  EXPECT_TRUE(fs::is_symlink(scratch.path / "dangling"));
}

// A file write_into cannot rename into place says why: the clean-up of its temporary file used to
// overwrite the rename's error, and the message read "cannot write d/sub: Success".
TEST(OutputSetWrite, AFileThatCannotBeWrittenSaysWhy) {
  namespace fs = std::filesystem;
  const contact::ScratchDir scratch{contact::make_scratch_dir("output_set")};
  fs::create_directories(scratch.path / "sub");
  OutputSet out;
  out.add("sub", "a file where a folder is\n");
  try {
    out.write_into(scratch.path);
    ADD_FAILURE() << "a file was written over a folder";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + (scratch.path / "sub").string() + ": Is a directory");
  }
  EXPECT_FALSE(fs::exists(scratch.path / ".sub.tmp"));
}
