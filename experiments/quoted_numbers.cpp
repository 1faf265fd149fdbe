#include "quoted_numbers.hpp"

#include "contact_ode/analysis/table.hpp"
#include "output.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <stdexcept>

namespace contact {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A cell that is wholly a number (strtod's syntax: "0.001", "1e-3", "nan").
bool parse_number(const std::string& text, double& x) {
  std::size_t used = 0;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size();
}

// "1.5e-07" reads better as 1.5 x 10^-7 in the text; anything else stays as it is.
std::string latex_number(const std::string& s) {
  const auto e = s.find_first_of("eE");
  double mantissa = 0, exponent = 0;
  if (e == std::string::npos || !parse_number(s.substr(0, e), mantissa) ||
      !parse_number(s.substr(e + 1), exponent) || exponent != std::round(exponent))
    return s;
  return fmt::format("\\ensuremath{{{}\\times10^{{{}}}}}", s.substr(0, e), static_cast<int>(exponent));
}

bool cell_matches(const std::string& cell, const std::string& wanted) {
  double x = 0, y = 0;  // numbers: "0.001" matches "1e-3"
  return cell == wanted ||
         (parse_number(cell, x) && parse_number(wanted, y) && std::abs(x - y) <= 1e-12 * std::abs(y));
}

// One entry, every key checked; `bad` throws naming the entry.
QuotedNumber parse_entry(const json& e, const std::function<void(const std::string&)>& bad) {
  if (!e.is_object()) bad("is not an object; accepted: {\"macro\", \"file\", \"where\", \"column\", ...}");
  for (const auto& [key, value] : e.items())
    if (!std::set<std::string>{"macro", "file", "where", "column", "format", "scale", "last"}.count(key))
      bad(fmt::format("key '{}' is not known; accepted: macro, file, where, column, format, scale, last",
                      key));
  const auto text = [&](const char* key, bool required) {
    if (!e.contains(key)) {
      if (required) bad(fmt::format("{}: missing", key));
      return std::string();
    }
    if (!e.at(key).is_string() || e.at(key).get<std::string>().empty())
      bad(fmt::format("{}: value {} is not accepted; accepted: a non-empty string", key, e.at(key).dump()));
    return e.at(key).get<std::string>();
  };
  QuotedNumber n{text("macro", true), text("file", true), {}, text("column", true), text("format", false)};
  if (!std::all_of(n.macro.begin(), n.macro.end(), [](unsigned char c) { return std::isalpha(c); }))
    bad(fmt::format("macro: value '{}' is not accepted; accepted: letters only (a LaTeX command's name)",
                    n.macro));
  if (!stays_inside(n.file))
    bad(fmt::format("file: value '{}' is not accepted; accepted: a relative path under the results folder",
                    n.file));
  if (!e.contains("where")) bad("where: missing");
  const json& where = e.at("where");
  const auto is_pair = [](const json& w) {
    return w.is_array() && w.size() == 2 && w[0].is_string() && w[1].is_string();
  };
  if (!where.is_array() || !std::all_of(where.begin(), where.end(), is_pair))
    bad(fmt::format("where: value {} is not accepted; accepted: a list of [column, value] string pairs",
                    where.dump()));
  for (const auto& w : where) n.where.emplace_back(w[0], w[1]);
  if (e.contains("scale") && (!e.at("scale").is_number() || !std::isfinite(e.at("scale").get<double>())))
    bad(fmt::format("scale: value {} is not accepted; accepted: a finite number", e.at("scale").dump()));
  n.scale = e.value("scale", 1.0);
  if (e.contains("last") && !e.at("last").is_boolean())
    bad(fmt::format("last: value {} is not accepted; accepted: true or false", e.at("last").dump()));
  n.last = e.value("last", false);
  std::string sample = "1", error;
  try {
    if (!n.format.empty()) sample = fmt::format(fmt::runtime(n.format), 1.0);
  } catch (const fmt::format_error& ex) {
    error = ex.what();
  }
  const char* accepted = "accepted: an fmt format of one number, such as {:.3f}";
  if (!error.empty())
    bad(fmt::format("format: value '{}' cannot print a number ({}); {}", n.format, error, accepted));
  if (sample.find_first_of("%$#&_{}\\~^") != std::string::npos)
    bad(fmt::format("format: value '{}' prints '{}', which LaTeX cannot typeset as it is; {}", n.format,
                    sample, accepted));
  return n;
}

}  // namespace

std::vector<QuotedNumber> load_quoted_numbers(const fs::path& list) {
  std::ifstream in(list);
  if (!in) throw std::invalid_argument(fmt::format("'{}' cannot be read", list.string()));
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& ex) {
    throw std::invalid_argument(fmt::format("'{}' is not JSON: {}", list.string(), ex.what()));
  }
  if (!j.is_object() || !j.contains("numbers") || !j.at("numbers").is_array())
    throw std::invalid_argument(fmt::format(
        "'{}' is not a list of quoted numbers; accepted: JSON {{\"numbers\": [entries]}}", list.string()));
  std::vector<QuotedNumber> numbers;
  std::set<std::string> macros;
  for (std::size_t i = 0; i < j.at("numbers").size(); ++i) {
    const json& e = j.at("numbers")[i];
    const auto bad = [&](const std::string& what) {
      const std::string name =
          e.is_object() && e.value("macro", json()).is_string() ? e.at("macro") : json("");
      throw std::invalid_argument(fmt::format("'{}': entry {} ('{}'): {}", list.string(), i + 1, name, what));
    };
    numbers.push_back(parse_entry(e, bad));
    if (!macros.insert(numbers.back().macro).second)
      bad("macro: defined by an entry before it; accepted: each macro once");
  }
  return numbers;
}

std::string quoted_value(const fs::path& results, const QuotedNumber& n) {
  const auto rows = read_csv(results / n.file);
  const CsvRecord* found = nullptr;
  for (const auto& row : rows) {
    const bool all = std::all_of(n.where.begin(), n.where.end(), [&](const auto& w) {
      return row.count(w.first) && cell_matches(row.at(w.first), w.second);
    });
    if (all) found = &row;
    if (all && !n.last) break;
  }
  std::string where;
  for (const auto& [column, value] : n.where) where += fmt::format(" {}={}", column, value);
  if (!found) throw std::runtime_error(fmt::format("{}: no row with{}", n.file, where));
  if (!found->count(n.column)) throw std::runtime_error(fmt::format("{}: no column '{}'", n.file, n.column));
  const std::string& cell = found->at(n.column);
  double x = 0;
  const bool number = parse_number(cell, x);
  // The paper quotes what it reads: an empty cell, NaN or infinity is a failed run's, not a result.
  if (cell.empty() || (number && !std::isfinite(x)) || (!number && (!n.format.empty() || n.scale != 1.0)))
    throw std::runtime_error(fmt::format("{}: column '{}' on the row with{} holds '{}', not a finite number",
                                         n.file, n.column, where, cell));
  if (n.format.empty() && n.scale == 1.0) return number ? latex_number(cell) : latex_escape(cell);
  return latex_number(fmt::format(fmt::runtime(n.format.empty() ? "{}" : n.format), n.scale * x));
}

}  // namespace contact
