// libFuzzer target horse_csv (tests/fuzz/targets.h, docs/fuzzing.md): scripts/fuzz horse_csv SECONDS.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return stirrup::fuzz::horseCsv(data, size);
}
