#pragma once
// Results of an experiment are gathered in memory and written only once the experiment has
// succeeded, into a staging folder beside --out that then replaces --out whole: a failed, refused
// or interrupted run leaves no file and keeps the previous results, and a folder never mixes the
// files of two runs.
#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace contact {

class Table;

// A folder removed with everything in it when its owner goes out of scope; clear `path` to keep it.
struct ScratchDir {
  std::filesystem::path path;
  ScratchDir() = default;
  explicit ScratchDir(std::filesystem::path p) : path(std::move(p)) {}
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir();
};

// A new private folder in the temporary directory (mkdtemp: unique, not guessable), named
// STEM_XXXXXX; throws std::invalid_argument naming TMPDIR and its value (bad input: exit 2) when
// the temporary directory is missing, not a folder or not writable, and std::runtime_error on any
// other failure (a full disk). Own it with a ScratchDir.
std::filesystem::path make_scratch_dir(const std::string& stem);

// Throws as make_scratch_dir does unless a scratch folder can be made: checked before any work, so
// that a TMPDIR that is not a folder is refused at once, not after a run, when figures are drawn.
void require_scratch_location();

// A figure drawn by gnuplot (figure.hpp): NAME.png, NAME.pdf and the script NAME.gp.
struct Figure {
  std::string name;    // file stem: NAME.png, NAME.pdf, NAME.gp
  std::string data;    // CSV the script reads as 'data.csv'
  std::string script;  // gnuplot commands after the terminal and output lines; plots 'data.csv'
};

class OutputSet {
 public:
  void add(const std::string& name, std::string content) { files_[name] = std::move(content); }
  // name.csv, name.md and name.tex.
  void add_table(const std::string& name, const Table& table);
  // Figures wait here to be drawn together (draw_figures in figure.hpp: one gnuplot run for all of
  // an experiment's figures, not one each; a run's start costs as much as a simple figure).
  void queue_figure(Figure figure) { figures_.push_back(std::move(figure)); }
  std::vector<Figure> take_figures() { return std::exchange(figures_, {}); }
  // Writes every file into a staging folder and swaps it in as `dir` (the previous `dir`, an
  // earlier run's results, is removed only then). Throws std::runtime_error naming the path on
  // failure, having removed the staging folder, and std::logic_error while figures wait undrawn.
  // A `dir` that check_output_dir(dir, program) refuses (a folder holding anything but an earlier
  // run's results of `program`) is never replaced: the refusal is thrown.
  void write(const std::filesystem::path& dir, const std::string& program) const;
  // Adds the files to the existing folder `dir`, each written to a temporary name and renamed
  // into place (the study's index beside the experiments' folders).
  void write_into(const std::filesystem::path& dir) const;
  const std::map<std::string, std::string>& files() const { return files_; }

 private:
  std::map<std::string, std::string> files_;
  std::vector<Figure> figures_;
};

// meta.json, the record every program leaves beside its results: the program's name (which makes
// the folder its earlier --out, replaceable by its next run), its options (a JSON object), the
// command line, the source revision, the libraries' versions, the wall time and the MPI ranks.
std::string run_meta_json(const std::string& program, const std::string& options_json,
                          const std::vector<std::string>& command_line, double wall_time_s, int ranks);

// JSON text that any run can write. A path or an option is bytes on Linux, not always UTF-8 (a
// folder named in Latin-1), and nlohmann's dump throws on a byte that is not: a run with such an
// --out, or built in such a folder, did all its work and then failed writing meta.json. Such a
// byte is written as U+FFFD instead (the record loses that byte, the run nothing).
std::string json_text(const nlohmann::json& value, int indent = -1);

// A path that names something inside the folder it is taken from: relative, non-empty, with no
// ".." (a manifest's outputs, the paper's quoted files).
bool stays_inside(const std::filesystem::path& p);

// The folder --out names, absolute: through a link to a folder, the folder it points to (its
// results are replaced there, the link kept). Sets `ec` when it cannot be resolved.
std::filesystem::path results_folder(const std::filesystem::path& dir, std::error_code& ec);

// Checks before running that --out can receive the results: not empty, not a file or under one,
// every name short enough for the staging folder beside it, the nearest existing folder
// writable, and, if it exists, empty or an earlier run's results of `program` (its meta.json names
// it), since it will be replaced whole; another program's results are not (ball_drop --out
// results/zeno replaced zeno's). An empty `program` skips this: the folder is written into, not
// replaced. Returns an error line naming --out, or "".
std::string check_output_dir(const std::filesystem::path& dir, const std::string& program);

}  // namespace contact
