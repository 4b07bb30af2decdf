// Quality presets: named sets of samples per pixel and light/sky samples per camera sample, so a
// scene or the command line can ask for "draft", "review" or "final" instead of three numbers.
#pragma once

#include <span>
#include <string_view>

#include "scene/scene.h"

namespace stirrup::scene {

struct QualityPreset {
  std::string_view name;
  int samples;        // camera samples per pixel, stratified
  int light_samples;  // sun shadow rays per camera sample
  int ao_samples;     // sky occlusion rays per camera sample
};

// draft (playblast speed), review (the movies' default), final (stills and turntables), in that order.
std::span<const QualityPreset> qualityPresets();

// The preset called `name`; throws rig::InputError
// "--preset: expected draft, review or final, got NAME" for any other name.
const QualityPreset& findPreset(std::string_view name);

// Sets the scene's samples, light_samples and ao_samples to the preset's.
void applyPreset(SceneSpec& scene, const QualityPreset& p);

// The zlib level a scene's PNG frames are written at unless asked otherwise (the levels:
// scene/png_compression.h): a draft (the draft preset's one camera sample a pixel, or fewer
// samples of any kind) writes them stored, uncompressed, because at draft speed the write competes with
// the trace for the cores; the others at review's level 1.
int defaultPngCompression(const SceneSpec& scene);

}  // namespace stirrup::scene
