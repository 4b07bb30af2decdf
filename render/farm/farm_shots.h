// Farm plans for what stirrup renders: one scene through one camera (`stirrup render`), or the review
// movie set (`stirrup movies`). Each shot's frames are cut into chunks; each chunk's task runs the same
// stirrup command a user would run locally, for its frames only, so farm frames are local frames.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/farm/farm_plan.h"
#include "render/review/movie_set.h"
#include "rig/rig_profile.h"
#include "scene/scene.h"

namespace stirrup::render {

// What every plan needs: where, how finely cut, which program, which scheduler settings.
struct FarmRequest {
  std::filesystem::path out;          // absolute
  int chunk = 48;                     // frames a task
  std::filesystem::path stirrup;      // the program every node runs (same path everywhere)
  SbatchSettings sbatch;
  std::string submitted;              // UTC time stamp for the manifest
};

// One shot: `scene` through `camera`; `frames` empty means the scene's. `render_args` are further
// `stirrup render` options both the tasks and the finishing encode get (--preset, --resolution, --set,
// --allow-impossible: then the scene loads here too when it is beyond a horse's limits).
// Frames are OUT/SCENE_CAMERA.####.png; the finishing job encodes OUT/SCENE_CAMERA.mp4.
// With `framed` (planCamera's, for the scene as the tasks will see it), the plan keeps the framed
// camera and every task reads it (--camera-plan OUT/farm.json) instead of framing the view again.
FarmPlan planRender(const FarmRequest& request, const std::filesystem::path& scene, const std::string& camera,
                    const std::string& frames, const std::vector<std::string>& render_args,
                    const std::optional<PlannedCamera>& framed = std::nullopt);

// What a view's framing reads, as a hash: the scene file's text, the frames it is framed over, the
// image's size and the resolved rig profile. A camera planned for one key is refused for another.
std::string framingKey(const scene::SceneSpec& scene, const rig::RigProfile& profile);
// `camera` (a view camera of `scene`) framed now, as the characters and the clip place it
// (scene/shot_camera.h), for a plan; none for a camera without a view (nothing to frame).
std::optional<PlannedCamera> planCamera(const scene::SceneSpec& scene, const rig::RigProfile& profile, const scene::CameraSpec& camera,
                                        int threads = 0);
// The camera a shot renders with instead of framing `camera` again: its view's preset with the
// planned position, target, up, size and lens, and no view left to frame (Shot takes it as it is).
// `where` names the plan's camera in errors ("FILE: shots[0].camera"): a one-line InputError when
// it is another camera's or was framed for another key.
scene::CameraSpec plannedCameraSpec(const scene::SceneSpec& scene, const rig::RigProfile& profile, const scene::CameraSpec& camera,
                             const PlannedCamera& planned, const std::string& where);
// The planned camera of the shot `shot` in the manifest `file`, and where it is ("FILE:
// shots[0].camera", for plannedCameraSpec's errors): an InputError naming the file when the plan has
// no such shot or the shot no camera.
PlannedCamera plannedCameraOf(const std::filesystem::path& file, const std::string& shot, std::string& where);

// The movie set `jobs` with `options`; `movie_args` are the `stirrup movies` options that reproduce
// `options` (cli/movie_set_options.h). `subset`: the finishing job names the movies with --only.
FarmPlan planMovies(const FarmRequest& request, const std::vector<MovieJob>& jobs, const MovieOptions& options,
                    const std::vector<std::string>& movie_args, bool subset);

// InputError unless `out` can take a farm's output: a folder (made if missing) this process can write,
// not in memory (tmpfs, ramfs: no other node sees it), and, on a cluster of more than one node, on a
// network filesystem (NFS, Lustre, CephFS, GPFS, BeeGFS, SMB...).
void checkSharedOutput(const std::filesystem::path& out, int cluster_nodes);

}  // namespace stirrup::render
