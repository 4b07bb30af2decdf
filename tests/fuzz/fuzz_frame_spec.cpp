// libFuzzer target frame_spec (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz frame_spec SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::frameSpec(data, size);
}
