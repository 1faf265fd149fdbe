// The paper reads only what the experiments produce: every table it \inputs is the LaTeX
// rendering of a CSV some experiment declares in the study's manifest, every figure the PDF of a
// declared PNG, and the quoted numbers come from paper_numbers' numbers.tex. And paper/ holds no
// generated file. (Whether it builds is the paper_builds test, where LaTeX is installed.)
#include "cli_fixture.hpp"
#include "study_manifest.hpp"

#include <regex>
#include <set>

using namespace contact;

TEST(PaperInputs, EveryInputIsADeclaredExperimentOutput) {
  const StudyManifest manifest = load_study_manifest(STUDY_MANIFEST);
  std::set<std::string> declared;
  for (const auto& e : manifest.experiments)
    for (const auto& o : e.outputs) declared.insert(e.name + "/" + o.file);
  const std::string tex = slurp(fs::path(PAPER_DIR) / "paper.tex");
  // \input{x}, \widetable{x}, \fig{x} or \fig[width]{x}, \includegraphics[...]{x}
  const std::regex use(R"(\\(input|widetable|fig|includegraphics)(\[[^\]]*\])?\{([^}#]+)\})");
  std::size_t tables = 0, figures = 0;
  for (std::sregex_iterator it(tex.begin(), tex.end(), use), end; it != end; ++it) {
    const std::string path = (*it)[3];
    if (path == "numbers.tex") continue;   // written by paper_numbers from the results
    if (path == "preamble.tex") continue;  // the paper's own class and packages (paper/)
    const fs::path p(path);
    ASSERT_TRUE(p.extension() == ".tex" || p.extension() == ".pdf") << path;
    const std::string source =
        fs::path(p).replace_extension(p.extension() == ".tex" ? ".csv" : ".png").string();
    EXPECT_TRUE(declared.count(source))
        << path << " is not the rendering of a declared output (" << source << ")";
    (p.extension() == ".tex" ? tables : figures) += 1;
  }
  EXPECT_GE(tables, 5u);
  EXPECT_GE(figures, 10u);
}

TEST(PaperInputs, PaperFolderHoldsOnlySources) {
  const std::set<std::string> sources = {"paper.tex", "preamble.tex", "references.bib", "numbers.json",
                                         "CMakeLists.txt"};
  for (const auto& entry : fs::directory_iterator(PAPER_DIR))
    EXPECT_TRUE(sources.count(entry.path().filename().string()))
        << entry.path() << " is not a source of the paper";
}

// paper_numbers reads the study's CSVs with read_csv: it gives back what Table::to_csv wrote,
// quoted commas and quotes included, by column name.
TEST(PaperInputs, CsvReadsBackWhatTablesWrite) {
  contact::Table t({"name", "value"});
  t.add_row({std::string("a, \"b\""), 1.5});
  t.add_row({std::string("c"), 2L});
  const fs::path file = fs::temp_directory_path() / ("contact_csv_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(file) << t.to_csv();
  const auto rows = contact::read_csv(file);
  fs::remove(file);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("name"), "a, \"b\"");
  EXPECT_DOUBLE_EQ(std::stod(rows[0].at("value")), 1.5);
  EXPECT_EQ(rows[1].at("value"), "2");
  EXPECT_THROW(contact::read_csv(file), std::runtime_error);
}

// A CSV written elsewhere reads the same: CRLF line ends are not part of the last cell, a blank last
// line is no row; a quoted
// newline is part of its cell (Table::to_csv quotes one). A file that is not a table is refused
// naming the file and the record: a row cut short or run on (their cells used to be dropped or
// shifted silently), a quote not closed, an empty file. LaTeX's ten specials are escaped.
TEST(PaperInputs, CsvReadsOnlyTables) {
  const fs::path file = fs::temp_directory_path() / ("contact_csv_" + std::to_string(::getpid()) + ".csv");
  const auto read = [&](const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
    return contact::read_csv(file);
  };
  auto rows = read("name,value\r\n\"a\nb\",1.5\r\nc,2\r\n\r\n");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("name"), "a\nb");
  EXPECT_EQ(rows[1].at("value"), "2");
  contact::Table t({"name"});
  t.add_row({std::string("two\nlines")});
  EXPECT_EQ(read(t.to_csv()).at(0).at("name"), "two\nlines");
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"a,b\n1,2\n3\n", "row 2 has 1 cells, the header 2"},
           {"a,b\n1,2,3\n", "row 1 has 3 cells, the header 2"},
           {"a,b\n\"1,2\n", "record 2: a quoted cell is not closed"},
           {"", "empty, not even a header"}}) {
    try {
      read(text);
      ADD_FAILURE() << text << " was read";
    } catch (const std::runtime_error& ex) {
      EXPECT_EQ(std::string(ex.what()), file.string() + ": " + message);
    }
  }
  fs::remove(file);
  EXPECT_EQ(contact::latex_escape("a&b%c$d#e_f{g}h~i^j\\k"),
            "a\\&b\\%c\\$d\\#e\\_f\\{g\\}h\\textasciitilde{}i\\textasciicircum{}j\\textbackslash{}k");
}

// A CSV cell holds the shortest text that reads back as its double: exact, and what a reader types
// to find it (0.2, not 0.20000000000000001; 1e-05, not 1.0000000000000001e-05).
TEST(PaperInputs, CsvNumbersAreTheShortestTextThatReadsBackExactly) {
  contact::Table t({"value"});
  for (double v : {0.2, 1e-5, 1000.0, 1.0 / 3, 9.810000000000374e-05, 1e300}) t.add_row({v});
  EXPECT_EQ(t.to_csv(), "value\n0.2\n1e-05\n1000\n0.3333333333333333\n9.810000000000374e-05\n1e+300\n");
  std::istringstream csv(t.to_csv());
  std::string cell;
  std::getline(csv, cell);
  for (const auto& row : t.rows()) {
    std::getline(csv, cell);
    EXPECT_EQ(std::stod(cell), std::get<double>(row[0])) << cell;
  }
}

// A negated zero (the stack's top sink -y at y = 0) prints as 0 in every format, not "-0".
TEST(PaperInputs, ZeroPrintsWithoutASign) {
  contact::Table t({"sink_m"});
  t.add_row({-0.0});
  EXPECT_EQ(t.to_csv(), "sink_m\n0\n");
  EXPECT_EQ(t.to_markdown(4).find("-0"), std::string::npos) << t.to_markdown(4);
}

// A pivot spreads a long table by one column: each (row, across) pair's value lands in its cell,
// the kept columns come from the row's first appearance, a missing pair is NaN.
TEST(PaperInputs, PivotSpreadsALongTable) {
  contact::Table t({"method", "setting", "scene", "error"});
  t.add_row({std::string("a"), std::string("x"), std::string("drop"), 1.0});
  t.add_row({std::string("a"), std::string("ignored"), std::string("stack"), 2.0});
  t.add_row({std::string("b"), std::string("y"), std::string("drop"), 3.0});
  const contact::Table p = contact::pivot(t, "method", {"setting"}, "scene", "error");
  EXPECT_EQ(p.columns(), (std::vector<std::string>{"method", "setting", "drop", "stack"}));
  ASSERT_EQ(p.rows().size(), 2u);
  EXPECT_EQ(std::get<std::string>(p.rows()[0][1]), "x");
  EXPECT_EQ(std::get<double>(p.rows()[0][3]), 2.0);
  EXPECT_EQ(std::get<double>(p.rows()[1][2]), 3.0);
  EXPECT_TRUE(std::isnan(std::get<double>(p.rows()[1][3])));
  EXPECT_THROW(contact::pivot(t, "method", {}, "nope", "error"), std::invalid_argument);
}
