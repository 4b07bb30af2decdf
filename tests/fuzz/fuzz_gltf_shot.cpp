// libFuzzer target gltf_shot (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz gltf_shot SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::gltfShot(data, size);
}
