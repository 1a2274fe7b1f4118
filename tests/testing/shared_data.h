#pragma once
// Locating ../shared/data for tests. A test that needs it and cannot find it skips loudly.
#include <gtest/gtest.h>

#include <string>

namespace objscan::testing {

// The shared data folder (../shared/data relative to the project root, or $OBJSCAN_SHARED_DATA),
// or an empty string when it is not there.
std::string SharedDataDir();
// Absolute path of the project root (for config/ files).
std::string ProjectRoot();
// Prints a loud warning on stderr; use through OBJSCAN_REQUIRE_SHARED_DATA.
void WarnMissingSharedData(const char* test_name);

}  // namespace objscan::testing

// Sets `var` to the shared data folder or skips the test with a loud message.
#define OBJSCAN_REQUIRE_SHARED_DATA(var)                                                     \
  const std::string var = ::objscan::testing::SharedDataDir();                               \
  if (var.empty()) {                                                                         \
    ::objscan::testing::WarnMissingSharedData(                                               \
        ::testing::UnitTest::GetInstance()->current_test_info()->name());                    \
    GTEST_SKIP() << "SKIPPED: ../shared/data not found (set OBJSCAN_SHARED_DATA)";          \
  }
