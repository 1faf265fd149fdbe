#pragma once
// Double's machine epsilon, 2^-52: the tests' round-off tolerances are stated as multiples of it.
// One definition for every test file (a label's files compile as one unit: tests/CMakeLists.txt).
#include <limits>

inline constexpr double kEps = std::numeric_limits<double>::epsilon();
