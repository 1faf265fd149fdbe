// A sweep for the MPI tests: --cases cases, case i returns i * i, and case --fail (if >= 0) throws
// (std::invalid_argument with --bad-input). Writes squares.csv. Run under mpirun by
// test_study_mpi, to see a case failing on one rank fail the whole run instead of hanging it.
#include "contact_ode/analysis/table.hpp"
#include "experiment.hpp"
#include "process.hpp"

#include <fmt/format.h>

#include <stdexcept>

int program(int argc, char** argv) {
  long cases = 6, fail = -1;
  bool bad_input = false;
  contact::Experiment app("share_probe", "A sweep of squares for the MPI tests.", "results/share_probe");
  app.add("--cases", cases, "number of cases", contact::cli::integer_at_least(1));
  app.add("--fail", fail, "the case that throws (-1: none)");
  app.add_flag("--bad-input", bad_input, "the failing case reports bad input");
  return app.run(argc, argv, [&](contact::OutputSet& files) {
    const auto results = app.share(static_cast<std::size_t>(cases), [&](std::size_t i) -> nlohmann::json {
      if (static_cast<long>(i) == fail) {
        const std::string what = fmt::format("case {} failed on purpose", i);
        if (bad_input) throw std::invalid_argument(what);
        throw std::runtime_error(what);
      }
      return static_cast<double>(i * i);
    });
    if (!results) return;
    contact::Table squares({"case", "square"});
    for (std::size_t i = 0; i < results->size(); ++i)
      squares.add_row({static_cast<long>(i), (*results)[i].get<double>()});
    files.add_table("squares", squares);
  });
}

int main(int argc, char** argv) { return contact::guarded_main("share_probe", argc, argv, program); }
