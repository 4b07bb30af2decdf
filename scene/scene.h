// A scene file (scenes/NAME.json): which clip, which characters, which rig profile, the frame range,
// the resolution and quality, the cameras and the output folder. Every field has a default, so `{}` is
// a valid scene (the default trot); unknown fields and wrong types are one-line errors.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/motion/crowd.h"
#include "rig/motion/horse_limits.h"
#include "rig/motion/procedural_gait.h"
#include "scene/clip_factory.h"
#include "scene/reference_spec.h"

namespace stirrup::scene {

struct CameraSpec {
  std::string name = "side";
  bool orthographic = true;
  double fov_deg = 30.0;             // vertical field of view (perspective)
  double ortho_height_cm = 320.0;    // height of the view (orthographic)
  // Positions in the horse's travel frame when follow is true (the camera travels with the horse),
  // else in the world. Centimetres, Y up, +X the horse's direction of travel, +Z its right side.
  std::array<double, 3> position = {20.0, 255.0, 900.0};
  std::array<double, 3> target = {20.0, 100.0, 0.0};
  // The camera's up direction (world): Y, except for a camera looking straight down (the top view).
  std::array<double, 3> up = {0.0, 1.0, 0.0};
  bool follow = true;
  // How the camera moves (scene/camera_motion.h). "follow" with damping_s 0 and target "travel" is
  // the camera rigidly in the horse's travel frame (the old `follow: true`); "fixed" is in the world.
  std::string motion = "follow";     // fixed | follow | orbit
  std::string follow_target = "travel";  // travel (the horse's travel frame) | rider (the rider's seat)
  double damping_s = 0.0;            // critically damped time constant of a follow camera, seconds
  double orbit_deg_per_frame = 0.0;  // orbit: degrees about the vertical through `target` per frame
  int orbit_frames = 0;              // orbit: a full 360 degrees over this many frames (overrides deg)
  double focal_length_mm = 0.0;      // perspective: > 0 sets fov from a 24 mm high film back
  // A named view preset (scene/view.h): side, persp, close, turntable. Its position, target and size
  // are framed from the characters' bounds over the whole clip, so `position`/`target` are ignored.
  std::string view;
  double frame_margin = 0.12;        // view framing: fraction of the image kept free at each border
  bool treadmill = false;            // the horse moves in place: travel removed (turntables)
  // A crowd scene (SceneSpec::pairs): the pair (index into pairs) the camera follows and a view frames,
  // as a single-pair scene's camera follows its horse. -1: the whole crowd (its middle, every pair).
  int follow_pair = -1;
  int hold_frame = 0;                // > 0: every frame shows the pose of this frame (held-pose turntable)
  // Not a scene field: set by the shot from its horse when it resolves the camera. The saddle's rest
  // place relative to the horse's rear pivot (its root joint), cm, world axes, so a camera following
  // the rider's seat sees the seat swing about the pivot as the body pitches and rolls (a rear lifts
  // the saddle 60 cm). Zero: the seat moves with the pivot's translation only.
  std::array<double, 3> seat_from_pivot_cm = {0.0, 0.0, 0.0};
};

struct SceneSpec {
  std::filesystem::path file;        // where the scene was read from (empty for built-in defaults)
  std::string name = "trot";
  rig::GaitParams gait = rig::trotParams();  // the steady gait when clip is one (walk/trot/canter/gallop)
  scene::ClipSpec clip;                         // what plays: a generator and its parameters, or a glTF file
  // The ground (scene/terrain_json.h); null = the flat plane. The same object is clip.terrain.
  std::shared_ptr<const rig::Terrain> terrain;
  // "default" (the built-in generator) or a glTF file (resolved against the scene's folder), with an
  // optional mapping file (empty: the file's own role table). See rig::resolveCharacter.
  std::string horse = "default";
  std::string rider = "default";
  std::string horse_mapping, rider_mapping;
  std::string profile = "thesis";
  nlohmann::json profile_overrides = nlohmann::json::object();
  double fps = 24.0;
  std::string frames = "1-48";
  int width = 640;
  int height = 360;
  int samples = 16;                  // per pixel, stratified
  int light_samples = 1;            // sun shadow rays per camera sample
  int ao_samples = 1;               // sky rays per camera sample
  std::array<double, 3> sun_direction = {0.45, 0.75, 0.5};  // toward the sun, from the camera's side
  double sun_angular_radius_deg = 2.0;
  // Aerial perspective ("haze": AerialPerspective in render/tracer/lights.h): the ground is wholly haze this
  // far from a perspective camera, and this far behind an orthographic camera's target.
  double haze_visibility_cm = 60000.0;
  double haze_ortho_depth_cm = 1500.0;
  std::vector<CameraSpec> cameras = {CameraSpec{}};
  std::filesystem::path output = "out/trot";
  // Reference footage for the layered view ("reference": {...}, scene/reference_spec.h ReferenceSpec); its
  // file is resolved against the scene file. Absent: the layered view compares with the rigid rider.
  std::optional<ReferenceSpec> reference;
  // A crowd (issue 19; rig/motion/crowd.h): "crowd" generates the pairs, "riders" lists them; either
  // way `pairs` holds them, checked (no two horses meet at any frame). Empty: the one horse and rider
  // of `clip`, as every scene before it. A "crowd" without "frames" plays its lead's whole ride
  // (rig::crowdFrames).
  std::optional<rig::CrowdSpec> crowd;
  std::vector<rig::PairSpec> pairs;
  // Each pair's clip as loading checked it (rig::validatePairs) on `pair_clips_terrain`: a shot of the
  // scene takes them instead of making them again, while the scene's terrain is still that one (a copy
  // set on other ground makes its own). Whoever changes a pair's path after loading clears them.
  rig::PairClips pair_clips;
  std::shared_ptr<const rig::Terrain> pair_clips_terrain;
  // Limits a horse has (rig/motion/horse_limits.h), read along every path of the scene (its path clip,
  // or each pair's). A path beyond one is refused when the scene loads, unless `allow_impossible` (the
  // scene field, or SceneLoadOptions from --allow-impossible): then it loads, and each frame that
  // breaks a limit is warned about (impossibleFrameWarning).
  bool allow_impossible = false;
  struct PathLimits {
    std::shared_ptr<const rig::PathLimitCheck> check;
    double clip_offset_s = 0;  // the path's clip is sampled at the shot's time plus this (a crowd's pair)
    int pair = 0;              // the crowd's pair riding it (0: the scene's one pair); a pair playing its own animation has none
  };
  std::vector<PathLimits> limits;
  // The generated clip's gaits faster than horses go at them (scene::generatedGaitSpeeds, HorseLimits):
  // refused like a path, unless `allow_impossible`; then kept here, for the warnings and `stirrup check`.
  std::vector<rig::GaitSpeedBreach> gait_breaches;
};

struct SceneLoadOptions {
  bool allow_impossible = false;  // --allow-impossible: load a scene beyond a horse's limits, with warnings
};

// Reads a scene file; throws rig::InputError "FILE: FIELD: expected ..., got ..." on bad input.
// A relative path that does not exist from the working folder is looked up in stirrup's data folder
// (scene/data_dir.h), so `stirrup render scenes/trot.json` works from anywhere once installed.
SceneSpec loadScene(const std::filesystem::path& file, const SceneLoadOptions& options = {});
// Where loadScene reads `file` from: the path itself, or the data folder's file of that relative path.
std::filesystem::path findSceneFile(const std::filesystem::path& file);
// Parses scene JSON already in memory; `file` names it in errors.
SceneSpec parseScene(const nlohmann::json& json, const std::string& file, const SceneLoadOptions& options = {});

// The scene's clip, for its horse: a path clip turns the hooves about the horse's own rest places (a
// glTF horse is read for them; the default horse's are built in). A crowd scene has no one clip: an
// InputError (each pair rides its own: scene/shot_evaluator.h evaluates them all, rig::makePairClip
// makes one).
std::unique_ptr<rig::Clip> makeSceneClip(const SceneSpec& scene);

// The camera of the scene named `name` (or the first when empty); InputError if there is none.
const CameraSpec& findCamera(const SceneSpec& scene, const std::string& name);

// Seconds into the clip at a frame: frame 1 is t = 0.
double frameTime(const SceneSpec& scene, int frame);

// One line for a frame of an allowed impossible scene that breaks a horse's limits within half a frame
// of its time: "FILE: frame 12 (0.458 s): impossible: turn (...); footing (...)"; "" when it breaks none.
std::string impossibleFrameWarning(const SceneSpec& scene, int frame);
// Writes that line (if any) to stderr.
void warnImpossibleFrame(const SceneSpec& scene, int frame);

}  // namespace stirrup::scene

