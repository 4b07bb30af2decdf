// libFuzzer target farm_manifest (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz farm_manifest SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::farmManifest(data, size);
}
