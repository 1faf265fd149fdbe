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
  for (const int p : slopes)
    plot += fmt::format(", {} * (x / {})**{} with lines dt 3 lc rgb 'gray50' title 'slope {}'", y0, x0, p, p);
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

void render(const Figure& f, OutputSet& out) {
  throw_if_interrupted();
  // A private scratch folder (mkdtemp: unique, not guessable) removed however render() ends.
  const ScratchDir scratch{make_scratch_dir("contact_figure")};
  const fs::path& dir = scratch.path;
  std::ofstream(dir / "data.csv") << f.data;
  // One gnuplot run draws both pictures, the script once per terminal (a multiplot cannot be
  // replotted). The file names are relative (gnuplot runs in the scratch folder), so no path is
  // ever quoted.
  std::ofstream(dir / "plot.gp") << "set datafile separator ','\n"
                                 << "set terminal pngcairo size 900,600 font ',11'\nset output '" << f.name
                                 << ".png'\n"
                                 << f.script << "\nunset output\n"
                                 << "set terminal pdfcairo size 6in,4in font ',10'\nset output '" << f.name
                                 << ".pdf'\n"
                                 << f.script << "\nunset output\n";
  const int code = run_process({"gnuplot", "plot.gp"}, dir, dir / "gnuplot.log");
  if (code != 0) {
    const std::string log = read_file(dir / "gnuplot.log");
    throw std::runtime_error(
        fmt::format("gnuplot failed for {} (exit {}): {}", f.name, code,
                    log.empty() ? "is gnuplot installed? (bash scripts/setup.sh)" : log));
  }
  for (const char* ext : {"png", "pdf"})
    out.add(fmt::format("{}.{}", f.name, ext), read_file(dir / fmt::format("{}.{}", f.name, ext)));
  // The saved script re-runs beside its data: `gnuplot NAME.gp` in the folder reads NAME-data.csv.
  const std::string data_file = f.name + "-data.csv";
  std::string script = f.script;
  for (std::size_t at = script.find("'data.csv'"); at != std::string::npos;
       at = script.find("'data.csv'", at))
    script.replace(at, 10, "'" + data_file + "'");
  out.add(data_file, f.data);
  out.add(f.name + ".gp",
          "# gnuplot " + f.name + ".gp, in this folder, draws " + f.name + ".png from " + data_file +
              "\nset datafile separator ','\nset terminal pngcairo size 900,600 font ',11'\nset output '" +
              f.name + ".png'\n" + script + "\n");
}

}  // namespace contact
