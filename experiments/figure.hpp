#pragma once
// Figures drawn by gnuplot (Debian's gnuplot-nox, cairo terminals) from the experiment's own CSV,
// as PNG for quick viewing and PDF for the paper. The script and data are written to a scratch
// directory, gnuplot runs there, and the pictures join the experiment's OutputSet, so they are
// written with everything else or not at all.
#include "output.hpp"

#include <string>

namespace contact {

struct Figure {
  std::string name;    // file stem: NAME.png, NAME.pdf, NAME.gp
  std::string data;    // CSV the script reads as 'data.csv'
  std::string script;  // gnuplot commands after the terminal and output lines; plots 'data.csv'
};

// Renders the figure into `out` (NAME.png, NAME.pdf, and the script NAME.gp for reuse). Throws
// std::runtime_error with gnuplot's message if it fails or is missing.
void render(const Figure& figure, OutputSet& out);

}  // namespace contact
