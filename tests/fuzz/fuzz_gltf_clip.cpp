// libFuzzer target gltf_clip (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz gltf_clip SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::gltfClip(data, size);
}
