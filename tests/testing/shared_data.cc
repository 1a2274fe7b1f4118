#include "shared_data.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace objscan::testing {

std::string ProjectRoot() { return OBJSCAN_PROJECT_ROOT; }

std::string SharedDataDir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("OBJSCAN_SHARED_DATA"); env && fs::is_directory(env)) return env;
  const fs::path candidate = fs::path(ProjectRoot()) / ".." / "shared" / "data";
  if (fs::is_directory(candidate)) return fs::canonical(candidate).string();
  return "";
}

void WarnMissingSharedData(const char* test_name) {
  std::fprintf(stderr,
               "\n*** WARNING: test %s SKIPPED: ../shared/data not found next to the project "
               "(or via OBJSCAN_SHARED_DATA) ***\n\n",
               test_name);
}

}  // namespace objscan::testing
