#include "figure.hpp"

#include <fmt/format.h>

#include "process.hpp"

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace contact {

namespace fs = std::filesystem;

namespace {

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::string Series::plot() const {
  // (Fixed ranges: autoscaling a log axis on no point is an error too.)
  return count_ ? plot_ : "[1:10][1:10] 1/0 title 'nothing to draw: no run gave a point'";
}

void Series::add(const std::string& rows, const std::string& clause) {
  // A series without a row is left out: gnuplot skips its block with a warning, and a panel of
  // only such series has nothing to autoscale a log axis on, a gnuplot error that ended the
  // experiment (convergence_dt at --k 1e300, where every run fails).
  if (rows.find_first_not_of(" \n") == std::string::npos) return;
  data_ += rows + "\n\n";
  plot_ += fmt::format("{}'data.csv' index {} {}", count_ ? ", " : "", count_, clause);
  ++count_;
}

namespace {
constexpr std::array<const char*, 10> kColours = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                                  "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#000000"};
}  // namespace

std::string line_colour(std::size_t i) {
  if (i >= kColours.size()) throw std::invalid_argument(fmt::format("series {}: a panel has at most 10", i));
  return fmt::format("lc rgb '{}'", kColours[i]);
}

std::string series_style(std::size_t i) {
  static constexpr std::array<int, 10> kPoints = {1, 2, 4, 6, 8, 10, 12, 3, 5, 7};
  return fmt::format("{} pt {}", line_colour(i), kPoints[i]);
}

Figure convergence_figure(const std::string& name, const std::string& xlabel, const std::string& ylabel,
                          const std::vector<NamedPoints>& series, const std::vector<int>& slopes) {
  Series lines;
  double x0 = 0, y0 = 0;
  for (const auto& [title, points] : series) {
    std::string rows;
    for (const auto& p : points) {
      if (!(p.step > 0 && p.error > 0 && std::isfinite(p.step) && std::isfinite(p.error)))
        continue;  // not on a log-log panel
      rows += fmt::format("{},{}\n", p.step, p.error);
      if (p.step >= x0) {
        y0 = p.step > x0 ? p.error : std::max(y0, p.error);
        x0 = p.step;
      }
    }
    lines.add(rows,
              fmt::format("using 1:2 with linespoints {} title '{}'", series_style(lines.count()), title));
  }
  std::string plot = loglog(xlabel, ylabel) + "set key outside right font ',9'\nplot " + lines.plot();
  for (const int p : slopes) {
    if (lines.empty()) break;  // a reference line needs a point to pass through
    plot += fmt::format(", {} * (x / {})**{} with lines dt 3 lc rgb 'gray50' title 'slope {}'", y0, x0, p, p);
  }
  return {name, lines.data(), plot};
}

std::string loglog(const std::string& xlabel, const std::string& ylabel) {
  return fmt::format(
      "set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\nset xlabel '{}'\nset ylabel "
      "'{}'\nset grid\n",
      xlabel, ylabel);
}

std::string logy(const std::string& ylabel) {
  return fmt::format("set logscale y\nset format y '10^{{%L}}'\nset ylabel '{}'\nset grid\n", ylabel);
}

namespace {

// The figure's script reading its own data file, NAME-data.csv (the file saved beside it).
std::string script_reading_own_data(const Figure& f) {
  std::string script = f.script;
  const std::string data_file = "'" + f.name + "-data.csv'";
  for (std::size_t at = script.find("'data.csv'"); at != std::string::npos;
       at = script.find("'data.csv'", at + data_file.size()))
    script.replace(at, 10, data_file);
  return script;
}

const char* const kPng = "set terminal pngcairo size 900,600 font ',11'\n";
const char* const kPdf = "set terminal pdfcairo size 6in,4in font ',10'\n";
const std::string kMarker = "drawing figure ";  // printed on the log before each figure

}  // namespace

void render(Figure figure, OutputSet& out) { out.queue_figure(std::move(figure)); }

void draw_figures(OutputSet& out) {
  const std::vector<Figure> figures = out.take_figures();
  if (figures.empty()) return;
  throw_if_interrupted();
  // A private scratch folder (mkdtemp: unique, not guessable) removed however this ends. One
  // gnuplot run draws every picture, each figure's script once per terminal (a multiplot cannot
  // be replotted) after a reset, so that no setting carries over from the figure before. Each
  // figure announces itself on the log, so that a failure is put to the figure that failed. The
  // file names are relative (gnuplot runs in the scratch folder), so no path is ever quoted.
  const ScratchDir scratch{make_scratch_dir("contact_figure")};
  const fs::path& dir = scratch.path;
  std::string batch;
  std::vector<std::string> scripts;  // each reading its own NAME-data.csv, as the saved NAME.gp does
  for (const Figure& f : figures) {
    scripts.push_back(script_reading_own_data(f));
    std::ofstream(dir / (f.name + "-data.csv")) << f.data;
    batch += fmt::format(
        "reset\nprint '{4}{0}'\nset datafile separator ','\n{1}set output '{0}.png'\n{2}\n"
        "unset output\n{3}set output '{0}.pdf'\n{2}\nunset output\n",
        f.name, kPng, scripts.back(), kPdf, kMarker);
  }
  std::ofstream(dir / "plot.gp") << batch;
  const int code = run_process({"gnuplot", "plot.gp"}, dir, dir / "gnuplot.log");
  if (code != 0) {
    // The log from the failing figure's announcement on (the first figure's if gnuplot never ran).
    const std::string log = read_file(dir / "gnuplot.log");
    const std::size_t at = log.rfind(kMarker);
    const std::string tail = at == std::string::npos ? log : log.substr(at + kMarker.size());
    const std::string failed =
        at == std::string::npos ? figures.front().name : tail.substr(0, tail.find('\n'));
    throw std::runtime_error(
        fmt::format("gnuplot failed for {} (exit {}): {}", failed, code,
                    log.empty() ? "is gnuplot installed? (bash scripts/setup.sh)" : tail));
  }
  for (std::size_t i = 0; i < figures.size(); ++i) {
    const Figure& f = figures[i];
    for (const char* ext : {"png", "pdf"})
      out.add(fmt::format("{}.{}", f.name, ext), read_file(dir / fmt::format("{}.{}", f.name, ext)));
    // The saved script re-runs beside its data: `gnuplot NAME.gp` in the folder reads NAME-data.csv.
    out.add(f.name + "-data.csv", f.data);
    out.add(f.name + ".gp", "# gnuplot " + f.name + ".gp, in this folder, draws " + f.name + ".png from " +
                                f.name + "-data.csv\nset datafile separator ','\n" + kPng + "set output '" +
                                f.name + ".png'\n" + scripts[i] + "\n");
  }
}

}  // namespace contact
