#include "figure.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

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

void Series::add(const std::string& rows, const std::string& clause) {
  data_ += rows + "\n\n";
  plot_ += fmt::format("{}'data.csv' index {} {}", count_ ? ", " : "", count_, clause);
  ++count_;
}

void render(const Figure& f, OutputSet& out) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("contact_figure_{}_{}", ::getpid(), f.name);
  fs::create_directories(dir);
  std::ofstream(dir / "data.csv") << f.data;
  for (const auto& [terminal, ext] : {std::pair{"pngcairo size 900,600 font ',11'", "png"},
                                      std::pair{"pdfcairo size 6in,4in font ',10'", "pdf"}}) {
    std::ofstream(dir / "plot.gp") << "set terminal " << terminal << "\nset output '" << f.name << "." << ext
                                   << "'\nset datafile separator ','\n" << f.script << "\n";
    const std::string cmd = fmt::format("cd '{}' && gnuplot plot.gp > gnuplot.log 2>&1", dir.string());
    if (std::system(cmd.c_str()) != 0) {
      const std::string log = read_file(dir / "gnuplot.log");
      fs::remove_all(dir);
      throw std::runtime_error(fmt::format("gnuplot failed for {}: {}", f.name, log.empty() ? "is gnuplot installed?" : log));
    }
    out.add(fmt::format("{}.{}", f.name, ext), read_file(dir / fmt::format("{}.{}", f.name, ext)));
  }
  out.add(f.name + ".gp", "set datafile separator ','\n# data: " + f.name + ".csv\n" + f.script + "\n");
  fs::remove_all(dir);
}

}  // namespace contact
