#include "scene/view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "rig/units.h"
#include "scene/camera_motion.h"
#include "scene/frame_range.h"

namespace stirrup::scene {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The lens of a crowd's whole-troop perspective view (our choice): wider than a pair's 50 mm.
constexpr double kCrowdPerspFocalMm = 35.0;

double fovFromFocal(double mm) { return 2.0 * std::atan(12.0 / mm) * 180.0 / rig::kPi; }

// The direction from the target toward the camera, in the travel frame.
glm::dvec3 viewDirection(const std::string& view) {
  if (view == "side") return glm::normalize(glm::dvec3(0.0, 0.12, 1.0));
  // Perspective views look down less than half their field of view, so the horizon is in the frame.
  if (view == "persp") return glm::normalize(glm::dvec3(0.75, 0.12, 1.0));
  if (view == "close") return glm::normalize(glm::dvec3(0.45, 0.06, 1.0));
  // A crowd's whole troop (render/shot.h): from higher, about 15 degrees down, so the ranks behind
  // the first show over it; a 35 mm lens's half field (19 degrees) keeps the horizon in the frame.
  if (view == "crowd persp") return glm::normalize(glm::dvec3(0.75, 0.335, 1.0));
  return glm::normalize(glm::dvec3(0.0, 0.12, 1.0));  // turntable: starts on the right side
}

// Runs f(i) for every frame index in parallel, on the caller's threads (ShotCamera runs the framing on
// its evaluator's). Each frame's part is kept apart and the parts are then combined in frame order, by
// min and max, which are exact: the framing is the same at any thread count.
void eachFrame(std::size_t frames, const std::function<void(std::size_t)>& f) {
  tbb::parallel_for(std::size_t(0), frames, [&](std::size_t i) { f(i); });
}

struct Basis {
  glm::dvec3 forward, right, up, target;
};

Basis basisOf(const Camera& c) {
  Basis b;
  b.forward = glm::normalize(c.target - c.position);
  b.right = glm::normalize(glm::cross(b.forward, c.up));
  b.up = glm::cross(b.right, b.forward);
  b.target = c.target;
  return b;
}

// The points a view frames at one frame: the horse's and the rider's, kept apart (joining them was one
// more copy of every frame's points), or for `close` the rider's above the saddle alone. Skinned
// positions are floats; every use below reads them as doubles, exactly.
struct FramePoints {
  std::span<const glm::vec3> horse, rider;
  std::vector<glm::vec3> kept;  // the rider's points a view keeps of its own (keepViewPoints), when it keeps some
  // f(p) for every point, the horse's then the rider's.
  template <typename F>
  void each(F&& f) const {
    for (const glm::dvec3 p : horse) f(p);
    for (const glm::dvec3 p : rider) f(p);
  }
};

void keepViewPoints(const CameraSpec& spec, FramePoints& points) {
  if (spec.view != "close") return;
  // The rider above the saddle: the upper 55% of the rider's height at this frame.
  double lo = kInf, hi = -kInf;
  for (const glm::dvec3 p : points.rider) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
  const double cut = lo + 0.45 * (hi - lo);
  points.kept.clear();
  for (const glm::vec3& p : points.rider)
    if (double(p.y) >= cut) points.kept.push_back(p);
  points.rider = points.kept;
  points.horse = {};
}

glm::dvec3 toVec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> toArray(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// How far above the highest point the top camera stands: any height works for an orthographic camera
// (rays start at its film); this keeps it clear of the characters and the hills.
constexpr double kTopCameraClearanceCm = 1000.0;
// The top view's image up is world -Z (so +X runs to the right and the horse's right side, +Z, down).
constexpr std::array<double, 3> kTopUp = {0.0, 0.0, -1.0};

// The top view: straight down, fixed, over the bounds (x, z) of the travel and of the characters'
// points over every frame, so the whole ground track (a figure eight, a circle) is in the picture
// with frame_margin free at each border.
CameraSpec frameTopView(CameraSpec spec, const SceneSpec& scene, const rig::Clip& clip,
                        const std::vector<FramePoints>& pts) {
  glm::dvec3 lo(kInf), hi(-kInf);
  for (int f : scene::parseFrameList(scene.frames, "frames")) {
    const rig::HorseFrame h = clip.sampleTravel(frameTime(scene, f));
    const glm::dvec3 travel(h.travel_cm, h.ground_y_cm, h.travel_z_cm);
    lo = glm::min(lo, travel), hi = glm::max(hi, travel);
  }
  for (const FramePoints& frame : pts) frame.each([&](const glm::dvec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); });
  const glm::dvec3 centre = 0.5 * (lo + hi);
  spec.target = toArray({centre.x, lo.y, centre.z});
  spec.position = toArray({centre.x, hi.y + kTopCameraClearanceCm, centre.z});
  spec.up = kTopUp;
  const double aspect = double(scene.width) / double(scene.height);
  const double keep = 1.0 - 2.0 * spec.frame_margin;
  // Image width is world x, image height world z.
  spec.ortho_height_cm = std::max(hi.z - lo.z, (hi.x - lo.x) / aspect) / keep;
  return spec;
}

// An orthographic view's rays start on its film, which stands at the camera, a few metres from the
// target and a little above it. A wide subject (a crowd) makes the film so tall that its lower rows
// start under the ground and show nothing of it. Moving the camera back along its view changes no
// ray's direction or place in the picture, only where it starts: when the film's lower edge dips
// below the lowest framed point at any frame, the camera moves back until that edge is above the
// highest. A single pair's film clears the ground already and is left exactly as it was.
void raiseOrthographicFilm(CameraSpec& spec, const std::vector<int>& frames, const std::vector<FollowFrame>& follows,
                           const std::vector<FramePoints>& pts) {
  std::vector<double> dips(frames.size()), needs(frames.size());
  eachFrame(frames.size(), [&](std::size_t i) {
    const Camera cam = cameraFromFollow(spec, follows[i], frames[i]);
    const double bottom = cam.position.y - 0.5 * spec.ortho_height_cm * basisOf(cam).up.y;
    double lo = kInf, hi = -kInf;
    pts[i].each([&](const glm::dvec3 p) { lo = std::min(lo, p.y), hi = std::max(hi, p.y); });
    dips[i] = lo - bottom;
    needs[i] = hi - bottom;
  });
  double dip = 0.0, need = 0.0;
  for (std::size_t i = 0; i < frames.size(); ++i) dip = std::max(dip, dips[i]), need = std::max(need, needs[i]);
  const glm::dvec3 t = toVec(spec.target), back = glm::normalize(toVec(spec.position) - t);
  if (!(dip > 0.0) || !(back.y > 0.0)) return;
  spec.position = toArray(toVec(spec.position) + back * (need / back.y));
}

// What every framing pass reads: the frames, where the camera's motion takes it at each
// (cameraFollowAtFrame, found once), and the points it frames there.
struct FramingFrames {
  const std::vector<int>& frames;
  const std::vector<FollowFrame>& follows;
  const std::vector<FramePoints>& pts;
};

// Aims at the centre of the points' bounds in the followed frame (turned back by the heading the
// camera turns with, so a path clip's points are seen from the horse's side), from the view's
// direction. Returns the radius of those bounds.
double aimAtPointsCentre(CameraSpec& spec, const SceneSpec& scene, const rig::Clip& clip, const rig::RigProfile& profile,
                         const FramingFrames& f) {
  const std::vector<int>& frames = f.frames;
  std::vector<glm::dvec3> los(frames.size(), glm::dvec3(kInf)), his(frames.size(), glm::dvec3(-kInf));
  eachFrame(frames.size(), [&](std::size_t i) {
    const int shown = spec.hold_frame > 0 ? spec.hold_frame : frames[i];
    const glm::dvec3 follow = spec.motion == "fixed" ? glm::dvec3(0.0)
                                                     : followPoint(spec, clip, profile, frameTime(scene, shown));
    const HeadingTurn back(-f.follows[i].heading_deg);  // cameraHeadingAtFrame's, undone
    f.pts[i].each([&](const glm::dvec3 p) {
      const glm::dvec3 q = back(p - follow);
      los[i] = glm::min(los[i], q), his[i] = glm::max(his[i], q);
    });
  });
  glm::dvec3 lo(kInf), hi(-kInf);
  for (std::size_t i = 0; i < frames.size(); ++i) lo = glm::min(lo, los[i]), hi = glm::max(hi, his[i]);
  if (!(lo.x <= hi.x)) throw std::invalid_argument("frameView: the characters have no vertices");
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * glm::length(hi - lo);
  // A crowd seen whole (no follow_pair) is a wide shot of many pairs: from higher, on a wider lens.
  const bool crowd_persp = scene.pairs.size() >= 2 && spec.follow_pair < 0 && spec.view == "persp";
  if (crowd_persp) spec.fov_deg = fovFromFocal(kCrowdPerspFocalMm);
  const glm::dvec3 dir = viewDirection(crowd_persp ? "crowd persp" : spec.view);
  spec.target = toArray(centre);
  spec.position = toArray(centre + dir * (spec.orthographic ? radius + 600.0 : 3.0 * radius));
  return radius;
}

// The points' extent on the film over every frame: in the film plane for an orthographic camera, else
// in film coordinates at the target's distance (so a truck by d moves them by d).
struct FilmExtent {
  double umin = kInf, umax = -kInf, vmin = kInf, vmax = -kInf;
};

FilmExtent filmExtent(const CameraSpec& spec, const FramingFrames& f) {
  std::vector<FilmExtent> extents(f.frames.size());
  eachFrame(f.frames.size(), [&](std::size_t i) {
    const Camera cam = cameraFromFollow(spec, f.follows[i], f.frames[i]);
    const Basis b = basisOf(cam);
    const double dist = glm::length(cam.target - cam.position);
    FilmExtent e;
    f.pts[i].each([&](const glm::dvec3 p) {
      const glm::dvec3 q = p - b.target;
      const double x = glm::dot(q, b.right), y = glm::dot(q, b.up), z = glm::dot(q, b.forward);
      if (spec.orthographic) {
        e.umin = std::min(e.umin, x), e.umax = std::max(e.umax, x), e.vmin = std::min(e.vmin, y), e.vmax = std::max(e.vmax, y);
      } else {
        const double depth = dist + z;  // along the view axis from the camera
        if (depth <= 1.0) return;  // behind the camera: the dolly below moves it out
        // Film coordinates at the target's distance (so a truck by d moves them by d).
        e.umin = std::min(e.umin, x * dist / depth), e.umax = std::max(e.umax, x * dist / depth);
        e.vmin = std::min(e.vmin, y * dist / depth), e.vmax = std::max(e.vmax, y * dist / depth);
      }
    });
    extents[i] = e;
  });
  FilmExtent all;
  for (const FilmExtent& e : extents)
    all.umin = std::min(all.umin, e.umin), all.umax = std::max(all.umax, e.umax), all.vmin = std::min(all.vmin, e.vmin),
    all.vmax = std::max(all.vmax, e.vmax);
  return all;
}

// Trucks (shifts position and target together) to centre the extent: along the first frame's right/up
// (constant for follow cameras, in their own turning frame: turned back by the first frame's heading);
// an orbit only rises or sinks, along the world vertical.
void truckToCentre(CameraSpec& spec, const FramingFrames& f, const FilmExtent& e, bool orbit) {
  const Basis first = basisOf(cameraFromFollow(spec, f.follows[0], f.frames[0]));
  glm::dvec3 right0 = first.right, up0 = first.up;
  const double heading0 = f.follows[0].heading_deg;
  right0 = turnByHeading(right0, -heading0), up0 = turnByHeading(up0, -heading0);
  const double cu = 0.5 * (e.umin + e.umax), cv = 0.5 * (e.vmin + e.vmax);
  glm::dvec3 shift = orbit ? glm::dvec3(0.0, cv / std::max(0.2, up0.y), 0.0) : right0 * cu + up0 * cv;
  spec.position = toArray(toVec(spec.position) + shift);
  spec.target = toArray(toVec(spec.target) + shift);
}

// Dollies a perspective camera back along the view axis until every point fits, |x| <= tw keep (dist' + z)
// (th, tw: the tangents of the half field), and never inside the characters' `radius`.
void dollyToFit(CameraSpec& spec, const FramingFrames& f, double th, double tw, double keep, double radius) {
  std::vector<double> dists(f.frames.size());
  eachFrame(f.frames.size(), [&](std::size_t i) {
    const Camera cam = cameraFromFollow(spec, f.follows[i], f.frames[i]);
    const Basis b = basisOf(cam);
    double need = 0.0;
    f.pts[i].each([&](const glm::dvec3 p) {
      const glm::dvec3 q = p - b.target;
      const double x = glm::dot(q, b.right), y = glm::dot(q, b.up), z = glm::dot(q, b.forward);
      need = std::max(need, std::abs(x) / (tw * keep) - z);
      need = std::max(need, std::abs(y) / (th * keep) - z);
      need = std::max(need, 1.05 * radius - z);  // never inside the characters
    });
    dists[i] = need;
  });
  double dist_needed = 0.0;
  for (double need : dists) dist_needed = std::max(dist_needed, need);
  const glm::dvec3 t = toVec(spec.target);
  const glm::dvec3 back = glm::normalize(toVec(spec.position) - t);
  spec.position = toArray(t + back * dist_needed);
}

}  // namespace

void applyViewPreset(CameraSpec& spec) {
  if (spec.view.empty()) return;
  spec.follow_target = "travel";
  if (spec.view == "side") {
    spec.orthographic = true;
    spec.motion = "follow";
    spec.damping_s = 0.3;
  } else if (spec.view == "persp") {
    spec.orthographic = false;
    spec.focal_length_mm = 50.0;
    spec.motion = "follow";
    spec.damping_s = 0.4;
  } else if (spec.view == "close") {
    spec.orthographic = false;
    spec.focal_length_mm = 85.0;
    spec.motion = "follow";
    spec.follow_target = "rider";
    spec.damping_s = 0.3;
  } else if (spec.view == "top") {
    spec.orthographic = true;
    spec.motion = "fixed";
    spec.damping_s = 0.0;
  } else if (spec.view == "turntable") {
    spec.orthographic = false;
    spec.focal_length_mm = 50.0;
    spec.motion = "orbit";
    if (spec.orbit_frames == 0 && spec.orbit_deg_per_frame == 0.0) spec.orbit_frames = 96;
  } else {
    throw std::invalid_argument("unknown view \"" + spec.view + "\"");
  }
  if (!spec.orthographic) spec.fov_deg = fovFromFocal(spec.focal_length_mm);
  spec.follow = spec.motion == "follow";
  spec.up = spec.view == "top" ? kTopUp : std::array<double, 3>{0.0, 1.0, 0.0};
}

std::vector<int> framingFrames(const CameraSpec& spec, const SceneSpec& scene) {
  std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
  if (spec.motion == "orbit") {
    const int n = spec.orbit_frames > 0
                      ? spec.orbit_frames
                      : (spec.orbit_deg_per_frame != 0.0 ? int(std::ceil(360.0 / std::abs(spec.orbit_deg_per_frame))) : 1);
    for (int f = 1; f <= n; ++f) frames.push_back(f);
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  }
  return frames;
}

CameraSpec frameView(CameraSpec spec, const SceneSpec& scene, const rig::Clip& clip,
                     const rig::RigProfile& profile, const std::vector<int>& frames,
                     const CharacterPoints& points) {
  applyViewPreset(spec);
  if (frames.empty()) throw std::invalid_argument("frameView: no frames");
  // The points of every frame, once.
  std::vector<CharacterFramePoints> shown;
  points(frames, shown);
  if (shown.size() != frames.size()) throw std::logic_error("frameView: expected the points of every frame");
  std::vector<FramePoints> pts(frames.size());
  eachFrame(frames.size(), [&](std::size_t i) {
    pts[i].horse = shown[i].horse;
    pts[i].rider = shown[i].rider;
    keepViewPoints(spec, pts[i]);
  });

  if (spec.view == "top") return frameTopView(spec, scene, clip, pts);
  // Where the camera's motion takes it at every frame, once: the passes below move and size the
  // camera but not its motion (cameraFollowAtFrame).
  std::vector<FollowFrame> follows(frames.size());
  eachFrame(frames.size(), [&](std::size_t i) { follows[i] = cameraFollowAtFrame(spec, scene, clip, profile, frames[i]); });
  const FramingFrames framing{frames, follows, pts};

  // 1. Aim at the centre of the points' bounds in the followed frame.
  const double radius = aimAtPointsCentre(spec, scene, clip, profile, framing);

  const double aspect = double(scene.width) / double(scene.height);
  const double keep = 1.0 - 2.0 * spec.frame_margin;  // fraction of the film the points may use
  const bool orbit = spec.motion == "orbit";

  // 2. Truck (shift position and target together) to centre the extents, then size; three passes so
  //    the perspective centring sees the final distance.
  for (int pass = 0; pass < 3; ++pass) {
    const double th = std::tan(0.5 * spec.fov_deg * rig::kPi / 180.0), tw = th * aspect;
    const FilmExtent e = filmExtent(spec, framing);
    truckToCentre(spec, framing, e, orbit);
    if (spec.orthographic) {
      const double half = std::max(0.5 * (e.vmax - e.vmin), 0.5 * (e.umax - e.umin) / aspect);
      const double halfu = orbit ? std::max(std::abs(e.umin), std::abs(e.umax)) / aspect : 0.0;
      spec.ortho_height_cm = 2.0 * std::max(half, halfu) / keep;
    } else {
      dollyToFit(spec, framing, th, tw, keep, radius);
    }
  }
  if (spec.orthographic) raiseOrthographicFilm(spec, frames, follows, pts);
  return spec;
}

}  // namespace stirrup::scene
