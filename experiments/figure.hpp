#pragma once
// Figures drawn by gnuplot (Debian's gnuplot-nox, cairo terminals) from the experiment's own CSV,
// as PNG for quick viewing and PDF for the paper. The scripts and data are written to a private
// scratch folder, one gnuplot run draws all of an experiment's figures there (no shell), and the
// pictures join the experiment's OutputSet, so they are written with everything else or not at all.
#include "contact_ode/analysis/fit.hpp"
#include "output.hpp"

#include <string>
#include <utility>
#include <vector>

namespace contact {

// Several series in one data file, one gnuplot index block each: add() appends a block of CSV
// rows and the clause that draws it ("using 1:2 with lines title 'x'"); plot() is the
// comma-separated list of "'data.csv' index i <clause>" to put after "plot ". With no series (a
// sweep whose every run failed) it is an empty panel that says so, which gnuplot draws: a bare
// "plot " is a gnuplot error, which used to end the experiment with gnuplot's message.
class Series {
 public:
  void add(const std::string& rows, const std::string& clause);
  const std::string& data() const { return data_; }
  std::string plot() const;
  bool empty() const { return count_ == 0; }
  std::size_t count() const { return static_cast<std::size_t>(count_); }

 private:
  std::string data_, plot_;
  int count_ = 0;
};

// The line colour and point type of series i of a panel (i < 10): ten colours (Tableau 10) and ten
// markers, so that no two of a panel's series look alike.
std::string series_style(std::size_t i);
// Its colour alone, for series drawn `with lines` (gnuplot warns at a point type there).
std::string line_colour(std::size_t i);

// The lines that start a log-log figure: both axes logarithmic with powers-of-ten ticks, the
// axis labels (gnuplot text) and a grid.
std::string loglog(const std::string& xlabel, const std::string& ylabel);
// The same with only the y axis logarithmic.
std::string logy(const std::string& ylabel);

// A convergence panel (at most 10 series): each named series' errors against its steps (log-log,
// lines and points), and dashed grey reference lines of the given slopes through the largest
// error at the largest step.
using NamedPoints = std::pair<std::string, std::vector<ConvergencePoint>>;
Figure convergence_figure(const std::string& name, const std::string& xlabel, const std::string& ylabel,
                          const std::vector<NamedPoints>& series, const std::vector<int>& slopes);

// Queues the figure in `out`, to be drawn by draw_figures: NAME.png and NAME.pdf, and, to redraw
// it, the script NAME.gp with its data NAME-data.csv.
void render(Figure figure, OutputSet& out);
// Draws every figure queued in `out` by one gnuplot run and adds their files (Experiment::run
// calls it after the body). Throws std::runtime_error naming the figure, with gnuplot's message,
// if gnuplot fails or is missing.
void draw_figures(OutputSet& out);

}  // namespace contact
