#include "cli.hpp"
#include "output.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <set>

namespace contact::cli {

namespace {

std::string bound(double v) {
  if (v == HUGE_VAL) return "inf";
  if (v == -HUGE_VAL) return "-inf";
  return fmt::format("{:g}", v);
}

}  // namespace

Check real_in(double lo, double hi, bool lo_open, bool hi_open) {
  const std::string range =
      fmt::format("{}{}, {}{}", lo_open ? "(" : "[", bound(lo), bound(hi), hi_open ? ")" : "]");
  return Check{"in " + range, [=](const std::string& s) -> std::string {
                 const char* begin = s.c_str();
                 char* end = nullptr;
                 errno = 0;
                 const double v = std::strtod(begin, &end);
                 const bool parsed = end != begin && *end == '\0';
                 // strtod flags a value below the smallest normal double (4.9e-324, 1e-400) with
                 // ERANGE, as it does one past the largest: refused either way, but it is finite.
                 const bool underflow = parsed && errno == ERANGE && std::abs(v) < DBL_MIN;
                 const bool number = parsed && errno != ERANGE && std::isfinite(v);
                 const bool inside = number && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
                 if (inside) return {};
                 return fmt::format("value '{}' is {}; accepted range {}", s,
                                    underflow
                                        ? fmt::format("below the smallest normal double ({:g})", DBL_MIN)
                                    : number ? "out of range"
                                             : "not a finite number",
                                    range);
               }};
}

Check integer_in(long lo, long hi) {
  const std::string range = hi == std::numeric_limits<long>::max()
                                ? fmt::format("integer >= {}", lo)
                                : fmt::format("integer in [{}, {}]", lo, hi);
  return Check{range, [=](const std::string& s) -> std::string {
                 const char* begin = s.c_str();
                 char* end = nullptr;
                 errno = 0;
                 const long v = std::strtol(begin, &end, 10);
                 if (end != begin && *end == '\0' && errno != ERANGE && v >= lo && v <= hi) return {};
                 if (hi == std::numeric_limits<long>::max())
                   return fmt::format("value '{}' is not a whole number >= {}", s, lo);
                 return fmt::format("value '{}' is not a whole number in [{}, {}]", s, lo, hi);
               }};
}

Check integer_at_least(long lo) { return integer_in(lo, std::numeric_limits<long>::max()); }

Check one_of(std::vector<std::string> names, bool list) {
  const std::string accepted = fmt::format("{}", fmt::join(names, ", "));
  return Check{(list ? "comma-separated list of: " : "one of: ") + accepted,
               [=](const std::string& s) -> std::string {
                 const auto items = list ? split_list(s) : std::vector<std::string>{s};
                 std::set<std::string> seen;
                 for (const auto& item : items) {
                   if (std::find(names.begin(), names.end(), item) == names.end() || item.empty())
                     return fmt::format("value '{}' is not one of: {}", item, accepted);
                   // "penalty,penalty" ran it twice; "penalty,all" passed here and failed later
                   if (!seen.insert(item).second)
                     return fmt::format("value '{}' names '{}' twice; accepted: each name once", s, item);
                   if (items.size() > 1 && (item == "all" || item == "none"))
                     return fmt::format(
                         "value '{}' lists '{}', which stands alone; accepted: {} alone, or a "
                         "list of the others",
                         s, item, item);
                 }
                 return items.empty() ? fmt::format("value '' is not one of: {}", accepted) : std::string{};
               }};
}

Check some_of(std::vector<std::string> names, bool allow_none) {
  names.insert(names.begin(), "all");
  if (allow_none) names.emplace_back("none");
  return one_of(std::move(names), true);
}

std::vector<std::string> chosen(const std::string& value, const std::vector<std::string>& names) {
  if (value == "all") return names;
  if (value == "none") return {};
  return split_list(value);
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

Check existing_file() {
  return {"an existing file", [](const std::string& s) -> std::string {
            std::error_code ec;
            return std::filesystem::is_regular_file(s, ec)
                       ? ""
                       : fmt::format("value '{}' is not an existing file", s);
          }};
}

Check existing_folder() {
  return {"an existing folder", [](const std::string& s) -> std::string {
            std::error_code ec;
            return std::filesystem::is_directory(s, ec)
                       ? ""
                       : fmt::format("value '{}' is not an existing folder", s);
          }};
}

namespace {

CLI::Validator validator(const Check& c) {
  return CLI::Validator([error = c.error](std::string& s) { return error(s); }, c.description);
}

// Each item of a comma-separated list checked by `each`.
Check each_item(const Check& each) {
  return {"comma-separated, each " + each.description, [each](const std::string& s) -> std::string {
            for (const std::string& part : split_list(s)) {
              if (part.empty())
                return fmt::format("value '{}' has an empty item; accepted: a comma-separated list, each {}",
                                   s, each.description);
              if (std::string err = each.error(part); !err.empty()) return err;
            }
            std::map<double, std::string> seen;  // each a number now: the same one twice ran twice
            for (const std::string& part : split_list(s))
              if (const auto [it, added] = seen.emplace(std::strtod(part.c_str(), nullptr), part); !added)
                return fmt::format("value '{}' gives {} twice{}; accepted: each value once", s, part,
                                   part == it->second ? "" : fmt::format(" (as '{}')", it->second));
            return {};
          }};
}

}  // namespace

struct Options::Impl {
  CLI::App app;
  Impl(const std::string& description, const std::string& name) : app(description, name) {
    app.option_defaults()->always_capture_default();
  }
  CLI::Option* checked(CLI::Option* o, const Check& check) {
    return check.error ? o->check(validator(check)) : o;
  }
};

Options::Options(std::string program, std::string description)
    : program_(std::move(program)), impl_(std::make_unique<Impl>(description, program_)) {}
Options::~Options() = default;

void Options::add(const std::string& flag, double& value, const std::string& help, const Check& check) {
  impl_->checked(impl_->app.add_option(flag, value, help), check);
}
void Options::add_unset(const std::string& flag, double& value, const std::string& help, const Check& check) {
  impl_->checked(impl_->app.add_option(flag, value, help), check)->default_str("");
}
void Options::add(const std::string& flag, long& value, const std::string& help, const Check& check) {
  impl_->checked(impl_->app.add_option(flag, value, help), check);
}
void Options::add(const std::string& flag, std::string& value, const std::string& help, const Check& check) {
  impl_->checked(impl_->app.add_option(flag, value, help), check);
}
void Options::add(const std::string& flag, std::vector<double>& values, std::size_t count,
                  const std::string& help, const Check& each) {
  impl_->checked(impl_->app.add_option(flag, values, help)->expected(static_cast<int>(count)), each);
}
void Options::add_list(const std::string& flag, std::vector<double>& values, const std::string& help,
                       const Check& each) {
  const std::string shown = fmt::format("{}", fmt::join(values, ","));
  impl_->app
      .add_option_function<std::string>(
          flag,
          [&values](const std::string& s) {
            values.clear();
            for (const auto& part : split_list(s)) values.push_back(std::strtod(part.c_str(), nullptr));
          },
          help)
      ->check(validator(each_item(each)))
      ->default_str(shown);
}
void Options::add_flag(const std::string& flag, bool& value, const std::string& help) {
  impl_->app.add_flag(flag, value, help);
}

int Options::parse(int argc, char** argv, bool speak) {
  CLI::App& app = impl_->app;
  std::ostream silent(nullptr);  // no buffer: what is written to it goes nowhere
  std::ostream& out = speak ? std::cout : silent;
  std::ostream& err = speak ? std::cerr : silent;
  try {
    app.parse(argc, argv);
    return -1;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ExtrasError& e) {
    err << app.get_name() << ": unknown option or argument: " << e.what()
        << " (see --help for the accepted options)\n";
  } catch (const CLI::ParseError& e) {
    err << app.get_name() << ": " << e.what() << "\n";
  }
  return kExitBadInput;
}

bool Options::given(const std::string& flag) const { return impl_->app.get_option(flag)->count() > 0; }

std::string Options::values_json() const {
  nlohmann::json options = nlohmann::json::object();
  for (const CLI::Option* opt : impl_->app.get_options()) {
    const std::string name = opt->get_single_name();
    if (name.empty() || name == "help") continue;
    if (opt->get_expected_min() == 0) {
      options[name] = opt->count() > 0;  // a flag
    } else {
      // Every value given (a list option has several, or one comma-separated string).
      options[name] =
          opt->count() > 0 ? fmt::format("{}", fmt::join(opt->results(), ",")) : opt->get_default_str();
    }
  }
  return json_text(options);
}

}  // namespace contact::cli
