// libFuzzer target spine_json (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz spine_json SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::spineJson(data, size);
}
