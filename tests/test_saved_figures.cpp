// Every figure the full study saved re-runs as its script's first line says (`gnuplot NAME.gp` in its
// folder, beside NAME-data.csv) without a word from gnuplot: no error and no warning (a point type on
// a series drawn with lines drew one per series in energy_drift's scripts). Reads the results the
// paper_builds test leaves in PAPER_RESULTS (a CTest fixture); each script runs in a scratch copy, so
// the results stay as the study left them.
#include "output.hpp"
#include "process.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace fs = std::filesystem;

TEST(SavedFigures, EveryScriptReRunsWithoutAWordFromGnuplot) {
  std::size_t scripts = 0, pictures = 0;
  for (const auto& entry : fs::recursive_directory_iterator(PAPER_RESULTS)) {
    const fs::path& path = entry.path();
    if (path.extension() == ".png") ++pictures;
    if (path.extension() != ".gp") continue;
    ++scripts;
    const contact::ScratchDir scratch{contact::make_scratch_dir("saved_figure")};
    const std::string data = path.stem().string() + "-data.csv";
    fs::copy_file(path, scratch.path / path.filename());
    fs::copy_file(path.parent_path() / data, scratch.path / data);
    const int code = contact::run_process({"gnuplot", path.filename().string()}, scratch.path,
                                          scratch.path / "gnuplot.log");
    EXPECT_EQ(code, 0) << path;
    EXPECT_EQ(contact::read_text(scratch.path / "gnuplot.log"), "") << path;
    EXPECT_TRUE(fs::exists(scratch.path / (path.stem().string() + ".png"))) << path;
  }
  EXPECT_GT(scripts, 0u);
  EXPECT_EQ(scripts, pictures);  // every picture of the study has its script
}
