#pragma once
// Command-line helpers shared by every experiment (CLI11).
// Contract: --help lists each option with its default and accepted range; bad input prints one
// line naming the option, the value given and the accepted range, and exits with code 2 before
// anything is written.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace contact::cli {

inline constexpr int kExitBadInput = 2;
inline constexpr int kExitFailure = 1;

// A real number in an interval; `lo_open`/`hi_open` exclude the ends. Rejects NaN, infinities
// and text that is not entirely a number.
CLI::Validator real_in(double lo, double hi, bool lo_open, bool hi_open);
inline CLI::Validator positive() { return real_in(0, HUGE_VAL, true, true); }
inline CLI::Validator non_negative() { return real_in(0, HUGE_VAL, false, true); }
inline CLI::Validator finite() { return real_in(-HUGE_VAL, HUGE_VAL, true, true); }
// A whole number >= lo (and <= hi).
CLI::Validator integer_at_least(long lo);
CLI::Validator integer_in(long lo, long hi);
// One of the names, or a comma-separated list of them when `list` is set.
CLI::Validator one_of(std::vector<std::string> names, bool list = false);

// Parses argv. Returns -1 to go on, or the exit code to return: 0 after --help, 2 after an
// error (its one-line message already printed on stderr).
int parse(CLI::App& app, int argc, char** argv);

// Splits "a,b,c", keeping empty items ("a,,b" and "a," have one), so that validators refuse them.
std::vector<std::string> split_list(const std::string& s);

// A comma-separated list of reals, each checked by `item`; an empty item is refused with the
// option's name. (CLI11's own delimiter drops empty items silently.)
CLI::Option* add_real_list(CLI::App& app, const std::string& name, std::vector<double>& values,
                           const std::string& help, const CLI::Validator& item);

}  // namespace contact::cli
