#pragma once
// What a call refuses with: the message of the std::invalid_argument it throws, or "" if it
// throws none. One definition for every test file (a label's files compile as one unit:
// tests/CMakeLists.txt).
#include <stdexcept>
#include <string>

template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
