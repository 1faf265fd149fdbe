#include "cli.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

namespace contact::cli {

namespace {

std::string bound(double v) {
  if (v == HUGE_VAL) return "inf";
  if (v == -HUGE_VAL) return "-inf";
  return fmt::format("{:g}", v);
}

}  // namespace

CLI::Validator real_in(double lo, double hi, bool lo_open, bool hi_open) {
  const std::string range =
      fmt::format("{}{}, {}{}", lo_open ? "(" : "[", bound(lo), bound(hi), hi_open ? ")" : "]");
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const char* begin = s.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(begin, &end);
        const bool number = end != begin && *end == '\0' && errno != ERANGE && std::isfinite(v);
        const bool inside = number && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
        if (inside) return {};
        return fmt::format("value '{}' is {}; accepted range {}", s,
                           number ? "out of range" : "not a finite number", range);
      },
      "in " + range);
}

CLI::Validator integer_in(long lo, long hi) {
  const std::string range = hi == std::numeric_limits<long>::max() ? fmt::format("integer >= {}", lo)
                                                                    : fmt::format("integer in [{}, {}]", lo, hi);
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const char* begin = s.c_str();
        char* end = nullptr;
        errno = 0;
        const long v = std::strtol(begin, &end, 10);
        if (end != begin && *end == '\0' && errno != ERANGE && v >= lo && v <= hi) return {};
        if (hi == std::numeric_limits<long>::max()) return fmt::format("value '{}' is not a whole number >= {}", s, lo);
        return fmt::format("value '{}' is not a whole number in [{}, {}]", s, lo, hi);
      },
      range);
}

CLI::Validator integer_at_least(long lo) { return integer_in(lo, std::numeric_limits<long>::max()); }

CLI::Validator one_of(std::vector<std::string> names, bool list) {
  const std::string accepted = fmt::format("{}", fmt::join(names, ", "));
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const auto items = list ? split_list(s) : std::vector<std::string>{s};
        for (const auto& item : items)
          if (std::find(names.begin(), names.end(), item) == names.end() || item.empty())
            return fmt::format("value '{}' is not one of: {}", item, accepted);
        return items.empty() ? fmt::format("value '' is not one of: {}", accepted) : std::string{};
      },
      (list ? "comma-separated list of: " : "one of: ") + accepted);
}

int parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return -1;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    std::cerr << app.get_name() << ": unknown option or argument: " << e.what()
              << " (see --help for the accepted options)\n";
  } catch (const CLI::ParseError& e) {
    std::cerr << app.get_name() << ": " << e.what() << "\n";
  }
  return kExitBadInput;
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  for (std::size_t comma = s.find(','); comma != std::string::npos; comma = s.find(',', begin)) {
    out.push_back(s.substr(begin, comma - begin));
    begin = comma + 1;
  }
  out.push_back(s.substr(begin));
  return out;
}

CLI::Option* add_real_list(CLI::App& app, const std::string& name, std::vector<double>& values,
                           const std::string& help, const CLI::Validator& item) {
  const std::string shown = fmt::format("{}", fmt::join(values, ","));
  CLI::Validator each(
      [item](std::string& s) -> std::string {
        for (std::string part : split_list(s)) {
          if (part.empty()) return fmt::format("value '{}' has an empty item; accepted: a comma-separated list, each {}", s, item.get_description());
          if (std::string err = item(part); !err.empty()) return err;
        }
        return {};
      },
      "comma-separated, each " + item.get_description());
  return app
      .add_option_function<std::string>(
          name,
          [&values](const std::string& s) {
            values.clear();
            for (const auto& part : split_list(s)) values.push_back(std::strtod(part.c_str(), nullptr));
          },
          help)
      ->check(each)
      ->default_str(shown);
}

}  // namespace contact::cli
