#include "scene/preset.h"

#include <array>
#include <string>

#include "rig/error.h"
#include "scene/png_compression.h"

namespace stirrup::scene {
namespace {

// Numbers chosen by measurement on the 2-core development machine (docs/performance.md).
constexpr std::array<QualityPreset, 3> kPresets = {{
    {"draft", 1, 1, 1},
    {"review", 4, 1, 1},
    {"final", 64, 1, 1},
}};

}  // namespace

std::span<const QualityPreset> qualityPresets() { return kPresets; }

const QualityPreset& findPreset(std::string_view name) {
  for (const QualityPreset& p : kPresets)
    if (p.name == name) return p;
  throw rig::InputError("--preset: expected draft, review or final, got " + std::string(name));
}

void applyPreset(SceneSpec& scene, const QualityPreset& p) {
  scene.samples = p.samples;
  scene.light_samples = p.light_samples;
  scene.ao_samples = p.ao_samples;
}

int defaultPngCompression(const SceneSpec& scene) {
  const QualityPreset& draft = findPreset("draft");
  const bool is_draft = scene.samples <= draft.samples && scene.light_samples <= draft.light_samples &&
                        scene.ao_samples <= draft.ao_samples;
  return is_draft ? kDraftPngCompression : kReviewPngCompression;
}

}  // namespace stirrup::scene
