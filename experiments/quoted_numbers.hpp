#pragma once
// The list of numbers the paper quotes (paper/numbers.json), read and checked whole before any
// result is: each entry names a macro, the CSV under the study's results, the row (column = value
// pairs) and the column its value comes from, with an optional fmt format, scale and "last".
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace contact {

struct QuotedNumber {
  std::string macro;                                       // letters only: LaTeX's \newcommand name
  std::string file;                                        // relative, under the results folder
  std::vector<std::pair<std::string, std::string>> where;  // column, value: every one must hold
  std::string column;
  std::string format;  // fmt syntax for the cell as a number; empty: the cell as it is
  double scale = 1.0;  // a factor on the number (1e3: s as ms)
  bool last = false;   // the last matching row rather than the first (a sweep's finest step)
};

// Throws std::invalid_argument naming the entry, its key, the value and what is accepted: a list
// that is not JSON, an unknown or missing key, a value of the wrong kind, a macro that is not
// letters or is defined twice, a file outside the results, a format that cannot print a number.
std::vector<QuotedNumber> load_quoted_numbers(const std::filesystem::path& list);

// The number's text from the study's results. Throws std::runtime_error naming the file when the
// file, the row or the column is missing, or the cell is empty, not finite, or not a number where
// a format or scale needs one.
std::string quoted_value(const std::filesystem::path& results, const QuotedNumber& n);

}  // namespace contact
