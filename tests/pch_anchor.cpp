// The source the tests' precompiled header is built with (contact_test_pch, tests/CMakeLists.txt):
// an executable with GoogleTest's main and no tests.
