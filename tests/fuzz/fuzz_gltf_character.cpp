// libFuzzer target gltf_character (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz gltf_character SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::gltfCharacter(data, size);
}
