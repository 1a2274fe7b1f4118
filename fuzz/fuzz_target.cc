// A libFuzzer target for one loader (OBJSCAN_FUZZ_TARGET_NAME, see fuzz_input.h); built per target by
// fuzz/CMakeLists.txt with -DOBJSCAN_FUZZ=ON and run by scripts/fuzz.sh.
#include <cstdio>
#include <cstdlib>

#include "fuzz_input.h"

namespace {
const objscan::fuzz::Target kTarget = objscan::fuzz::TargetFromName(OBJSCAN_FUZZ_TARGET_NAME);
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    objscan::fuzz::RunInput(kTarget, data, size);
  } catch (const objscan::fuzz::ContractViolation& e) {
    std::fprintf(stderr, "objscan fuzz: contract violated: %s\n", e.what());
    std::abort();
  }
  return 0;
}
