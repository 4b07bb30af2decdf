// Farm plans for what stirrup renders: one scene through one camera (`stirrup render`), or the review
// movie set (`stirrup movies`). Each shot's frames are cut into chunks; each chunk's task runs the same
// stirrup command a user would run locally, for its frames only, so farm frames are local frames.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/farm/farm_plan.h"
#include "render/review/movie_set.h"

namespace stirrup::render::farm {

// What every plan needs: where, how finely cut, which program, which scheduler settings.
struct FarmRequest {
  std::filesystem::path out;          // absolute
  int chunk = 48;                     // frames a task
  std::filesystem::path stirrup;      // the program every node runs (same path everywhere)
  SbatchSettings sbatch;
  std::string submitted;              // UTC time stamp for the manifest
};

// One shot: `scene` through `camera`; `frames` empty means the scene's. `render_args` are further
// `stirrup render` options both the tasks and the finishing encode get (--preset, --resolution, --set).
// Frames are OUT/SCENE_CAMERA.####.png; the finishing job encodes OUT/SCENE_CAMERA.mp4.
FarmPlan planRender(const FarmRequest& request, const std::filesystem::path& scene, const std::string& camera,
                    const std::string& frames, const std::vector<std::string>& render_args);

// The movie set `jobs` with `options`; `movie_args` are the `stirrup movies` options that reproduce
// `options` (cli/movie_set_options.h). `subset`: the finishing job names the movies with --only.
FarmPlan planMovies(const FarmRequest& request, const std::vector<MovieJob>& jobs, const MovieOptions& options,
                    const std::vector<std::string>& movie_args, bool subset);

// InputError unless `out` can take a farm's output: a folder (made if missing) this process can write,
// not in memory (tmpfs, ramfs: no other node sees it), and, on a cluster of more than one node, on a
// network filesystem (NFS, Lustre, CephFS, GPFS, BeeGFS, SMB...).
void checkSharedOutput(const std::filesystem::path& out, int cluster_nodes);

}  // namespace stirrup::render::farm
