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

// Inverse CDF of the tent filter of radius 1: warping stratified points through it keeps their
// stratification and gives every sample the same weight, so no pixel reads another's samples.
float tentOffset(float u) { return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(2.0f - 2.0f * u); }

// How far to push a secondary ray's origin off the surface: above the float error of a hit point
// computed as origin + t * direction at these coordinates (a few ulps of the largest coordinate).
float originOffset(const glm::vec3& p) {
  const float extent = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return 2e-3f + 3e-5f * extent;
}

}  // namespace

float filteredChecker(float s, float t, float width) {
  const float half = 0.5f * width;
  if (half < 1e-4f) return float((int64_t(std::floor(s)) + int64_t(std::floor(t))) & 1);
  if (half >= 1.0f) return 0.5f;  // the box spans whole pairs of squares: exactly the mean
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
  return ss + tt - 2.0f * ss * tt;  // odd in s xor odd in t
}

struct Integrator::Surface {
  glm::vec3 p;       // hit point
  glm::vec3 ng;      // geometric normal, facing the camera
  glm::vec3 n;       // shading normal, same side as ng
  glm::vec3 wo;      // toward the camera
  glm::vec3 albedo;  // linear base colour
  float specular;    // Blinn-Phong weight
  bool on_ground;
};

Integrator::Integrator(const RenderSettings& settings, const EmbreeScene& scene,
                       std::span<const ShadingMesh* const> meshes_by_geometry)
    : settings_(settings),
      characters_(scene.characters()),
      ground_(scene.ground()),
      meshes_(meshes_by_geometry) {
  const RTCBounds& b = scene.characterBounds();
  bounds_lower_ = {b.lower_x, b.lower_y, b.lower_z};
  bounds_upper_ = {b.upper_x, b.upper_y, b.upper_z};
  const bool empty = !(b.lower_x <= b.upper_x && b.lower_y <= b.upper_y && b.lower_z <= b.upper_z);
  bounds_centre_ = 0.5f * (bounds_lower_ + bounds_upper_);
  bounds_radius_ = empty ? -1.0f : 0.5f * glm::length(bounds_upper_ - bounds_lower_);
  const glm::vec3 sun = glm::normalize(glm::vec3(settings.sun_direction));
  sun_frame_ = Frame::around(sun);
  sun_angle_ = float(std::max(0.0, settings.sun_angular_radius_deg) * std::numbers::pi / 180.0);
  sun_cos_max_ = std::cos(sun_angle_);
  sun_tan_ = std::tan(sun_angle_);
  sun_radiance_ = settings.sun_color * settings.sun_strength;
  const glm::vec3 ground_albedo = 0.5f * (settings.ground_color_a + settings.ground_color_b);
  ground_bounce_ = ground_albedo * (sun_radiance_ * std::max(0.0f, sun.y) + settings.sky.upwardIrradianceOverPi());
  blinn_norm_ = (settings.shininess + 8.0f) / 8.0f;
  ground_extent_ = settings.ground_half_extent_cm;
  spp_ = uint32_t(settings.samples_per_pixel);
  light_spp_ = uint32_t(settings.light_samples);
  ao_spp_ = uint32_t(settings.ao_samples);
}

// Slab test against the characters' bounds: most ground pixels' rays never come near them, and this is
// far cheaper than a call into Embree. (Empty bounds have lower > upper: always a miss.)
bool Integrator::mayHitCharacters(const glm::vec3& origin, const glm::vec3& direction, float t_far) const {
  if (!(t_far > 0.0f)) return false;
  float t0 = 0.0f, t1 = t_far;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / direction[a];
    float near = (bounds_lower_[a] - origin[a]) * inv, far = (bounds_upper_[a] - origin[a]) * inv;
    if (near > far) std::swap(near, far);
    t0 = near > t0 ? near : t0;  // written so a NaN (0 * inf) leaves the interval unchanged
    t1 = far < t1 ? far : t1;
    if (t0 > t1 * 1.0000004f) return false;  // a little slack for rounding at grazing angles
  }
  return true;
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

unsigned Integrator::occluded4(const glm::vec3& origin, const glm::vec3* directions, const float* t_far,
                               int count, RayTally& tally) const {
  unsigned blocked = 0;
  for (int k = 0; k < count; ++k) {
    if (!(t_far[k] > 0.0f)) continue;
    ++tally.rays;
    if (tally.occlusion) tally.occlusion->push_back(makeRay(origin, directions[k], t_far[k]));
    if (!mayHitCharacters(origin, directions[k], t_far[k])) continue;
    RTCRay ray = makeRay(origin, directions[k], t_far[k]);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(characters_, &context, &ray);
    if (ray.tfar < 0.0f) blocked |= 1u << k;  // Embree sets tfar to -inf on a hit
  }
  return blocked;
}

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
    float near = (lower[a] - origin[a]) / d[a], far = (upper[a] - origin[a]) / d[a];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return true;
}

float Integrator::distanceToCharacters(const glm::vec3& p) const {
  if (bounds_radius_ < 0.0f) return kInfinity;
  const glm::vec3 d = glm::max(glm::max(bounds_lower_ - p, p - bounds_upper_), glm::vec3(0.0f));
  return glm::length(d);
}

PixelResult Integrator::renderPixel(const CameraFrame& camera, int x, int y, int frame, RayTally& tally) const {
  const PixelSampler sampler(x, y, frame);
  const Stratified2D pixel_points(sampler, spp_, SampleDimension::PixelFilter);
  const Stratified2D sun_points(sampler, spp_ * light_spp_, SampleDimension::SunCone);
  const Stratified2D sky_points(sampler, spp_ * ao_spp_, SampleDimension::SkyHemisphere);
  const PixelPoints points{sun_points, sky_points};
  glm::vec3 sum(0.0f), normal_sum(0.0f);
  uint32_t hits = 0, character_hits = 0;
  float nearest = kInfinity;
  // Votes for the object id pass: at most a handful of distinct ids can meet in one pixel.
  constexpr int kMaxIds = 4;
  uint32_t ids[kMaxIds], votes[kMaxIds];
  int distinct = 0, sky_votes = 0;
  for (uint32_t i = 0; i < spp_; ++i) {
    const glm::vec2 u = pixel_points[i];
    const float px = float(x) + 0.5f + tentOffset(u.x);
    const float py = float(y) + 0.5f + tentOffset(u.y);
    const Sample s = traceCameraSample(camera, px, py, i, points, tally);
    sum += s.radiance;
    if (!s.hit) {
      ++sky_votes;
      continue;
    }
    ++hits;
    normal_sum += s.normal;
    if (s.id != ObjectId::Ground) ++character_hits;
    nearest = std::min(nearest, s.depth);
    int k = 0;
    while (k < distinct && ids[k] != uint32_t(s.id)) ++k;
    if (k == distinct && distinct < kMaxIds) ids[distinct] = uint32_t(s.id), votes[distinct++] = 0;
    if (k < distinct) ++votes[k];
  }
  PixelResult r;
  const float inv = 1.0f / float(spp_);
  r.rgba = glm::vec4(sum * inv, float(hits) * inv);
  r.depth = nearest;
  r.matte = float(character_hits) * inv;
  const float normal_length = glm::length(normal_sum);
  if (normal_length > 0.0f) r.normal = normal_sum / normal_length;
  // Most votes wins; on a tie the id seen first, and the sky only with more votes than any object.
  r.object_id = kNoObject;
  int best = -1;
  for (int k = 0; k < distinct; ++k) {
    if (int(votes[k]) > best) best = int(votes[k]), r.object_id = ids[k];
  }
  if (sky_votes > best) r.object_id = kNoObject;
  return r;
}

Integrator::Sample Integrator::traceCameraSample(const CameraFrame& camera, float px, float py, uint32_t sample,
                                                 const PixelPoints& points, RayTally& tally) const {
  glm::vec3 origin, dir;
  camera.rayFromPixel(px, py, origin, dir);
  ++tally.rays;
  if (tally.camera) tally.camera->push_back(makeRay(origin, dir, kInfinity));
  // The ground is a square in the plane y = 0: intersected here, without a call into Embree. Its
  // distance then bounds the search through the characters.
  float t_ground = kInfinity;
  if (dir.y != 0.0f) {
    const float t = -origin.y / dir.y;
    if (t > 0.0f) {
      const float hx = origin.x + t * dir.x, hz = origin.z + t * dir.z;
      if (std::abs(hx) <= ground_extent_ && std::abs(hz) <= ground_extent_) t_ground = t;
    }
  }
  const bool ground_hit = t_ground < kInfinity;
  RTCRayHit rh;
  rh.ray = makeRay(origin, dir, t_ground);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  // Most camera rays of a review view pass beside the characters' box: no call into Embree.
  if (mayHitCharacters(origin, dir, t_ground)) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1(characters_, &context, &rh);
  }
  const bool character_hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;

  Sample result;
  if (!ground_hit && !character_hit) {
    result.radiance = settings_.sky.radiance(dir);
    return result;
  }
  const float t = rh.ray.tfar;
  Surface s;
  s.p = origin + t * dir;
  s.wo = -dir;
  if (!character_hit) {
    s.p.y = 0.0f;  // exactly on the plane; the offset below then lifts it the same everywhere
    s.ng = s.n = glm::vec3(0.0f, dir.y <= 0.0f ? 1.0f : -1.0f, 0.0f);
    // The sample's footprint on the ground: a pixel's width at this distance, stretched by the
    // grazing angle (isotropically, which blurs a little more than needed across the view).
    const float cos_view = std::max(std::abs(dir.y), 0.02f);
    const float width = camera.pixelFootprintF(t) / cos_view / settings_.ground_square_cm;
    const float odd = filteredChecker(s.p.x / settings_.ground_square_cm, s.p.z / settings_.ground_square_cm, width);
    s.albedo = glm::mix(settings_.ground_color_a, settings_.ground_color_b, odd);
    s.specular = 0.0f;
    s.on_ground = true;
    result.id = ObjectId::Ground;
  } else {
    const ShadingMesh& mesh = *meshes_[rh.hit.geomID];
    const uint32_t* tri = &mesh.indices[size_t(rh.hit.primID) * 3];
    const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0f - b1 - b2;
    s.ng = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
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
    s.on_ground = false;
    result.id = mesh.id;
  }
  result.hit = true;
  result.depth = camera.viewDepthF(s.p);
  result.normal = s.n;
  result.radiance = shade(s, sample, points, tally);
  return result;
}

glm::vec3 Integrator::shade(const Surface& s, uint32_t sample, const PixelPoints& points, RayTally& tally) const {
  // Secondary rays start off the surface along the geometric normal (not the shading normal,
  // which can point into neighbouring triangles): no acne, and contacts stay tight.
  const glm::vec3 origin = s.p + s.ng * originOffset(s.p);
  const glm::vec3 diffuse = s.albedo * (1.0f - s.specular);

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
  glm::vec3 sun(0.0f);
  if (!sunMayBeBlocked(origin)) {
    sun = reflected(sun_frame_.z) * sun_radiance_;
  } else {
    for (uint32_t first = 0; first < light_spp_; first += 4) {
      const int n = int(std::min(4u, light_spp_ - first));
      glm::vec3 wi[4], f[4];
      float t_far[4];
      for (int k = 0; k < n; ++k) {
        wi[k] = sampleCone(sun_frame_, sun_cos_max_, points.sun[sample * light_spp_ + first + k]);
        f[k] = reflected(wi[k]);
        t_far[k] = f[k] == glm::vec3(0.0f) ? 0.0f : kInfinity;  // no light from below: skip the ray
      }
      const unsigned blocked = occluded4(origin, wi, t_far, n, tally);
      for (int k = 0; k < n; ++k) {
        if (!(blocked & (1u << k))) sun += f[k];
      }
    }
    sun *= sun_radiance_ / float(light_spp_);
  }

  // Sky: ambient occlusion against the gradient sky. Rays heading down from a character stop just
  // short of the ground: if nothing else is in the way they see the sunlit ground's bounce.
  // Open ground farther than ao_distance from the characters sees the whole sky: use its exact
  // cosine-weighted mean instead of rays.
  if (s.on_ground && s.ng.y > 0.0f && distanceToCharacters(origin) > settings_.ao_distance_cm) {
    return sun + diffuse * settings_.sky.upwardIrradianceOverPi();
  }
  glm::vec3 sky(0.0f);
  const Frame around = Frame::around(s.n);
  for (uint32_t first = 0; first < ao_spp_; first += 4) {
    const int n = int(std::min(4u, ao_spp_ - first));
    glm::vec3 wi[4];
    float t_far[4];
    bool open[4];
    for (int k = 0; k < n; ++k) {
      wi[k] = sampleCosineHemisphere(around, points.sky[sample * ao_spp_ + first + k]);
      open[k] = glm::dot(s.ng, wi[k]) > 0.0f;  // below the real surface: blocked by it
      t_far[k] = settings_.ao_distance_cm;
      if (!s.on_ground && wi[k].y < 0.0f) t_far[k] = std::min(t_far[k], 0.999f * origin.y / -wi[k].y);
      if (!open[k]) t_far[k] = 0.0f;
    }
    const unsigned blocked = occluded4(origin, wi, t_far, n, tally);
    for (int k = 0; k < n; ++k) {
      if (!open[k] || (blocked & (1u << k))) continue;
      sky += (!s.on_ground && wi[k].y < 0.0f) ? ground_bounce_ : settings_.sky.radiance(wi[k]);
    }
  }
  sky *= diffuse / float(ao_spp_);
  return sun + sky;
}

}  // namespace stirrup::render
