#include "rig/io/terrain_json.h"

#include "rig/error.h"

namespace stirrup::rig {

std::shared_ptr<const Terrain> parseTerrain(JsonObjectReader& r, const std::filesystem::path& base_dir) {
  (void)base_dir;
  const std::string source = r.file();
  if (r.has("hills")) {
    JsonObjectReader h = r.object("hills");
    HillsParams p;
    const int seed = h.integer("seed", static_cast<int>(p.seed));
    if (seed < 0) h.fail("seed", "expected a whole number from 0 to 2147483647, got " + std::to_string(seed));
    p.seed = static_cast<std::uint32_t>(seed);
    p.amplitude_cm = h.number("amplitude_cm", p.amplitude_cm);
    p.wavelength_cm = h.number("wavelength_cm", p.wavelength_cm);
    p.octaves = h.integer("octaves", p.octaves);
    h.finish();
    r.finish();
    return std::make_shared<const Terrain>(Terrain::hills(p, source));
  }
  r.finish();
  r.fail("hills", "expected \"hills\": {\"seed\", \"amplitude_cm\", \"wavelength_cm\", \"octaves\"}");
}

}  // namespace stirrup::rig
