#include "contact_ode/analysis/table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace contact {

namespace {

std::string render(const Table::Cell& c, int digits) {
  struct Render {
    int digits;
    std::string operator()(const std::string& s) const { return s; }
    std::string operator()(long v) const { return fmt::format("{}", v); }
    std::string operator()(double v) const {
      if (std::isnan(v)) return digits > 0 ? "—" : "nan";
      v += 0.0;  // a zero's sign is an artefact of a negation (a sink of -y at y = 0): print 0
      // Full precision (digits 0, the CSV files) is the shortest text that reads back as the same
      // double: 0.2, not 0.20000000000000001.
      return digits > 0 ? fmt::format("{:.{}g}", v, digits) : fmt::format("{}", v);
    }
  };
  return std::visit(Render{digits}, c);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

// A rendered number as LaTeX: "3.2e-05" becomes $3.2\times10^{-5}$; text is escaped.
std::string latex_cell(const Table::Cell& c, int digits) {
  const std::string s = render(c, digits);
  if (s == "—") return "--";
  if (!std::holds_alternative<double>(c)) return latex_escape(s);
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  const int exponent = std::stoi(s.substr(e + 1));
  const std::string mantissa = s.substr(0, e);
  return mantissa == "1" ? fmt::format("$10^{{{}}}$", exponent)
                         : fmt::format("${}\\times10^{{{}}}$", mantissa, exponent);
}

}  // namespace

std::string latex_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      case '&':
      case '%':
      case '$':
      case '#':
      case '_':
      case '{':
      case '}':
        out += '\\';
        out += ch;
        break;
      default:
        out += ch;
    }
  }
  return out;
}

void Table::set_latex_header(std::vector<std::string> header) {
  if (header.size() != columns_.size())
    throw std::invalid_argument(
        fmt::format("LaTeX header has {} cells, the table {} columns", header.size(), columns_.size()));
  for (auto& cell : header) {
    if (cell.find('\n') == std::string::npos) continue;
    for (std::size_t nl; (nl = cell.find('\n')) != std::string::npos;) cell.replace(nl, 1, "\\\\");
    cell = "\\shortstack{" + cell + "}";
  }
  latex_header_ = std::move(header);
}

void Table::add_row(std::vector<Cell> row) {
  if (row.size() != columns_.size())
    throw std::invalid_argument(
        fmt::format("table row has {} cells, header has {}", row.size(), columns_.size()));
  rows_.push_back(std::move(row));
}

std::string Table::to_csv() const {
  std::string out;
  auto field = [&](std::size_t j, const std::string& s) {
    if (j > 0) out += ',';
    out += csv_field(s);
  };
  for (std::size_t j = 0; j < columns_.size(); ++j) field(j, columns_[j]);
  out += '\n';
  for (const auto& row : rows_) {
    for (std::size_t j = 0; j < row.size(); ++j) field(j, render(row[j], 0));
    out += '\n';
  }
  return out;
}

std::string Table::to_markdown(int digits) const {
  std::vector<std::vector<std::string>> cells;
  std::vector<std::size_t> width(columns_.size(), 3);
  for (std::size_t j = 0; j < columns_.size(); ++j) width[j] = std::max(width[j], columns_[j].size());
  for (const auto& row : rows_) {
    auto& r = cells.emplace_back();
    for (std::size_t j = 0; j < row.size(); ++j) {
      r.push_back(render(row[j], digits));
      width[j] = std::max(width[j], r.back().size());
    }
  }
  auto line = [&](const std::vector<std::string>& r) {
    std::string s = "|";
    for (std::size_t j = 0; j < r.size(); ++j) s += fmt::format(" {:<{}} |", r[j], width[j]);
    return s + "\n";
  };
  std::string out = line(columns_) + "|";
  for (auto w : width) out += std::string(w + 2, '-') + "|";
  out += "\n";
  for (const auto& r : cells) out += line(r);
  return out;
}

std::string Table::to_latex(int digits) const {
  std::string out = "\\begin{tabular}{" + std::string(columns_.size(), 'r') + "}\n\\toprule\n";
  auto cell = [&](std::size_t j, const std::string& s) { out += (j > 0 ? " & " : "") + s; };
  for (std::size_t j = 0; j < columns_.size(); ++j)
    cell(j, latex_header_.empty() ? latex_escape(columns_[j]) : latex_header_[j]);
  out += " \\\\\n\\midrule\n";
  for (const auto& row : rows_) {
    for (std::size_t j = 0; j < row.size(); ++j) cell(j, latex_cell(row[j], digits));
    out += " \\\\\n";
  }
  return out + "\\bottomrule\n\\end{tabular}\n";
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"') {
      cells.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = begin;  // the record's end: the first newline outside quotes
    bool quoted = false;
    for (; end < text.size() && (quoted || text[end] != '\n'); ++end) quoted ^= text[end] == '"';
    if (quoted)
      throw std::runtime_error(fmt::format("record {}: a quoted cell is not closed", records.size() + 1));
    std::string record = text.substr(begin, end - begin);
    if (!record.empty() && record.back() == '\r') record.pop_back();  // a CRLF file
    records.push_back(split_csv_line(record));
    begin = end + 1;
  }
  return records;
}

std::vector<CsvRecord> read_csv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", path.string()));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw std::runtime_error(fmt::format("cannot read {}", path.string()));
  std::vector<std::vector<std::string>> records;
  try {
    records = parse_csv(text);
  } catch (const std::runtime_error& ex) {
    throw std::runtime_error(fmt::format("{}: {}", path.string(), ex.what()));
  }
  if (records.empty()) throw std::runtime_error(fmt::format("{}: empty, not even a header", path.string()));
  const auto& header = records.front();
  std::vector<CsvRecord> rows;
  for (std::size_t r = 1; r < records.size(); ++r) {
    if (records[r].size() == 1 && records[r][0].empty()) continue;  // a blank line (an editor's last)
    if (records[r].size() != header.size())  // a row cut short or run together: not a table
      throw std::runtime_error(fmt::format("{}: row {} has {} cells, the header {}", path.string(), r,
                                           records[r].size(), header.size()));
    CsvRecord row;
    for (std::size_t i = 0; i < header.size(); ++i) row[header[i]] = records[r][i];
    rows.push_back(std::move(row));
  }
  return rows;
}

Table pivot(const Table& t, const std::string& row, const std::vector<std::string>& keep,
            const std::string& across, const std::string& value) {
  auto index = [&](const std::string& name) {
    const auto it = std::find(t.columns().begin(), t.columns().end(), name);
    if (it == t.columns().end()) throw std::invalid_argument("pivot: no column '" + name + "'");
    return static_cast<std::size_t>(it - t.columns().begin());
  };
  const std::size_t r = index(row), a = index(across), v = index(value);
  auto text = [](const Table::Cell& c) {
    return std::holds_alternative<std::string>(c) ? std::get<std::string>(c) : std::string();
  };
  std::vector<std::string> rows, columns;
  for (const auto& cells : t.rows()) {
    if (std::find(rows.begin(), rows.end(), text(cells[r])) == rows.end()) rows.push_back(text(cells[r]));
    if (std::find(columns.begin(), columns.end(), text(cells[a])) == columns.end())
      columns.push_back(text(cells[a]));
  }
  std::vector<std::string> header{row};
  header.insert(header.end(), keep.begin(), keep.end());
  header.insert(header.end(), columns.begin(), columns.end());
  Table out(header);
  for (const auto& name : rows) {
    std::vector<Table::Cell> cells{name};
    std::vector<Table::Cell> spread(columns.size(), std::nan(""));
    bool first = true;
    for (const auto& source : t.rows()) {
      if (text(source[r]) != name) continue;
      if (first)
        for (const auto& k : keep) cells.push_back(source[index(k)]);
      first = false;
      const auto c = static_cast<std::size_t>(std::find(columns.begin(), columns.end(), text(source[a])) -
                                              columns.begin());
      spread[c] = source[v];
    }
    cells.insert(cells.end(), spread.begin(), spread.end());
    out.add_row(cells);
  }
  return out;
}

}  // namespace contact
