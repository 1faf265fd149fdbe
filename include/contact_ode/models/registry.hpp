#pragma once
// What every registry (laws, scenes, methods, integrators) does with its list of named entries:
// list the names, and find one by name or refuse it naming the option and what is accepted.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace contact {

template <class Entry>
std::vector<std::string> names_of(const std::vector<Entry>& entries) {
  std::vector<std::string> names;
  for (const auto& e : entries) names.push_back(e.name);
  return names;
}

// Throws std::invalid_argument "<option>: value '<name>' is not one of: <names>".
template <class Entry>
const Entry& find_named(const std::vector<Entry>& entries, const std::string& name, std::string_view option) {
  const auto it =
      std::find_if(entries.begin(), entries.end(), [&](const Entry& e) { return e.name == name; });
  if (it == entries.end())
    throw std::invalid_argument(
        fmt::format("{}: value '{}' is not one of: {}", option, name, fmt::join(names_of(entries), ", ")));
  return *it;
}

}  // namespace contact
