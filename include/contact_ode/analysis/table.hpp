#pragma once
// A small table of results rendered as CSV (full precision, for machines), Markdown (for the
// terminal and results/index.md) and LaTeX booktabs (for the paper: numbers in powers of ten,
// e.g. $3.2\times10^{-5}$, and a typeset header where one is set).
#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace contact {

class Table {
 public:
  using Cell = std::variant<std::string, double, long>;

  explicit Table(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  // Appends a row; throws std::invalid_argument if its width differs from the header's.
  void add_row(std::vector<Cell> row);

  // The header the LaTeX rendering shows instead of the column names (which stay the CSV's and
  // Markdown's): LaTeX source, for symbols and units ("$\\Delta t$ [s]"); a newline stacks a cell's
  // lines. Throws
  // std::invalid_argument if its width differs from the header's.
  void set_latex_header(std::vector<std::string> header);

  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::vector<Cell>>& rows() const { return rows_; }

  std::string to_csv() const;
  std::string to_markdown(int significant_digits = 4) const;
  std::string to_latex(int significant_digits = 4) const;

 private:
  std::vector<std::string> columns_, latex_header_;
  std::vector<std::vector<Cell>> rows_;
};

// The cells of one line of Table::to_csv(): the inverse of its quoting ("a, b" and "" escapes).
std::vector<std::string> split_csv_line(const std::string& line);

// The table spread out for reading: one row per distinct value of column `row` (in order of first
// appearance, with the `keep` columns of its first row), one column per distinct value of column
// `across`, holding that row's `value` (NaN where no row has the pair).
Table pivot(const Table& t, const std::string& row, const std::vector<std::string>& keep,
            const std::string& across, const std::string& value);

// Text as LaTeX typesets it: each of LaTeX's ten special characters escaped.
std::string latex_escape(const std::string& s);

// The records of a CSV text, each its cells: a newline inside quotes belongs to its cell, a CRLF
// ends a record as a LF does. Throws std::runtime_error naming the record whose quote is not closed.
std::vector<std::vector<std::string>> parse_csv(const std::string& text);

// The rows of a CSV file written by Table::to_csv(), each a map from column name to cell.
// Blank lines are skipped. Throws std::runtime_error naming the file when it cannot be read, is
// empty, has a quote not closed or a row whose width is not the header's.
using CsvRecord = std::map<std::string, std::string>;
std::vector<CsvRecord> read_csv(const std::filesystem::path& path);

}  // namespace contact
