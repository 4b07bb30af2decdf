#include "scene/terrain_json.h"

#include "rig/error.h"
#include "rig/io/gltf_terrain.h"

namespace stirrup::scene {

std::shared_ptr<const rig::Terrain> parseTerrain(rig::JsonObjectReader& r, const std::filesystem::path& base_dir) {
  const std::string source = r.file();
  if (r.has("file") && r.has("hills")) r.fail("file", "expected either \"file\" or \"hills\", not both");
  if (r.has("file")) {
    const std::string file = r.string("file", "");
    r.finish();
    const std::filesystem::path path = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : base_dir / file;
    return std::make_shared<const rig::Terrain>(rig::Terrain::mesh(rig::loadTerrainGltf(path, source + ": " + r.fieldPath("file"))));
  }
  if (r.has("hills")) {
    rig::JsonObjectReader h = r.object("hills");
    rig::HillsParams p;
    const int seed = h.integer("seed", static_cast<int>(p.seed));
    if (seed < 0) h.fail("seed", "expected a whole number from 0 to 2147483647, got " + std::to_string(seed));
    p.seed = static_cast<std::uint32_t>(seed);
    p.amplitude_cm = h.number("amplitude_cm", p.amplitude_cm);
    p.wavelength_cm = h.number("wavelength_cm", p.wavelength_cm);
    p.octaves = h.integer("octaves", p.octaves);
    h.finish();
    r.finish();
    return std::make_shared<const rig::Terrain>(rig::Terrain::hills(p, source));
  }
  r.finish();
  r.fail("hills", "expected \"hills\": {\"seed\", \"amplitude_cm\", \"wavelength_cm\", \"octaves\"} or \"file\": a glTF mesh");
}

}  // namespace stirrup::scene
