#pragma once
// Command-line options for every executable, without CLI11 in the header (it costs most of an
// experiment's compile time; only cli.cpp includes it).
// Contract: --help lists each option with its default and accepted range; bad input prints one
// line naming the option, the value given and the accepted range, and exits with code 2 before
// anything is written.
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace contact::cli {

inline constexpr int kExitBadInput = 2;
inline constexpr int kExitFailure = 1;

// A least accepted value as a refusal prints it: x rounded up to three significant digits, so that
// the printed value is accepted (up, never to nearest: a bound printed below x is refused again).
inline double rounded_up(double x) {
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2);
  return std::ceil(x / unit) * unit;
}

// A check of one value as typed: `description` is shown in --help; `error` returns "" when the
// value is accepted, else the message (naming the value and what is accepted).
struct Check {
  std::string description;
  std::function<std::string(const std::string&)> error;
};

// A real number in an interval; `lo_open`/`hi_open` exclude the ends. Rejects NaN, infinities
// and text that is not entirely a number.
Check real_in(double lo, double hi, bool lo_open, bool hi_open);
inline Check positive() { return real_in(0, HUGE_VAL, true, true); }
inline Check non_negative() { return real_in(0, HUGE_VAL, false, true); }
inline Check finite() { return real_in(-HUGE_VAL, HUGE_VAL, true, true); }
// A whole number >= lo (and <= hi).
Check integer_at_least(long lo);
Check integer_in(long lo, long hi);
// One of the names, or a comma-separated list of them when `list` is set.
Check one_of(std::vector<std::string> names, bool list = false);
// A comma-separated list of the names, or "all" (and "none" when allow_none is set).
Check some_of(std::vector<std::string> names, bool allow_none = false);
Check existing_file();
Check existing_folder();

// Splits "a,b,c", keeping empty items ("a,,b" and "a," have one), so that checks refuse them.
std::vector<std::string> split_list(const std::string& s);
// What a some_of option chose: every one of `names` for "all", none for "none", else the listed.
std::vector<std::string> chosen(const std::string& value, const std::vector<std::string>& names);

// The options of one program. Values are bound to the caller's variables, whose values at
// declaration are the defaults --help shows.
class Options {
 public:
  Options(std::string program, std::string description);
  ~Options();
  Options(const Options&) = delete;
  Options& operator=(const Options&) = delete;

  void add(const std::string& flag, double& value, const std::string& help, const Check& check = {});
  // An option read only when given (Options::given), whose variable's initial value means nothing:
  // its help shows no default ("in (0, inf)=0" read as a default outside its own range).
  void add_unset(const std::string& flag, double& value, const std::string& help, const Check& check);
  void add(const std::string& flag, long& value, const std::string& help, const Check& check = {});
  void add(const std::string& flag, std::string& value, const std::string& help, const Check& check = {});
  // Exactly `count` values after the flag, each checked (e.g. --half-extents 0.3 0.2 0.1).
  void add(const std::string& flag, std::vector<double>& values, std::size_t count, const std::string& help,
           const Check& each);
  // A comma-separated list of reals, each checked; an empty item is refused with the option's name.
  void add_list(const std::string& flag, std::vector<double>& values, const std::string& help,
                const Check& each);
  void add_flag(const std::string& flag, bool& value, const std::string& help);

  // Parses argv. Returns -1 to go on, or the exit code to return: 0 after --help, 2 after an
  // error (its one-line message already printed on stderr). With `speak` false it prints nothing
  // and returns the same: every MPI rank parses, one of them speaks for all.
  int parse(int argc, char** argv, bool speak = true);
  bool given(const std::string& flag) const;
  const std::string& program() const { return program_; }
  // Every option with its value as given or its default, as JSON text ({"name": value, ...}).
  std::string values_json() const;

 private:
  struct Impl;
  std::string program_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contact::cli
