#include "render/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace stirrup::render {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// How far to push a secondary ray's origin off the surface: above the float error of a hit point
// computed as origin + t * direction at these coordinates (a few ulps of the largest coordinate).
float originOffset(const glm::vec3& p) {
  const float extent = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return 2e-3f + 3e-5f * extent;
}

}  // namespace

float filteredChecker(float s, float t, float width) {
  const float half = 0.5f * width;
  if (half < 1e-4f) {  // sharp: the parity of floor(s) + floor(t), in floats as the SIMD lanes make it
    auto parity = [](float v) { return v - 2.0f * std::floor(v * 0.5f); };
    const float ps = parity(std::floor(s)), pt = parity(std::floor(t));
    return ps + pt - 2.0f * ps * pt;
  }
  // A box filter's side lobes alias: a footprint of 1.5 squares still shows a third of the contrast,
  // as bands that crawl when the camera moves. So the contrast also fades, from full where a square
  // spans four footprints (width 0.25) to none where it spans one: no pattern finer than the pixels.
  if (width >= kCheckerFadeEnd) return 0.5f;
  // Integral of the square wave that is 1 on [1, 2) mod 2. The wave has period 2, so each
  // coordinate is first reduced to [0, 2): the differences below then stay exact enough in floats
  // however far from the origin the point is.
  auto integral = [](float x) {
    const float f = std::floor(x * 0.5f);
    return f + 2.0f * std::max(x * 0.5f - f - 0.5f, 0.0f);
  };
  auto box = [&](float x) {
    x -= 2.0f * std::floor(x * 0.5f);
    return (integral(x + half) - integral(x - half)) / (2.0f * half);
  };
  const float ss = box(s), tt = box(t);
  const float odd = ss + tt - 2.0f * ss * tt;  // odd in s xor odd in t
  if (width <= kCheckerFadeStart) return odd;
  const float x = (width - kCheckerFadeStart) * (1.0f / (kCheckerFadeEnd - kCheckerFadeStart));
  const float contrast = 1.0f - x * x * (3.0f - 2.0f * x);
  return 0.5f + (odd - 0.5f) * contrast;
}

struct Integrator::Surface {
  glm::vec3 p;       // hit point
  glm::vec3 ng;      // geometric normal, facing the camera
  glm::vec3 n;       // shading normal, same side as ng
  glm::vec3 wo;      // toward the camera
  glm::vec3 albedo;  // linear base colour
  float specular;    // Blinn-Phong weight
  float haze;        // aerial perspective: the fraction of the surface's light that reaches the camera
  bool on_ground;
};

Integrator::Integrator(const RenderSettings& settings, const EmbreeScene& scene,
                       std::span<const ShadingMesh* const> meshes_by_geometry, const rig::Terrain* terrain,
                       float ground_floor)
    : settings_(settings),
      characters_(scene.characters()),
      meshes_(meshes_by_geometry),
      terrain_(terrain),
      ground_(scene.ground()),
      ground_floor_(terrain ? ground_floor : 0.0f),
      pixel_layout_(uint32_t(settings.samples_per_pixel)),
      sun_layout_(uint32_t(settings.samples_per_pixel * settings.light_samples)),
      sky_layout_(uint32_t(settings.samples_per_pixel * settings.ao_samples)) {
  const RTCBounds& b = scene.characterBounds();
  bounds_lower_ = {b.lower_x, b.lower_y, b.lower_z};
  bounds_upper_ = {b.upper_x, b.upper_y, b.upper_z};
  const bool empty = !(b.lower_x <= b.upper_x && b.lower_y <= b.upper_y && b.lower_z <= b.upper_z);
  bounds_radius_ = empty ? -1.0f : 0.5f * glm::length(bounds_upper_ - bounds_lower_);
  const glm::vec3 sun = glm::normalize(glm::vec3(settings.sun_direction));
  sun_frame_ = Frame::around(sun);
  inv_sun_dir_ = 1.0f / sun_frame_.z;  // inf for a zero component, which sunMayBeBlocked never uses
  const float sun_angle = float(std::max(0.0, settings.sun_angular_radius_deg) * std::numbers::pi / 180.0);
  sun_cos_max_ = std::cos(sun_angle);
  sun_tan_ = std::tan(sun_angle);
  sun_radiance_ = settings.sun_color * settings.sun_strength;
  setGroundSunRegion();
  const glm::vec3 ground_albedo = 0.5f * (settings.ground_color_a + settings.ground_color_b);
  ground_bounce_ = ground_albedo * (sun_radiance_ * std::max(0.0f, sun.y) + settings.sky.upwardIrradianceOverPi());
  blinn_norm_ = (settings.shininess + 8.0f) / 8.0f;
  ground_extent_ = settings.ground_half_extent_cm;
  spp_ = uint32_t(settings.samples_per_pixel);
  light_spp_ = uint32_t(settings.light_samples);
  ao_spp_ = uint32_t(settings.ao_samples);
}

namespace {

RTCRay makeRay(const glm::vec3& origin, const glm::vec3& direction, float t_far) {
  RTCRay ray;
  ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
  ray.dir_x = direction.x, ray.dir_y = direction.y, ray.dir_z = direction.z;
  ray.tnear = 0.0f;
  ray.tfar = t_far;
  ray.time = 0.0f;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

}  // namespace

// Whether any ray of the sun's cone from `origin` can meet the characters' bounding box. The cone is
// covered by the axis ray against the box grown by the cone's radius at the box's far corner. When it
// misses, the sun is certainly unblocked there and needs no shadow rays (most of the ground).
bool Integrator::sunMayBeBlocked(const glm::vec3& origin) const {
  if (bounds_radius_ < 0.0f) return false;
  const glm::vec3 far_corner = glm::max(glm::abs(origin - bounds_lower_), glm::abs(origin - bounds_upper_));
  const float margin = glm::length(far_corner) * sun_tan_ * 1.01f + 0.1f;
  const glm::vec3 lower = bounds_lower_ - margin, upper = bounds_upper_ + margin;
  const glm::vec3& d = sun_frame_.z;
  float t0 = 0.0f, t1 = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0f) {
      if (origin[a] < lower[a] || origin[a] > upper[a]) return false;
      continue;
    }
    float near = (lower[a] - origin[a]) * inv_sun_dir_[a], far = (upper[a] - origin[a]) * inv_sun_dir_[a];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return true;
}

// sunMayBeBlocked(o) is true only when the sun's axis from o meets the characters' box grown by a
// margin M(o) = |far corner| tan(sun radius) 1.01 + 0.1 (above). For a point o on the ground, hitting
// it at q (in the grown box) means o = q - t d with t = (q.y - o.y) / d.y <= (H + M) / d.y, H the box's
// top, and the far corner is at most t + |box extent| + sqrt(3) M from o. So M <= k ((H + M) / d.y +
// |extent| + sqrt(3) M) + 0.1 with k = 1.01 tan: a bound on M, and with it a rectangle of the ground
// outside which sunMayBeBlocked is certainly false. The rectangle answers most of the ground in four
// comparisons, with the same answer the full test gives there.
void Integrator::setGroundSunRegion() {
  ground_sun_region_ = false;
  const glm::vec3& d = sun_frame_.z;
  if (bounds_radius_ < 0.0f || !(d.y > 0.0f)) return;
  const float k = 1.01f * sun_tan_;
  const float denominator = 1.0f - k / d.y - 1.7320508f * k;
  if (!(denominator > 0.1f)) return;  // a low or very wide sun: no useful bound, always run the test
  // Heights from the lowest ground (0 on the plane: then exactly the plane's bound).
  const float top = std::max(bounds_upper_.y - ground_floor_, 0.0f);
  const float extent = glm::length(bounds_upper_ - bounds_lower_);
  const float margin = (k * (top / d.y + extent) + 0.1f) / denominator * 1.01f + 1.0f;  // + rounding slack
  const float t_max = (top + margin) / d.y;
  ground_sun_lower_ = {bounds_lower_.x - margin - std::max(0.0f, t_max * d.x),
                       bounds_lower_.z - margin - std::max(0.0f, t_max * d.z)};
  ground_sun_upper_ = {bounds_upper_.x + margin - std::min(0.0f, t_max * d.x),
                       bounds_upper_.z + margin - std::min(0.0f, t_max * d.z)};
  ground_sun_region_ = true;
}

bool Integrator::groundSunRegionExcludes(const glm::vec3& origin) const {
  return ground_sun_region_ && origin.y >= ground_floor_ &&
         (origin.x < ground_sun_lower_.x || origin.x > ground_sun_upper_.x || origin.z < ground_sun_lower_.y ||
          origin.z > ground_sun_upper_.y);
}

bool Integrator::groundSunMayBeBlocked(const glm::vec3& origin) const {
  return !groundSunRegionExcludes(origin) && sunMayBeBlocked(origin);
}

float Integrator::distanceToCharacters(const glm::vec3& p) const {
  if (bounds_radius_ < 0.0f) return kInfinity;
  const glm::vec3 d = glm::max(glm::max(bounds_lower_ - p, p - bounds_upper_), glm::vec3(0.0f));
  return glm::length(d);
}

// A pixel of the batch: its sun and sky sequences, set up once and read by each of its samples.
struct TileScratch::PixelState {
  Stratified2D sun, sky;
};

// A camera sample of the batch, from its ray to the light it gathered.
struct TileScratch::CameraSample {
  glm::vec3 origin, dir;
  float t_ground;       // the ground's distance along the ray (within the visible distance), or infinity
  int32_t ray;          // its index in camera_rays, or -1: the ray cannot reach the characters
  // Set by the shading pass.
  bool hit;
  ObjectId id;
  float depth;
  glm::vec3 normal;
  glm::vec3 radiance;   // of the sky, when nothing was hit; of open ground, when resolved
  glm::vec3 sun, sky;   // light that needed no rays (when the matching *_traced is false)
  glm::vec3 diffuse;    // scales the sky rays' sum
  float haze;           // aerial perspective (1: none)
  bool sun_traced, sky_traced;
  bool resolved;        // open ground: `radiance` is its whole light, from the lanes
  uint32_t sun_pending, sky_pending;  // entries of the pending list: sun rays, then sky rays
};

// What an occlusion ray brings when it is open. `ray` indexes the batch's occlusion rays (the lanes
// in TileScratch::occluders), or is -1: no ray (its t_far was not positive), so it is open.
struct TileScratch::PendingRay {
  glm::vec3 weight;
  int32_t ray;
};

TileScratch::TileScratch() = default;
TileScratch::~TileScratch() = default;
TileScratch::TileScratch(TileScratch&&) noexcept = default;
TileScratch& TileScratch::operator=(TileScratch&&) noexcept = default;

namespace {

// Camera samples per batch: a batch's rays and results (about 200 bytes a sample) stay within the
// core's L2 cache, and the streams are long enough for Embree to trace them as packets.
constexpr int kBatchSamples = 1024;

bool blocked(const RTCRay& ray) { return ray.tfar < 0.0f; }  // Embree sets tfar to -inf on a hit

}  // namespace

void Integrator::renderTile(const CameraFrame& camera, int x0, int x1, int y0, int y1, int frame, TileScratch& scratch,
                            RayTally& tally, PixelResult* out) const {
  const int width = x1 - x0, count = width * (y1 - y0);
  const int batch = std::max(1, kBatchSamples / int(spp_));
  const LaneConstants constants = laneConstants(camera);
  for (int first = 0; first < count; first += batch) {
    renderBatch(camera, constants, x0, width, y0, first, std::min(batch, count - first), frame, scratch, tally,
                out + first);
  }
}

LaneConstants Integrator::laneConstants(const CameraFrame& camera) const {
  LaneConstants k;
  camera.laneView(k.perspective, k.pixel_dx, k.pixel_dy, k.half_width, k.half_height, k.footprint_at_0,
                  k.footprint_per_cm);
  k.position = camera.positionF(), k.forward = camera.forwardF(), k.right = camera.rightF(), k.up = camera.upF();
  k.target_distance = camera.targetDistanceF();
  k.ground_extent = ground_extent_;
  k.t_visible = visibleDistance(camera);
  k.square_cm = settings_.ground_square_cm;
  k.color_a = settings_.ground_color_a, k.color_b = settings_.ground_color_b;
  k.haze_visibility = settings_.haze.visibility_cm, k.haze_ortho_depth = settings_.haze.ortho_depth_cm;
  k.horizon = settings_.sky.horizon, k.zenith = settings_.sky.zenith, k.below = settings_.sky.below;
  // An orthographic sky is graded from the ground's height under the camera's target.
  if (terrain_ && !camera.perspective()) {
    const glm::vec3 target = camera.positionF() + camera.forwardF() * camera.targetDistanceF();
    k.sky_floor = float(terrain_->height(double(target.x), double(target.z)));
  }
  k.sun_y = sun_frame_.z.y;
  k.sun_radiance = sun_radiance_;
  k.sky_irradiance = settings_.sky.upwardIrradianceOverPi();
  k.sun_region = ground_sun_region_;
  k.ground_floor = ground_floor_;
  k.sun_lower_x = ground_sun_lower_.x, k.sun_lower_z = ground_sun_lower_.y;
  k.sun_upper_x = ground_sun_upper_.x, k.sun_upper_z = ground_sun_upper_.y;
  k.ao_distance = settings_.ao_distance_cm;
  k.box_lower = bounds_lower_, k.box_upper = bounds_upper_;
  k.box_empty = bounds_radius_ < 0.0f;
  return k;
}

void Integrator::renderBatch(const CameraFrame& camera, const LaneConstants& constants, int x0, int tile_width, int y0,
                             int first, int count, int frame, TileScratch& scratch, RayTally& tally,
                             PixelResult* out) const {
  scratch.pixels.clear();
  scratch.samples.clear();
  scratch.camera_rays.clear();
  scratch.ground_rays.clear();
  scratch.pending.clear();
  scratch.sun_rays.clear();
  scratch.sky_rays.clear();
  CameraLanes& lanes = scratch.lanes;
  const std::size_t n = std::size_t(count) * spp_;
  lanes.resize(n);
  scratch.samples.resize(n);

  // Pass 1: every camera ray of the batch. The sample sequences are hashed here, one pixel at a time;
  // the rays, the flat ground (a square in the plane y = 0, intersected without a call into Embree:
  // its distance then bounds the search through the characters) and the test against the characters'
  // box run in SIMD lanes over the whole batch. Uneven ground is traced below (pass 1b) first.
  std::size_t j = 0;
  for (int p = 0; p < count; ++p) {
    const int x = x0 + (first + p) % tile_width, y = y0 + (first + p) / tile_width;
    const PixelSampler sampler(x, y, frame);
    const Stratified2D pixel_points(sampler, pixel_layout_, SampleDimension::PixelFilter);
    scratch.pixels.push_back({Stratified2D(sampler, sun_layout_, SampleDimension::SunCone),
                              Stratified2D(sampler, sky_layout_, SampleDimension::SkyHemisphere)});
    const float cx = float(x) + 0.5f, cy = float(y) + 0.5f;
    for (uint32_t i = 0; i < spp_; ++i, ++j) {
      const glm::vec2 u = pixel_points[i];
      lanes.ux[j] = u.x, lanes.uy[j] = u.y, lanes.cx[j] = cx, lanes.cy[j] = cy;
    }
  }
  cameraRayLanes(constants, lanes, !terrain_);
  auto queueCharacterRay = [&](TileScratch::CameraSample& c, std::size_t k) {
    c.ray = -1;
    // Most camera rays of a review view pass beside the characters' box: no call into Embree.
    if (lanes.may_hit[k]) {
      c.ray = int32_t(scratch.camera_rays.size());
      RTCRayHit& rh = scratch.camera_rays.emplace_back();
      rh.ray = makeRay(c.origin, c.dir, c.t_ground);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
  };
  for (std::size_t k = 0; k < n; ++k) {
    TileScratch::CameraSample& c = scratch.samples[k];
    c.origin = {lanes.ox[k], lanes.oy[k], lanes.oz[k]};
    c.dir = {lanes.dx[k], lanes.dy[k], lanes.dz[k]};
    c.t_ground = lanes.t_ground[k];
    ++tally.rays;
    if (tally.camera) tally.camera->push_back(makeRay(c.origin, c.dir, kInfinity));
    if (terrain_) {
      RTCRayHit& rh = scratch.ground_rays.emplace_back();
      rh.ray = makeRay(c.origin, c.dir, constants.t_visible);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      continue;
    }
    queueCharacterRay(c, k);
  }

  // Pass 1b (uneven ground): every camera ray against the heightfield as one coherent stream; its
  // distance then bounds the search through the characters as the plane's does.
  if (terrain_ && n > 0) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1M(ground_, &context, scratch.ground_rays.data(), unsigned(scratch.ground_rays.size()),
                   sizeof(RTCRayHit));
    for (std::size_t k = 0; k < n; ++k) {
      const RTCRayHit& rh = scratch.ground_rays[k];
      scratch.samples[k].t_ground = lanes.t_ground[k] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : kInfinity;
    }
    boxTestLanes(constants, lanes);
    for (std::size_t k = 0; k < n; ++k) queueCharacterRay(scratch.samples[k], k);
  }

  // Pass 2: the camera rays that may meet the characters, as one coherent stream.
  if (!scratch.camera_rays.empty()) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1M(characters_, &context, scratch.camera_rays.data(), unsigned(scratch.camera_rays.size()),
                   sizeof(RTCRayHit));
  }

  // Pass 3: the surface each sample sees, the light that needs no rays, and the shadow and sky rays.
  // In lanes first: the flat ground's surface (and the whole light of open ground, most of a review
  // frame) where no character is nearer, and the sky behind every sample.
  for (std::size_t k = 0; k < n; ++k) {
    const TileScratch::CameraSample& c = scratch.samples[k];
    const bool character_hit = c.ray >= 0 && scratch.camera_rays[std::size_t(c.ray)].hit.geomID != RTC_INVALID_GEOMETRY_ID;
    lanes.t_shade[k] = character_hit ? kInfinity : c.t_ground;
  }
  if (!terrain_) groundLanes(constants, lanes);
  skyLanes(constants, lanes);
  RayLanes& occluders = scratch.occluders;
  occluders.clear();
  scratch.occluder_is_sky.clear();
  TileScratch::CameraSample* c = scratch.samples.data();
  j = 0;
  for (const TileScratch::PixelState& pixel : scratch.pixels) {
    for (uint32_t i = 0; i < spp_; ++i, ++c, ++j) {
      c->resolved = false;
      if (!terrain_ && lanes.open[j]) {  // open ground: its light is known
        c->hit = c->resolved = true;
        c->id = ObjectId::Ground;
        c->depth = lanes.depth[j];
        c->normal = glm::vec3(0.0f, 1.0f, 0.0f);
        c->radiance = {lanes.radiance_r[j], lanes.radiance_g[j], lanes.radiance_b[j]};
        continue;
      }
      const RTCRayHit* rh = c->ray >= 0 ? &scratch.camera_rays[size_t(c->ray)] : nullptr;
      Surface s;
      if (!surfaceOf(camera, *c, rh, lanes, j, s, c->id)) {
        c->hit = false;
        c->radiance = {lanes.sky_r[j], lanes.sky_g[j], lanes.sky_b[j]};
        continue;
      }
      c->hit = true;
      c->haze = s.haze;
      c->depth = s.on_ground && !terrain_ ? lanes.depth[j] : camera.viewDepthF(s.p);
      c->normal = s.n;
      emitShading(s, pixel.sun, pixel.sky, i, *c, scratch, tally);
    }
  }

  // Pass 3b: the occlusion rays against the characters' box in lanes; those that may meet them go to
  // their stream, in the order they were made.
  const std::size_t occluder_count = occluders.size;
  occluders.pad();
  boxTestLanes(constants, occluders);
  scratch.occluder_ray.resize(occluder_count);
  for (std::size_t k = 0; k < occluder_count; ++k) {
    int32_t& ray = scratch.occluder_ray[k];
    ray = -1;
    if (!occluders.may_hit[k]) continue;
    std::vector<RTCRay>& stream = scratch.occluder_is_sky[k] ? scratch.sky_rays : scratch.sun_rays;
    ray = int32_t(stream.size());
    stream.push_back(makeRay({occluders.ox[k], occluders.oy[k], occluders.oz[k]},
                             {occluders.dx[k], occluders.dy[k], occluders.dz[k]}, occluders.t_far[k]));
  }

  // Pass 4: the shadow rays (nearly parallel: one coherent stream) and the sky rays.
  if (!scratch.sun_rays.empty()) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded1M(characters_, &context, scratch.sun_rays.data(), unsigned(scratch.sun_rays.size()), sizeof(RTCRay));
  }
  if (!scratch.sky_rays.empty()) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1M(characters_, &context, scratch.sky_rays.data(), unsigned(scratch.sky_rays.size()), sizeof(RTCRay));
  }

  // Pass 5: each sample's light from its open rays, and each pixel's samples into its result.
  const TileScratch::PendingRay* pending = scratch.pending.data();
  auto open = [&](const TileScratch::PendingRay& r, const std::vector<RTCRay>& stream) {
    if (r.ray < 0) return true;
    const int32_t traced = scratch.occluder_ray[std::size_t(r.ray)];
    return traced < 0 || !blocked(stream[std::size_t(traced)]);
  };
  c = scratch.samples.data();
  for (int p = 0; p < count; ++p) {
    glm::vec3 sum(0.0f), normal_sum(0.0f);
    uint32_t hits = 0, character_hits = 0;
    float nearest = kInfinity;
    // Votes for the object id pass: at most a handful of distinct ids can meet in one pixel.
    constexpr int kMaxIds = 4;
    uint32_t ids[kMaxIds], votes[kMaxIds];
    int distinct = 0, sky_votes = 0;
    for (uint32_t i = 0; i < spp_; ++i, ++c) {
      if (!c->hit) {
        sum += c->radiance;
        ++sky_votes;
        continue;
      }
      glm::vec3 radiance;
      if (c->resolved) {
        radiance = c->radiance;
      } else {
      glm::vec3 sun = c->sun;
      if (c->sun_traced) {
        sun = glm::vec3(0.0f);
        for (uint32_t k = 0; k < c->sun_pending; ++k, ++pending)
          if (open(*pending, scratch.sun_rays)) sun += pending->weight;
        sun *= sun_radiance_ / float(light_spp_);
      }
      if (!c->sky_traced) {
        radiance = sun + c->sky;
      } else {
        glm::vec3 sky(0.0f);
        for (uint32_t k = 0; k < c->sky_pending; ++k, ++pending)
          if (open(*pending, scratch.sky_rays)) sky += pending->weight;
        sky *= c->diffuse / float(ao_spp_);
        radiance = sun + sky;
      }
      if (c->haze < 1.0f) radiance = radiance * c->haze + settings_.sky.horizon * (1.0f - c->haze);
      }
      sum += radiance;
      ++hits;
      normal_sum += c->normal;
      if (c->id != ObjectId::Ground) ++character_hits;
      nearest = std::min(nearest, c->depth);
      int k = 0;
      while (k < distinct && ids[k] != uint32_t(c->id)) ++k;
      if (k == distinct && distinct < kMaxIds) ids[distinct] = uint32_t(c->id), votes[distinct++] = 0;
      if (k < distinct) ++votes[k];
    }
    PixelResult& r = out[p];
    const float inv = 1.0f / float(spp_);
    r.rgba = glm::vec4(sum * inv, float(hits) * inv);
    r.depth = nearest;
    r.matte = float(character_hits) * inv;
    const float normal_length = glm::length(normal_sum);
    r.normal = normal_length > 0.0f ? normal_sum / normal_length : glm::vec3(0.0f);
    // Most votes wins; on a tie the id seen first, and the sky only with more votes than any object.
    r.object_id = kNoObject;
    int best = -1;
    for (int k = 0; k < distinct; ++k) {
      if (int(votes[k]) > best) best = int(votes[k]), r.object_id = ids[k];
    }
    if (sky_votes > best) r.object_id = kNoObject;
  }
}

bool Integrator::surfaceOf(const CameraFrame& camera, const TileScratch::CameraSample& c, const RTCRayHit* rh,
                           const CameraLanes& lanes, std::size_t j, Surface& s, ObjectId& id) const {
  const bool character_hit = rh && rh->hit.geomID != RTC_INVALID_GEOMETRY_ID;
  if (!character_hit && c.t_ground == kInfinity) return false;
  const float t = rh ? rh->ray.tfar : c.t_ground;
  const glm::vec3& dir = c.dir;
  s.p = c.origin + t * dir;
  s.wo = -dir;
  if (!character_hit) {
    float cos_view;
    if (terrain_) {
      // On the heightfield mesh as hit; shaded with the terrain's own (smooth, upward) normal, which
      // is also the geometric one the secondary rays leave along (they meet only the characters).
      // Never flipped toward the camera: at a hill's grazing far side a ray can meet a facet whose
      // smooth normal already faces away, and flipping it there left black specks on the horizon.
      const glm::vec3 n(terrain_->normal(double(s.p.x), double(s.p.z)));
      s.ng = s.n = n;
      cos_view = std::max(std::abs(glm::dot(n, dir)), 0.02f);
    } else {
      // The plane's surface came from the lanes (groundLanes: the same expressions as below).
      s.p.y = 0.0f;  // exactly on the plane; the offset below then lifts it the same everywhere
      s.ng = s.n = glm::vec3(0.0f, dir.y <= 0.0f ? 1.0f : -1.0f, 0.0f);
      s.albedo = {lanes.albedo_r[j], lanes.albedo_g[j], lanes.albedo_b[j]};
      s.specular = 0.0f;
      s.haze = lanes.haze[j];
      s.on_ground = true;
      id = ObjectId::Ground;
      return true;
    }
    // The sample's footprint on the ground: a pixel's width at this distance, stretched by the
    // grazing angle (isotropically, which blurs a little more than needed across the view).
    const float width = camera.pixelFootprintF(t) / cos_view / settings_.ground_square_cm;
    const float odd = filteredChecker(s.p.x / settings_.ground_square_cm, s.p.z / settings_.ground_square_cm, width);
    s.albedo = glm::mix(settings_.ground_color_a, settings_.ground_color_b, odd);
    s.specular = 0.0f;
    s.haze = camera.perspective()
                 ? AerialPerspective::perspective(t, settings_.haze.visibility_cm)
                 : AerialPerspective::orthographic(t - camera.targetDistanceF(), settings_.haze.ortho_depth_cm);
    s.on_ground = true;
    id = ObjectId::Ground;
    return true;
  }
  const ShadingMesh& mesh = *meshes_[rh->hit.geomID];
  const uint32_t* tri = &mesh.indices[size_t(rh->hit.primID) * 3];
  const float b1 = rh->hit.u, b2 = rh->hit.v, b0 = 1.0f - b1 - b2;
  s.ng = glm::normalize(glm::vec3(rh->hit.Ng_x, rh->hit.Ng_y, rh->hit.Ng_z));
  if (glm::dot(s.ng, dir) > 0.0f) s.ng = -s.ng;
  glm::vec3 n = b0 * mesh.normals[tri[0]] + b1 * mesh.normals[tri[1]] + b2 * mesh.normals[tri[2]];
  const float len = glm::length(n);
  n = len > 1e-12f ? n / len : s.ng;
  if (glm::dot(n, s.ng) < 0.0f) n = -n;  // seeing the back of the surface
  // Interpolated normals can face away from the camera at silhouettes; tilt them just enough
  // toward the viewer so the edge does not turn black.
  const float facing = glm::dot(n, s.wo);
  if (facing < 0.01f) n = glm::normalize(n + (0.01f - facing) * s.wo);
  s.n = n;
  s.albedo = b0 * mesh.colors[tri[0]] + b1 * mesh.colors[tri[1]] + b2 * mesh.colors[tri[2]];
  s.specular = settings_.specular;
  s.haze = 1.0f;  // the characters keep their colours: the haze is the ground's, for the horizon
  s.on_ground = false;
  id = mesh.id;
  return true;
}

float Integrator::visibleDistance(const CameraFrame& camera) const {
  return camera.perspective() ? settings_.haze.visibility_cm
                              : camera.targetDistanceF() + settings_.haze.ortho_depth_cm;
}

int32_t Integrator::emitOcclusion(const glm::vec3& origin, const glm::vec3& direction, float t_far, bool sky,
                                  TileScratch& scratch, RayTally& tally) const {
  if (!(t_far > 0.0f)) return -1;
  ++tally.rays;
  if (tally.occlusion) tally.occlusion->push_back(makeRay(origin, direction, t_far));
  // Queued for the box test in lanes (pass 3b), which sends it on to its stream or not.
  scratch.occluders.push(origin, direction, t_far);
  scratch.occluder_is_sky.push_back(sky);
  return int32_t(scratch.occluders.size - 1);
}

void Integrator::emitShading(const Surface& s, const Stratified2D& sun_points, const Stratified2D& sky_points,
                             uint32_t sample, TileScratch::CameraSample& c, TileScratch& scratch,
                             RayTally& tally) const {
  // Secondary rays start off the surface along the geometric normal (not the shading normal,
  // which can point into neighbouring triangles): no acne, and contacts stay tight.
  const glm::vec3 origin = s.p + s.ng * originOffset(s.p);
  const glm::vec3 diffuse = s.albedo * (1.0f - s.specular);
  c.diffuse = diffuse;

  // BRDF times cosine for light arriving from wi (0 from below the surface).
  auto reflected = [&](const glm::vec3& wi) {
    const float cos_n = glm::dot(s.n, wi);
    if (cos_n <= 0.0f || glm::dot(s.ng, wi) <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 f = diffuse;
    if (s.specular > 0.0f) {
      const float cos_h = std::max(0.0f, glm::dot(s.n, glm::normalize(wi + s.wo)));
      f += glm::vec3(s.specular * blinn_norm_ * std::pow(cos_h, settings_.shininess));
    }
    return f * cos_n;
  };

  // Sun: shadow rays spread over the sun's disc, stratified over all of the pixel's sun rays. Where
  // no ray of the cone can reach the characters the sun is evaluated once along its axis: over a disc
  // of a few degrees the cosine barely changes, and the open ground gets no shadow noise at all.
  c.sun_pending = 0;
  c.sun_traced = s.on_ground ? groundSunMayBeBlocked(origin) : sunMayBeBlocked(origin);
  if (!c.sun_traced) {
    c.sun = reflected(sun_frame_.z) * sun_radiance_;
  } else {
    for (uint32_t k = 0; k < light_spp_; ++k) {
      const glm::vec3 wi = sampleCone(sun_frame_, sun_cos_max_, sun_points[sample * light_spp_ + k]);
      const glm::vec3 f = reflected(wi);
      if (f == glm::vec3(0.0f)) continue;  // no light from below: no ray, and nothing to add
      const int32_t ray = emitOcclusion(origin, wi, kInfinity, false, scratch, tally);
      scratch.pending.push_back({f, ray});
      ++c.sun_pending;
    }
  }

  // Sky: ambient occlusion against the gradient sky. Rays heading down from a character stop just
  // short of the ground: if nothing else is in the way they see the sunlit ground's bounce.
  // Open ground farther than ao_distance from the characters sees the whole sky: use its exact
  // cosine-weighted mean instead of rays.
  c.sky_pending = 0;
  c.sky_traced = !(s.on_ground && s.ng.y > 0.0f && distanceToCharacters(origin) > settings_.ao_distance_cm);
  if (!c.sky_traced) {
    c.sky = diffuse * settings_.sky.upwardIrradianceOverPi();
    return;
  }
  const Frame around = Frame::around(s.n);
  // How high the surface is above the ground under it (on the plane: its height).
  const float above_ground =
      terrain_ && !s.on_ground ? origin.y - float(terrain_->height(double(origin.x), double(origin.z))) : origin.y;
  for (uint32_t k = 0; k < ao_spp_; ++k) {
    const glm::vec3 wi = sampleCosineHemisphere(around, sky_points[sample * ao_spp_ + k]);
    if (!(glm::dot(s.ng, wi) > 0.0f)) continue;  // below the real surface: blocked by it
    const bool toward_ground = !s.on_ground && wi.y < 0.0f;
    float t_far = settings_.ao_distance_cm;
    if (toward_ground) t_far = std::min(t_far, 0.999f * above_ground / -wi.y);
    const int32_t ray = emitOcclusion(origin, wi, t_far, true, scratch, tally);
    scratch.pending.push_back({toward_ground ? ground_bounce_ : settings_.sky.radiance(wi), ray});
    ++c.sky_pending;
  }
}

}  // namespace stirrup::render
