// libFuzzer target profile_sets (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz profile_sets SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::profileSets(data, size);
}
