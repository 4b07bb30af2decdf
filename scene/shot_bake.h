// A shot baked for another tool (stirrup bake -o, docs/round-trip.md): every pair's two characters (a
// crowd's at full detail) posed at every frame by the shot's evaluator (scene/shot_evaluator.h), every
// camera of the scene as `stirrup render` resolves it (scene/shot_camera.h: views framed, follow and
// orbit motion) at every frame, and over a terrain the ground under the tracks. rig::bakedShotGlb
// writes it as glTF.
#pragma once

#include <vector>

#include "rig/io/gltf_bake.h"
#include "scene/shot_evaluator.h"

namespace stirrup::scene {

// The frames sorted, each once. Pair i of the shot is the evaluator's pair i, named by its pairName;
// its characters are the evaluator's at `level` of detail (scene/detail_level.h: 0 full, 1 half,
// 2 quarter; a single pair has only 0), which must outlive the result. Every level has the same
// skeleton, so the animation is the same at each: only the meshes are coarser.
rig::BakedShot bakeShot(ShotEvaluator& characters, std::vector<int> frames, int level = 0);

}  // namespace stirrup::scene
