// property_main.cpp — the main of every property executable: a pinned RapidCheck seed by default.
//
// RapidCheck reads RC_PARAMS once, at its first use, so this main sets it before any test runs:
// the defaults below, followed by whatever the user's RC_PARAMS says (a later key wins, so
// `RC_PARAMS="seed=7"` or `RC_PARAMS="max_success=1000"` override one default and keep the rest).
// The defaults are compiled in from the CMake cache variables SHADOWREF_PROPERTY_SEED and
// SHADOWREF_PROPERTY_CASES. The pinned seed makes CI repeatable; a failure prints its
// `reproduce=` string.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
  std::string params = SHADOWREF_RC_DEFAULTS;
  if (const char* user = std::getenv("RC_PARAMS")) params += std::string(" ") + user;
  setenv("RC_PARAMS", params.c_str(), 1);
  ::testing::InitGoogleTest(&argc, argv);
  std::cout << "RC_PARAMS=\"" << params << "\"\n";
  return RUN_ALL_TESTS();
}
