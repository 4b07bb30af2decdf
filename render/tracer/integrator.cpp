#include "render/tracer/integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace stirrup::render {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// How much the heightfield's slab is widened before camera rays are clipped to it (cm).
constexpr float kSlabPadCm = 1.0f;

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

namespace {

OccluderBox characterBox(const EmbreeScene& scene) {
  const RTCBounds& b = scene.characterBounds();
  return {{b.lower_x, b.lower_y, b.lower_z}, {b.upper_x, b.upper_y, b.upper_z}};
}

Sun makeSun(const RenderSettings& settings, const OccluderBox& box, float ground_floor) {
  return Sun(settings.sun_direction, settings.sun_angular_radius_deg, settings.sun_color * settings.sun_strength, box,
             ground_floor);
}

// The sky, with the lit ground's bounce: the mean checker's albedo under the sun and the open sky.
Sky makeSky(const RenderSettings& settings, const OccluderBox& box, const Sun& sun) {
  const glm::vec3 ground_albedo = 0.5f * (settings.ground_color_a + settings.ground_color_b);
  const glm::vec3 bounce = ground_albedo * (sun.axisRadiance() * std::max(0.0f, sun.frame().z.y) +
                                            settings.sky.upwardIrradianceOverPi());
  return Sky(settings.sky, settings.ao_distance_cm, box, bounce);
}

}  // namespace

Integrator::Integrator(const RenderSettings& settings, const EmbreeScene& scene,
                       std::span<const ShadingMesh* const> meshes_by_geometry, const rig::Terrain* terrain,
                       float ground_floor, const SunHorizon* hills, const TerrainMesh* ground_mesh)
    : settings_(settings),
      characters_(scene.characters()),
      bounds_lower_(characterBox(scene).lower),
      bounds_upper_(characterBox(scene).upper),
      bounds_radius_(characterBox(scene).empty() ? -1.0f : 0.5f * glm::length(bounds_upper_ - bounds_lower_)),
      meshes_(meshes_by_geometry),
      ground_floor_(terrain ? ground_floor : 0.0f),
      sun_(makeSun(settings, characterBox(scene), ground_floor_)),
      sky_(makeSky(settings, characterBox(scene), sun_)),
      brdf_(Brdf::blinnPhong(settings.specular, settings.shininess)),
      ground_extent_(settings.ground_half_extent_cm),
      terrain_(terrain),
      hills_(hills),
      ground_mesh_(terrain ? ground_mesh : nullptr),
      slab_low_(-kInfinity),
      slab_high_(kInfinity),
      ground_(scene.ground()),
      spp_(uint32_t(settings.samples_per_pixel)),
      light_spp_(uint32_t(settings.light_samples)),
      ao_spp_(uint32_t(settings.ao_samples)),
      pixel_layout_(uint32_t(settings.samples_per_pixel)),
      sun_layout_(uint32_t(settings.samples_per_pixel * settings.light_samples)),
      sky_layout_(uint32_t(settings.samples_per_pixel * settings.ao_samples)) {
  if (ground_mesh_ && !ground_mesh_->positions.empty()) {
    // Every point of the mesh, and so every hit, is within [min, max] height; a centimetre more each way
    // (far more than a hit's rounding in y) keeps a hit on the slab's faces inside the traced interval.
    slab_low_ = ground_mesh_->min_height - kSlabPadCm;
    slab_high_ = ground_mesh_->max_height + kSlabPadCm;
  }
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

// The sun's shadow-ray test (render/tracer/light.h).
bool Integrator::sunMayBeBlocked(const glm::vec3& origin) const { return sun_.mayBeBlocked(origin); }
bool Integrator::groundSunRegionExcludes(const glm::vec3& origin) const { return sun_.groundRegionExcludes(origin); }
bool Integrator::groundSunMayBeBlocked(const glm::vec3& origin) const { return sun_.groundMayBeBlocked(origin); }

TileScratch::TileScratch() = default;
TileScratch::~TileScratch() = default;
TileScratch::TileScratch(TileScratch&&) noexcept = default;
TileScratch& TileScratch::operator=(TileScratch&&) noexcept = default;

// Embree's stream arrays must start on 16 bytes, as every allocation of the default new does here.
static_assert(__STDCPP_DEFAULT_NEW_ALIGNMENT__ >= 16);

void TileScratch::GroundStream::resize(std::size_t n) {
  if (time.size() >= n) return;
  for (auto* f : {&time, &ng_x, &ng_y, &ng_z, &u, &v}) f->resize(n, 0.0f);
  mask.resize(n, 0xffffffffu);
  for (auto* f : {&id, &flags, &prim, &geom, &inst}) f->resize(n, 0u);
}

namespace {

// Camera samples per batch: a batch's rays and results (about 200 bytes a sample) stay within the
// core's L2 cache, and the streams are long enough for Embree to trace them as packets.
constexpr int kBatchSamples = 1024;

bool blocked(const RTCRay& ray) { return ray.tfar < 0.0f; }  // Embree sets tfar to -inf on a hit

}  // namespace

void Integrator::renderTile(const scene::CameraFrame& camera, int x0, int x1, int y0, int y1, int frame, TileScratch& scratch,
                            RayTally& tally, PixelResult* out) const {
  const int width = x1 - x0, count = width * (y1 - y0);
  const int batch = std::max(1, kBatchSamples / int(spp_));
  const LaneConstants constants = laneConstants(camera);
  for (int first = 0; first < count; first += batch) {
    renderBatch(constants, x0, width, y0, first, std::min(batch, count - first), frame, scratch, tally,
                out + first);
  }
}

LaneConstants Integrator::laneConstants(const scene::CameraFrame& camera) const {
  LaneConstants k;
  camera.laneView(k.perspective, k.pixel_dx, k.pixel_dy, k.half_width, k.half_height, k.footprint_at_0,
                  k.footprint_per_cm);
  k.position = camera.positionF(), k.forward = camera.forwardF(), k.right = camera.rightF(), k.up = camera.upF();
  k.target_distance = camera.targetDistanceF();
  k.ground_extent = ground_extent_;
  k.t_visible = visibleDistance(camera);
  k.slab_low = slab_low_, k.slab_high = slab_high_;
  if (hills_) k.hills = hills_->laneView();
  k.square_cm = settings_.ground_square_cm;
  k.color_a = settings_.ground_color_a, k.color_b = settings_.ground_color_b;
  k.haze_visibility = settings_.haze.visibility_cm, k.haze_ortho_depth = settings_.haze.ortho_depth_cm;
  // An orthographic sky is graded from the ground's height under the camera's target.
  if (terrain_ && !camera.perspective()) {
    const glm::vec3 target = camera.positionF() + camera.forwardF() * camera.targetDistanceF();
    k.sky_floor = float(terrain_->height(double(target.x), double(target.z)));
  }
  sun_.toLanes(k);
  sky_.toLanes(k);
  brdf_.toLanes(k);
  k.sun_region = k.sun_region && settings_.open_ground_shortcuts;
  k.open_ground_shortcuts = settings_.open_ground_shortcuts;
  k.ground_floor = ground_floor_;
  k.box_lower = bounds_lower_, k.box_upper = bounds_upper_;
  k.box_empty = bounds_radius_ < 0.0f;
  k.light_samples = int(light_spp_), k.ao_samples = int(ao_spp_);
  return k;
}

// Pass 1c: the camera rays that may meet the characters' box, as Embree's rays: most camera rays of a
// review view pass beside it, with no call into Embree.
void Integrator::queueCharacterRays(TileScratch& scratch) const {
  const CameraLanes& lanes = scratch.lanes;
  scratch.ray_samples.resize(lanes.padded);
  const std::size_t count = listMayHit(lanes, scratch.ray_samples.data());
  scratch.camera_rays.resize(count);
  for (std::size_t r = 0; r < count; ++r) {
    const std::size_t k = std::size_t(scratch.ray_samples[r]);
    RTCRayHit& rh = scratch.camera_rays[r];
    rh.ray = makeRay(lanes.origin(k), lanes.direction(k), lanes.t_ground[k]);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  }
}

void Integrator::renderBatch(const LaneConstants& constants, int x0, int tile_width, int y0,
                             int first, int count, int frame, TileScratch& scratch, RayTally& tally,
                             PixelResult* out) const {
  scratch.camera_rays.clear();
  scratch.hill_rays.clear();
  scratch.hill_list.clear();
  scratch.surface_samples.clear();
  CameraLanes& lanes = scratch.lanes;
  const std::size_t n = std::size_t(count) * spp_;
  lanes.resize(n);

  cameraPass(constants, x0, tile_width, y0, first, count, frame, scratch, tally);
  std::fill_n(lanes.hit_ray.begin(), lanes.padded, -1);
  const bool hills = terrain_ && n > 0;
  if (hills) {  // the characters first, unbounded: their hits then bound the heightfield's rays (pass 2b)
    boxTestLanes(constants, lanes);
    queueCharacterRays(scratch);
  }
  if (!scratch.camera_rays.empty()) characterPass(scratch);
  if (hills) groundPass(scratch);
  surfacePass(constants, frame, scratch, tally);
  occlusionPass(constants, scratch);
  resolvePass(count, scratch, out);
}

// Pass 1: every camera ray of the batch. Each pixel's sequence is set up here; its points, the rays,
// the flat ground (a square in the plane y = 0, intersected without a call into Embree: its distance
// then bounds the search through the characters) and the test against the characters' box run in
// SIMD lanes over the whole batch. Over uneven ground the characters are traced unbounded (pass 2), then
// the heightfield up to them (pass 2b).
void Integrator::cameraPass(const LaneConstants& constants, int x0, int tile_width, int y0, int first, int count,
                            int frame, TileScratch& scratch, RayTally& tally) const {
  CameraLanes& lanes = scratch.lanes;
  const std::size_t n = std::size_t(count) * spp_;
  StratifiedLanes& points = scratch.pixel_points;
  points.resize(lanes.padded);
  const std::size_t padded_pixels = CameraLanes::paddedSize(std::size_t(count));
  scratch.pixel_x.assign(padded_pixels, 0u);
  scratch.pixel_y.assign(padded_pixels, 0u);
  std::size_t j = 0;
  for (int p = 0; p < count; ++p) {
    const int x = x0 + (first + p) % tile_width, y = y0 + (first + p) / tile_width;
    scratch.pixel_x[std::size_t(p)] = uint32_t(x), scratch.pixel_y[std::size_t(p)] = uint32_t(y);
    const float cx = float(x) + 0.5f, cy = float(y) + 0.5f;
    for (uint32_t i = 0; i < spp_; ++i, ++j) lanes.cx[j] = cx, lanes.cy[j] = cy;
  }
  // The pixels' sequences in lanes; with one sample a pixel, the samples' points are the pixels'.
  const uint32_t* xs = scratch.pixel_x.data();
  const uint32_t* ys = scratch.pixel_y.data();
  if (spp_ == 1) {
    pixelPartLanes(pixel_layout_, SampleDimension::PixelFilter, uint32_t(frame), xs, ys, padded_pixels, points);
  } else {
    StratifiedLanes& parts = scratch.pixel_parts;
    parts.resize(padded_pixels);
    pixelPartLanes(pixel_layout_, SampleDimension::PixelFilter, uint32_t(frame), xs, ys, padded_pixels, parts);
    j = 0;
    for (int p = 0; p < count; ++p) {
      const Stratified2D::PixelPart part = parts.part(std::size_t(p));
      for (uint32_t i = 0; i < spp_; ++i, ++j) points.set(j, part, i);
    }
  }
  stratifiedLanes(pixel_layout_, points, 0, lanes.padded, lanes.ux.data(), lanes.uy.data());
  cameraRayLanes(constants, lanes, !terrain_);
  tally.rays += n;
  if (tally.camera)
    for (std::size_t k = 0; k < n; ++k) tally.camera->push_back(makeRay(lanes.origin(k), lanes.direction(k), kInfinity));
  if (terrain_) return;  // over hills the characters' rays are not bounded by the ground (renderBatch)
  queueCharacterRays(scratch);
}

// Pass 2b (uneven ground, after the characters): the camera rays against the heightfield as one
// structure-of-arrays stream that Embree reads from the lanes in place (no per-ray structures to fill,
// no copies), coherent, each ray from where it enters the heightfield's slab to where it leaves it
// (cameraRayLanes) or meets a character, whichever is nearer; a ray wholly above the hills (the sky of
// most views) has t_enter > t_leave, which Embree skips. Where the ground is nearer than a character
// hit, the sample sees the ground. The characters' rays are not bounded by the ground here, so they
// search further than over the plane; the heightfield's rays saved more (docs/performance-history.md, "What a
// hill frame pays beyond a flat one").
void Integrator::groundPass(TileScratch& scratch) const {
  CameraLanes& lanes = scratch.lanes;
  const std::size_t n = lanes.size;
  TileScratch::GroundStream& g = scratch.ground;
  g.resize(lanes.padded);
  std::fill_n(g.geom.begin(), lanes.padded, RTC_INVALID_GEOMETRY_ID);  // Embree writes a hit's fields only
  RTCRayHitNp stream;
  stream.ray = {lanes.ox.data(), lanes.oy.data(), lanes.oz.data(), lanes.t_enter.data(),
                lanes.dx.data(), lanes.dy.data(), lanes.dz.data(), g.time.data(),
                lanes.t_leave.data(), g.mask.data(), g.id.data(), g.flags.data()};
  stream.hit.Ng_x = g.ng_x.data(), stream.hit.Ng_y = g.ng_y.data(), stream.hit.Ng_z = g.ng_z.data();
  stream.hit.u = g.u.data(), stream.hit.v = g.v.data();
  stream.hit.primID = g.prim.data(), stream.hit.geomID = g.geom.data();
  for (unsigned*& inst : stream.hit.instID) inst = g.inst.data();
  // A ray that met a character searches the hills only up to her: the ground behind is not seen.
  for (std::size_t r = 0; r < scratch.camera_rays.size(); ++r) {
    const RTCRayHit& rh = scratch.camera_rays[r];
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    float& t_leave = lanes.t_leave[std::size_t(scratch.ray_samples[r])];
    t_leave = std::min(t_leave, rh.ray.tfar);
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersectNp(ground_, &context, &stream, unsigned(n));
  // Each hit's distance (its tfar) and the ground's normal there, while the hits are at hand (a
  // character nearer makes the normal unused: few samples).
  if (ground_mesh_) {
    groundHitLanes({g.geom.data(), g.prim.data(), g.u.data(), g.v.data(), ground_mesh_->xs.size(),
                    ground_mesh_->normals.data()},
                   lanes);
  } else {
    for (std::size_t k = 0; k < n; ++k) {
      const bool hit = g.geom[k] != RTC_INVALID_GEOMETRY_ID;
      lanes.t_ground[k] = hit ? lanes.t_leave[k] : kInfinity;
      if (hit) terrainNormal(lanes, k);
    }
  }
  // Where the ground is nearer than the character a ray met, the sample sees the ground.
  for (std::size_t r = 0; r < scratch.camera_rays.size(); ++r) {
    const std::size_t k = std::size_t(scratch.ray_samples[r]);
    if (lanes.hit_ray[k] >= 0 && lanes.t_ground[k] < kInfinity) lanes.hit_ray[k] = -1;
  }
}

// Pass 2: the camera rays that may meet the characters, as one coherent stream.
void Integrator::characterPass(TileScratch& scratch) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1M(characters_, &context, scratch.camera_rays.data(), unsigned(scratch.camera_rays.size()),
                 sizeof(RTCRayHit));
  // Which samples hit, and the hit triangles' indices, fetched toward the cache now: gathering a
  // surface waited on them, each a miss in a mesh's index array (docs/performance-history.md).
  for (std::size_t r = 0; r < scratch.camera_rays.size(); ++r) {
    const RTCRayHit& rh = scratch.camera_rays[r];
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    scratch.lanes.hit_ray[std::size_t(scratch.ray_samples[r])] = int32_t(r);
    __builtin_prefetch(&meshes_[rh.hit.geomID]->indices[std::size_t(rh.hit.primID) * 3]);
  }
}

// Pass 3: the surface each sample sees, the light that needs no rays, and the shadow and sky rays.
// In lanes first: the flat ground's surface (and the whole light of open ground, most of a review
// frame) where no character is nearer, and the sky behind every sample. Then every other surface a
// sample sees is gathered into the surface lanes, shaded there, and its rays queued.
void Integrator::surfacePass(const LaneConstants& constants, int frame, TileScratch& scratch, RayTally& tally) const {
  groundAndSkyLanes(constants, scratch);
  const std::size_t m = gatherSurfaces(frame, scratch);
  SurfaceLanes& surfaces = scratch.surfaces;
  surfaces.setSize(m);
  // The surfaces' sun and sky points, in lanes: slot k of surface m is point k * stride + m.
  for (uint32_t k = 0; k < light_spp_; ++k)
    stratifiedLanes(sun_layout_, scratch.sun_points, k * surfaces.stride, surfaces.padded, surfaces.sun_u.data(),
                    surfaces.sun_v.data());
  for (uint32_t k = 0; k < ao_spp_; ++k)
    stratifiedLanes(sky_layout_, scratch.sky_points, k * surfaces.stride, surfaces.padded, surfaces.sky_u.data(),
                    surfaces.sky_v.data());
  Material::shadeLanes(constants, surfaces);
  shadingLanes(constants, surfaces);
  queueOcclusionRays(constants, scratch, tally);
}

// The ground where a sample sees it (t_shade: no character nearer) and the sky behind every sample.
void Integrator::groundAndSkyLanes(const LaneConstants& constants, TileScratch& scratch) const {
  CameraLanes& lanes = scratch.lanes;
  for (std::size_t k = 0; k < lanes.size; ++k) lanes.t_shade[k] = lanes.hit_ray[k] >= 0 ? kInfinity : lanes.t_ground[k];
  // The hits' vertices toward the cache (their indices were fetched after the trace).
  for (const RTCRayHit& rh : scratch.camera_rays) {
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    const ShadingMesh& mesh = *meshes_[rh.hit.geomID];
    const uint32_t* tri = &mesh.indices[std::size_t(rh.hit.primID) * 3];
    for (int v = 0; v < 3; ++v) {
      __builtin_prefetch(&mesh.normals[tri[v]]);
      __builtin_prefetch(&mesh.colors[tri[v]]);
    }
  }
  if (terrain_) {
    terrainGroundLanes(constants, lanes);
  } else {
    groundLanes(constants, lanes);
  }
  skyLanes(constants, lanes);
}

// Each sample resolved where the lanes know its light (open ground, sky), else its surface gathered
// into the surface lanes in sample order (a character's hit triangle, its vertices' normals and
// colours, or the ground's surface) with its pixel's sun and sky sequences, set up in lanes for the
// pixels that have a surface. Returns the number of surfaces.
std::size_t Integrator::gatherSurfaces(int frame, TileScratch& scratch) const {
  const CameraLanes& lanes = scratch.lanes;
  SurfaceLanes& surfaces = scratch.surfaces;
  surfaces.reserve(lanes.size, int(light_spp_), int(ao_spp_));
  StratifiedLanes &sun_points = scratch.sun_points, &sky_points = scratch.sky_points;
  sun_points.resize(surfaces.stride * light_spp_);
  sky_points.resize(surfaces.stride * ao_spp_);
  scratch.surface_samples.resize(lanes.padded);
  const std::size_t m = listSurfaceSamples(lanes, scratch.surface_samples.data());
  scratch.surface_samples.resize(m);
  scratch.surface_ids.resize(m);
  scratch.light_x.clear(), scratch.light_y.clear();
  scratch.surface_light.resize(m), scratch.surface_slot.resize(m);
  // The surfaces ascend by sample, so their pixels ascend too: a pixel's first surface gives it its
  // entry among the pixels with lights.
  std::size_t pixel = 0, pixel_end = spp_;  // the samples [pixel_end - spp, pixel_end) are pixel's
  std::size_t lit_pixel = std::size_t(-1);  // the last pixel given an entry
  for (std::size_t s = 0; s < m; ++s) {
    const std::size_t j = std::size_t(scratch.surface_samples[s]);
    while (j >= pixel_end) ++pixel, pixel_end += spp_;
    const int32_t ray = lanes.hit_ray[j];
    scratch.surface_ids[s] = gatherSurface(ray >= 0 ? &scratch.camera_rays[std::size_t(ray)] : nullptr, lanes, j, surfaces, s);
    if (pixel != lit_pixel) {
      lit_pixel = pixel;
      scratch.light_x.push_back(scratch.pixel_x[pixel]), scratch.light_y.push_back(scratch.pixel_y[pixel]);
    }
    scratch.surface_light[s] = int32_t(scratch.light_x.size() - 1);
    scratch.surface_slot[s] = uint32_t(j - (pixel_end - spp_));
  }
  // The sun and sky sequences of the pixels with surfaces, in lanes, then each surface's points.
  const std::size_t padded_lights = CameraLanes::paddedSize(scratch.light_x.size());
  if (padded_lights == 0) return m;
  scratch.light_x.resize(padded_lights, 0u), scratch.light_y.resize(padded_lights, 0u);
  // A draft: each surface is its pixel's only one and takes its pixel's first point, so its points are
  // its pixel's parts as they are, made in place (copying them surface by surface cost 1-3% of a
  // draft's CPU: docs/performance-history.md).
  const bool in_place = spp_ == 1 && light_spp_ == 1 && ao_spp_ == 1;
  StratifiedLanes& sun_parts = in_place ? sun_points : scratch.sun_parts;
  StratifiedLanes& sky_parts = in_place ? sky_points : scratch.sky_parts;
  if (!in_place) sun_parts.resize(padded_lights), sky_parts.resize(padded_lights);
  pixelPartLanes(sun_layout_, SampleDimension::SunCone, uint32_t(frame), scratch.light_x.data(), scratch.light_y.data(),
                 padded_lights, sun_parts);
  pixelPartLanes(sky_layout_, SampleDimension::SkyHemisphere, uint32_t(frame), scratch.light_x.data(),
                 scratch.light_y.data(), padded_lights, sky_parts);
  if (in_place) {
    std::fill_n(sun_points.index.begin(), padded_lights, 0u);
    std::fill_n(sky_points.index.begin(), padded_lights, 0u);
    return m;
  }
  // A row of points at a time (point k of every surface), so each array is written in order.
  const auto setPoints = [&](StratifiedLanes& points, const StratifiedLanes& parts, uint32_t per_sample) {
    for (uint32_t k = 0; k < per_sample; ++k) {
      const std::size_t row = k * surfaces.stride;
      for (std::size_t s = 0; s < m; ++s) {
        const std::size_t light = std::size_t(scratch.surface_light[s]);
        points.set(row + s, parts.part(light), scratch.surface_slot[s] * per_sample + k);
      }
    }
  };
  setPoints(sun_points, sun_parts, light_spp_);
  setPoints(sky_points, sky_parts, ao_spp_);
  return m;
}

// The shadow and sky rays that carry light, in lanes: those that may meet the characters' box go to
// their streams (each ray's origin and direction from the surface lanes), the rest are open at once.
// Over uneven ground, the sun rays of surfaces the hills may shade are also queued against the
// heightfield.
void Integrator::queueOcclusionRays(const LaneConstants& constants, TileScratch& scratch, RayTally& tally) const {
  const SurfaceLanes& S = scratch.surfaces;
  scratch.sun_list.resize(S.stride * light_spp_ + CameraLanes::kPad);
  scratch.sky_list.resize(S.stride * ao_spp_ + CameraLanes::kPad);
  const OccluderCounts counts = occluderLanes(constants, scratch.surfaces, scratch.sun_list.data(), scratch.sky_list.data());
  tally.rays += counts.made;
  if (tally.occlusion) logOcclusionRays(S, *tally.occlusion);
  // The listed rays as Embree's: the list ascends, one block of the per-ray arrays (ray k of every
  // surface) after another, so a ray's surface is its index less its block's start.
  auto stream = [&](const std::vector<int32_t>& list, std::size_t count, const std::vector<float>& wx,
                    const std::vector<float>& wy, const std::vector<float>& wz, const float* t_far,
                    std::vector<RTCRay>& rays) {
    rays.resize(count);
    std::size_t block = 0;
    for (std::size_t r = 0; r < count; ++r) {
      const std::size_t at = std::size_t(list[r]);
      while (at >= block + S.stride) block += S.stride;
      const std::size_t s = at - block;
      rays[r] = makeRay({S.rox[s], S.roy[s], S.roz[s]}, {wx[at], wy[at], wz[at]}, t_far ? t_far[at] : kInfinity);
    }
  };
  stream(scratch.sun_list, counts.sun, S.sun_wx, S.sun_wy, S.sun_wz, nullptr, scratch.sun_rays);
  stream(scratch.sky_list, counts.sky, S.sky_wx, S.sky_wy, S.sky_wz, S.sky_t_far.data(), scratch.sky_rays);
  if (!terrain_) return;
  for (std::size_t s = 0; s < S.size; ++s) {
    if (!S.hills[s] || !S.sun_traced[s]) continue;
    for (std::size_t k = 0, at = s; k < light_spp_; ++k, at += S.stride) {
      if (!S.sun_valid[at]) continue;
      scratch.hill_rays.push_back(makeRay({S.rox[s], S.roy[s], S.roz[s]}, {S.sun_wx[at], S.sun_wy[at], S.sun_wz[at]}, kInfinity));
      scratch.hill_list.push_back(int32_t(at));
      ++tally.rays;  // (not kept in a RayLog, whose occlusion rays are replayed against the characters)
    }
  }
}

void Integrator::logOcclusionRays(const SurfaceLanes& S, std::vector<RTCRay>& log) const {
  for (std::size_t s = 0; s < S.size; ++s) {
    const glm::vec3 origin(S.rox[s], S.roy[s], S.roz[s]);
    if (S.sun_traced[s])
      for (std::size_t k = 0, at = s; k < light_spp_; ++k, at += S.stride)
        if (S.sun_valid[at]) log.push_back(makeRay(origin, {S.sun_wx[at], S.sun_wy[at], S.sun_wz[at]}, kInfinity));
    if (S.sky_traced[s])
      for (std::size_t k = 0, at = s; k < ao_spp_; ++k, at += S.stride)
        if (S.sky_valid[at] && S.sky_t_far[at] > 0.0f)
          log.push_back(makeRay(origin, {S.sky_wx[at], S.sky_wy[at], S.sky_wz[at]}, S.sky_t_far[at]));
  }
}

// Pass 4: the shadow rays, the sky rays and the sun rays the hills may block, each as one stream, then
// each surface's light from the rays left open. All three streams go without Embree's coherent flag:
// the shadow rays are nearly parallel, but they start all over a tile's surfaces and part ways in the
// tree; traced ray by ray, a trot frame took 0.95 (draft) and 0.91 (review) of the CPU it took with
// them gathered into packets, with the same hits (docs/performance-history.md, "Streams, coherent or not").
void Integrator::occlusionPass(const LaneConstants& constants, TileScratch& scratch) const {
  auto occlude = [](RTCScene scene, std::vector<RTCRay>& rays, const std::vector<int32_t>& list,
                    std::vector<int32_t>& open) {
    if (rays.empty()) return;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1M(scene, &context, rays.data(), unsigned(rays.size()), sizeof(RTCRay));
    for (std::size_t r = 0; r < rays.size(); ++r)
      if (blocked(rays[r])) open[std::size_t(list[r])] = 0;
  };
  SurfaceLanes& S = scratch.surfaces;
  occlude(characters_, scratch.sun_rays, scratch.sun_list, S.sun_open);
  occlude(characters_, scratch.sky_rays, scratch.sky_list, S.sky_open);
  occlude(ground_, scratch.hill_rays, scratch.hill_list, S.sun_open);  // the sun rays the hills may block
  surfaceRadianceLanes(constants, S);
}

// Pass 5: each pixel's samples into its result. The sky's and open ground's light are read from the
// camera lanes, a surface's from the surface lanes; the passes (depth, matte, normal, object id) are
// worked out only when the renderer keeps them.
void Integrator::resolvePass(int count, TileScratch& scratch, PixelResult* out) const {
  const CameraLanes& lanes = scratch.lanes;
  const SurfaceLanes& S = scratch.surfaces;
  const bool passes = settings_.passes;
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const std::size_t m = scratch.surface_samples.size();
  std::size_t j = 0;  // the sample's index in the lanes
  std::size_t s = 0;  // the next surface's index in the surface lanes
  for (int p = 0; p < count; ++p) {
    glm::vec3 sum(0.0f), normal_sum(0.0f);
    uint32_t hits = 0, character_hits = 0;
    float nearest = kInfinity;
    // Votes for the object id pass: at most a handful of distinct ids can meet in one pixel.
    constexpr int kMaxIds = 4;
    uint32_t ids[kMaxIds], votes[kMaxIds];
    int distinct = 0, sky_votes = 0;
    for (uint32_t i = 0; i < spp_; ++i, ++j) {
      const bool open_ground = lanes.open[j] != 0;
      if (!open_ground && (s == m || std::size_t(scratch.surface_samples[s]) != j)) {  // the sky
        sum += glm::vec3(lanes.sky_r[j], lanes.sky_g[j], lanes.sky_b[j]);
        ++sky_votes;
        continue;
      }
      const std::size_t surface = open_ground ? 0 : s++;
      sum += open_ground ? glm::vec3(lanes.radiance_r[j], lanes.radiance_g[j], lanes.radiance_b[j])
                         : glm::vec3(S.radiance_r[surface], S.radiance_g[surface], S.radiance_b[surface]);
      ++hits;
      if (!passes) continue;
      const ObjectId id = open_ground ? ObjectId::Ground : scratch.surface_ids[surface];
      normal_sum += !open_ground ? glm::vec3(S.nx[surface], S.ny[surface], S.nz[surface])
                    : terrain_   ? glm::vec3(lanes.gnx[j], lanes.gny[j], lanes.gnz[j])
                                 : up;
      if (id != ObjectId::Ground) ++character_hits;
      nearest = std::min(nearest, open_ground ? lanes.depth[j] : S.depth[surface]);
      int k = 0;
      while (k < distinct && ids[k] != uint32_t(id)) ++k;
      if (k == distinct && distinct < kMaxIds) ids[distinct] = uint32_t(id), votes[distinct++] = 0;
      if (k < distinct) ++votes[k];
    }
    PixelResult& r = out[p];
    const float inv = 1.0f / float(spp_);
    r.rgba = glm::vec4(sum * inv, float(hits) * inv);
    if (!passes) continue;  // Renderer::setPasses(false): the colour alone
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

ObjectId Integrator::gatherSurface(const RTCRayHit* rh, const CameraLanes& lanes, std::size_t j, SurfaceLanes& S,
                                   std::size_t m) const {
  const glm::vec3 origin = lanes.origin(j), dir = lanes.direction(j);
  S.dx[m] = dir.x, S.dy[m] = dir.y, S.dz[m] = dir.z;
  if (rh) {
    // A character: the hit and its triangle's vertices, for hitSurfaceLanes.
    const float t = rh->ray.tfar;
    const ShadingMesh& mesh = *meshes_[rh->hit.geomID];
    S.character[m] = -1;
    S.on_ground[m] = 0;
    S.ox[m] = origin.x, S.oy[m] = origin.y, S.oz[m] = origin.z, S.t[m] = t;
    S.gx[m] = rh->hit.Ng_x, S.gy[m] = rh->hit.Ng_y, S.gz[m] = rh->hit.Ng_z;
    S.u[m] = rh->hit.u, S.v[m] = rh->hit.v;
    // Its material: the vertex normals and colours, and a texture's colour at the hit.
    const MaterialHit hit{&mesh, rh->hit.primID, rh->hit.u, rh->hit.v};
    Material::of(mesh, rh->hit.primID).gather(hit, S, m);
    // The ground under the hit (its downward sky rays stop just above it).
    S.ground_y[m] = 0.0f;
    S.hills[m] = 0;
    if (terrain_) {
      const glm::vec3 p = origin + t * dir;
      // The mesh as traced under the hit: within a fraction of a centimetre of the terrain's own height,
      // and a lookup where the terrain's noise costs many; the horizon map (of that mesh) then needs
      // no lookup of its own. Off the mesh, the terrain and the map's own test.
      const double mesh_height = ground_mesh_ ? ground_mesh_->heightAt(double(p.x), double(p.z)) : -kInfinity;
      const bool on_mesh = std::isfinite(mesh_height);
      S.ground_y[m] = float(on_mesh ? mesh_height : terrain_->height(double(p.x), double(p.z)));
      S.hills[m] = (on_mesh ? hillsMayBlockSunAbove(p, mesh_height) : hillsMayBlockSun(p, false)) ? -1 : 0;
    }
    S.haze[m] = 1.0f;  // the characters keep their colours: the haze is the ground's, for the horizon
    return mesh.id;
  }
  S.character[m] = 0;
  S.on_ground[m] = -1;
  S.ground_y[m] = 0.0f;
  S.specular[m] = 0.0f;  // the ground is matte
  const float t = lanes.t_ground[j];
  glm::vec3 p = origin + t * dir;
  // The ground's look came from the lanes (groundLanes or terrainGroundLanes).
  S.ar[m] = lanes.albedo_r[j], S.ag[m] = lanes.albedo_g[j], S.ab[m] = lanes.albedo_b[j];
  S.depth[m] = lanes.depth[j];
  S.haze[m] = lanes.haze[j];
  // On the heightfield mesh as hit: the normal interpolated from the mesh's vertex normals (the
  // terrain's own, smooth and upward), which is also the geometric one the secondary rays leave along
  // (they meet only the characters and the hills). Never flipped toward the camera: at a hill's grazing
  // far side a ray can meet a facet whose smooth normal already faces away, and flipping it there left
  // black specks on the horizon. On the plane: the point exactly on it, so the rays' offset lifts it the
  // same everywhere, and the side the camera sees.
  glm::vec3 n(lanes.gnx[j], lanes.gny[j], lanes.gnz[j]);
  if (!terrain_) {
    p.y = 0.0f;
    n = glm::vec3(0.0f, dir.y <= 0.0f ? 1.0f : -1.0f, 0.0f);
  }
  S.hills[m] = terrain_ && !lanes.hills_open[j] ? -1 : 0;
  S.px[m] = p.x, S.py[m] = p.y, S.pz[m] = p.z;
  S.ngx[m] = S.nx[m] = n.x, S.ngy[m] = S.ny[m] = n.y, S.ngz[m] = S.nz[m] = n.z;
  return ObjectId::Ground;
}

void Integrator::terrainNormal(CameraLanes& lanes, std::size_t k) const {
  const float t = lanes.t_ground[k];
  const glm::vec3 p(lanes.ox[k] + t * lanes.dx[k], lanes.oy[k] + t * lanes.dy[k], lanes.oz[k] + t * lanes.dz[k]);
  const glm::vec3 n(terrain_->normal(double(p.x), double(p.z)));
  lanes.gnx[k] = n.x, lanes.gny[k] = n.y, lanes.gnz[k] = n.z;
}

namespace {

// How far from p a secondary ray leaves: lifted by at most 2e-3 + 3e-5 * its largest coordinate
// (shading_lanes.cpp), and the lanes' p can differ from this one in its last bits: a little more.
float secondaryRaySlack(const glm::vec3& p) {
  const float extent = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
  return 3e-3f + 4e-5f * extent;
}

}  // namespace

bool Integrator::hillsMayBlockSun(const glm::vec3& p, bool on_ground) const {
  if (!hills_) return true;
  return !hills_->open(p, secondaryRaySlack(p), on_ground);
}

bool Integrator::hillsMayBlockSunAbove(const glm::vec3& p, double ground_height) const {
  if (!hills_) return true;
  return !hills_->openAbove(p, secondaryRaySlack(p), ground_height);
}

float Integrator::visibleDistance(const scene::CameraFrame& camera) const {
  return camera.perspective() ? settings_.haze.visibility_cm
                              : camera.targetDistanceF() + settings_.haze.ortho_depth_cm;
}

}  // namespace stirrup::render
