// Highway compiles this file once per target (foreach_target.h re-includes it); HWY_ONCE marks the
// part compiled once: the dispatch tables and the entry points of shading_lanes.h.
#include "render/tracer/shading_lanes.h"

#include <algorithm>
#include <limits>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/tracer/shading_lanes.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "render/tracer/lane_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace stirrup::render {
namespace HWY_NAMESPACE {

// A character's hit surface, lane by lane: the point along the camera ray, Embree's normal made unit
// and turned to the camera, the vertex normals interpolated (and turned to the same side), tilted
// toward the camera where they face away at a silhouette so the edge does not turn black, and the
// vertex colours interpolated (times the texture's colour the integrator looked up at the hit).
void HitSurfaceLanes(const LaneConstants& k, SurfaceLanes& S) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  for (size_t i = 0; i < S.padded; i += lanes) {
    const MF character = LoadMask(S.character, i);
    if (hn::AllFalse(df, character)) continue;
    const V3 d = Load3(S.dx, S.dy, S.dz, i);
    const VF t = Load(S.t, i);
    const V3 p = Add3(Load3(S.ox, S.oy, S.oz, i), Scale3(t, d));
    const V3 wo = Neg3(d);
    V3 ng = Normalize3(Load3(S.gx, S.gy, S.gz, i));
    ng = Select3(hn::Gt(Dot3(ng, d), Splat(0.0f)), Neg3(ng), ng);
    const VF b1 = Load(S.u, i), b2 = Load(S.v, i);
    const VF b0 = hn::Sub(hn::Sub(Splat(1.0f), b1), b2);
    auto interpolate = [&](const V3& a, const V3& b, const V3& c) {
      return Add3(Add3(Scale3(b0, a), Scale3(b1, b)), Scale3(b2, c));
    };
    V3 n = interpolate(Load3(S.n0x, S.n0y, S.n0z, i), Load3(S.n1x, S.n1y, S.n1z, i), Load3(S.n2x, S.n2y, S.n2z, i));
    const VF len = Length3(n);
    n = Select3(hn::Gt(len, Splat(1e-12f)), V3{hn::Div(n.x, len), hn::Div(n.y, len), hn::Div(n.z, len)}, ng);
    n = Select3(hn::Lt(Dot3(n, ng), Splat(0.0f)), Neg3(n), n);  // seeing the back of the surface
    const VF facing = Dot3(n, wo);
    const V3 tilted = Normalize3(Add3(n, Scale3(hn::Sub(Splat(0.01f), facing), wo)));
    n = Select3(hn::Lt(facing, Splat(0.01f)), tilted, n);
    // Times the texture's colour (exactly 1 without a texture, which leaves the colour's bits as they were).
    const V3 albedo = Mul3(
        interpolate(Load3(S.c0r, S.c0g, S.c0b, i), Load3(S.c1r, S.c1g, S.c1b, i), Load3(S.c2r, S.c2g, S.c2b, i)),
        Load3(S.tr, S.tg, S.tb, i));
    // CameraFrame::viewDepthF(p).
    const VF depth = Dot3(Sub3(p, Splat3(k.position)), Splat3(k.forward));
    auto keep = [&](VF fresh, std::vector<float>& out) { Store(hn::IfThenElse(character, fresh, Load(out, i)), out, i); };
    keep(p.x, S.px), keep(p.y, S.py), keep(p.z, S.pz);
    keep(ng.x, S.ngx), keep(ng.y, S.ngy), keep(ng.z, S.ngz);
    keep(n.x, S.nx), keep(n.y, S.ny), keep(n.z, S.nz);
    keep(albedo.x, S.ar), keep(albedo.y, S.ag), keep(albedo.z, S.ab);
    keep(Splat(k.specular), S.specular);
    keep(depth, S.depth);
  }
}

// BRDF times cosine for light arriving from wi (0 from below the surface): Brdf::reflected
// (render/tracer/material.h) for a vector of surfaces.
struct ReflectedLanes {
  V3 n, ng, wo, diffuse;
  MF glossy;
  VF lobe_weight;
  int shininess;

  HWY_INLINE V3 operator()(const V3& wi) const {
    const DF df;
    const VF zero = Splat(0.0f);
    const VF cos_n = Dot3(n, wi);
    const MF lit = hn::Not(hn::Or(hn::Le(cos_n, zero), hn::Le(Dot3(ng, wi), zero)));
    V3 f = diffuse;
    if (!hn::AllFalse(df, glossy)) {
      const VF cos_h = hn::Max(zero, Dot3(n, Normalize3(Add3(wi, wo))));
      const VF lobe = hn::Mul(lobe_weight, PowWhole(cos_h, shininess));
      f = Select3(glossy, V3{hn::Add(f.x, lobe), hn::Add(f.y, lobe), hn::Add(f.z, lobe)}, f);
    }
    f = Scale3(cos_n, f);
    return Select3(lit, f, V3{zero, zero, zero});
  }
};

// The sun (render/tracer/light.h, Sun) for the surfaces at i: shadow rays over its disc where any ray of
// its cone may meet the characters; elsewhere once along its axis, with no ray. Ground points outside
// the sun's rectangle are open at once.
HWY_INLINE void SunLanes(const LaneConstants& k, SurfaceLanes& S, size_t i, const V3& origin, MF on_ground,
                         const ReflectedLanes& reflected) {
  const DF df;
  const VF zero = Splat(0.0f), one = Splat(1.0f);
  const Frame3 sun_frame = {Splat3(k.sun_frame_x), Splat3(k.sun_frame_y), Splat3(k.sun_axis)};
  MF sun_traced = k.open_ground_shortcuts ? SunMayBeBlocked(k, origin) : hn::Not(hn::FirstN(df, 0));
  if (k.sun_region) {
    const MF outside = hn::Or(hn::Or(hn::Lt(origin.x, Splat(k.sun_lower_x)), hn::Gt(origin.x, Splat(k.sun_upper_x))),
                              hn::Or(hn::Lt(origin.z, Splat(k.sun_lower_z)), hn::Gt(origin.z, Splat(k.sun_upper_z))));
    const MF excluded = hn::And(on_ground, hn::And(hn::Ge(origin.y, Splat(k.ground_floor)), outside));
    sun_traced = hn::AndNot(excluded, sun_traced);
  }
  sun_traced = hn::Or(sun_traced, LoadMask(S.hills, i));
  StoreMask(sun_traced, S.sun_traced, i);
  Store3(Mul3(reflected(sun_frame.z), Splat3(k.sun_radiance)), S.sun_r, S.sun_g, S.sun_b, i);
  if (hn::AllFalse(df, sun_traced)) return;
  for (int s = 0; s < k.light_samples; ++s) {
    const size_t at = size_t(s) * S.stride + i;
    const VF cos_t = hn::Sub(one, hn::Mul(Load(S.sun_u, at), hn::Sub(one, Splat(k.sun_cos_max))));
    const VF sin_t = hn::Sqrt(hn::Max(zero, hn::Sub(one, hn::Mul(cos_t, cos_t))));
    VF c, sn;
    UnitCircle(Load(S.sun_v, at), c, sn);
    const V3 wi = sun_frame.toWorld(hn::Mul(sin_t, c), hn::Mul(sin_t, sn), cos_t);
    const V3 f = reflected(wi);
    const MF carries = hn::Or(hn::Or(hn::Ne(f.x, zero), hn::Ne(f.y, zero)), hn::Ne(f.z, zero));
    Store3(wi, S.sun_wx, S.sun_wy, S.sun_wz, at);
    Store3(f, S.sun_fr, S.sun_fg, S.sun_fb, at);
    StoreMask(hn::And(sun_traced, carries), S.sun_valid, at);
  }
}

// Whether the surfaces at i need sky rays: ambient occlusion against the gradient sky, except open
// ground farther than ao_distance from the characters, which sees the whole sky (Sky::mayBeBlocked).
// Without the shortcuts (a crowd) every point samples the sky.
HWY_INLINE MF SkyTraced(const LaneConstants& k, const V3& origin, const V3& ng, MF on_ground) {
  const DF df;
  const VF zero = Splat(0.0f);
  if (k.box_empty) return hn::Not(hn::And(on_ground, hn::Gt(ng.y, zero)));  // no characters: infinitely far
  if (!k.open_ground_shortcuts) return hn::Not(hn::FirstN(df, 0));
  const V3 e = {hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.x), origin.x), hn::Sub(origin.x, Splat(k.box_upper.x))), zero),
                hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.y), origin.y), hn::Sub(origin.y, Splat(k.box_upper.y))), zero),
                hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.z), origin.z), hn::Sub(origin.z, Splat(k.box_upper.z))), zero)};
  return hn::Not(hn::And(hn::And(on_ground, hn::Gt(ng.y, zero)), hn::Gt(Length3(e), Splat(k.ao_distance))));
}

// The sky (render/tracer/light.h, Sky) for the surfaces at i: the exact cosine-weighted mean where no
// ray is needed, else its cosine-weighted rays. A character's rays heading down stop just short of the
// ground: if nothing else is in the way they see the lit ground's bounce.
HWY_INLINE void SkyLanes(const LaneConstants& k, SurfaceLanes& S, size_t i, const V3& origin, const V3& ng, const V3& n,
                         const V3& diffuse, MF on_ground) {
  const DF df;
  const VF zero = Splat(0.0f), one = Splat(1.0f);
  const MF sky_traced = SkyTraced(k, origin, ng, on_ground);
  StoreMask(sky_traced, S.sky_traced, i);
  Store3(Mul3(diffuse, Splat3(k.sky_irradiance)), S.sky_r, S.sky_g, S.sky_b, i);
  if (hn::AllFalse(df, sky_traced)) return;
  const Frame3 around = FrameAround(n);
  const VF above = hn::Sub(origin.y, Load(S.ground_y, i));
  const VF quarter_pi = Splat(3.14159265358979323846f / 4.0f);
  for (int s = 0; s < k.ao_samples; ++s) {
    const size_t at = size_t(s) * S.stride + i;
    // sampleCosineHemisphere (render/tracer/lights.h).
    const VF a = hn::Sub(hn::Mul(Splat(2.0f), Load(S.sky_u, at)), one);
    const VF b = hn::Sub(hn::Mul(Splat(2.0f), Load(S.sky_v, at)), one);
    const MF wide = hn::Gt(hn::Abs(a), hn::Abs(b));
    const VF r = hn::IfThenElse(wide, a, b);
    const VF angle = hn::IfThenElse(hn::Ne(r, zero), hn::Mul(quarter_pi, hn::Div(hn::IfThenElse(wide, b, a), r)), zero);
    VF sn, c;
    SinCosQuarterPi(angle, sn, c);
    const VF dx = hn::Mul(r, hn::IfThenElse(wide, c, sn)), dy = hn::Mul(r, hn::IfThenElse(wide, sn, c));
    const VF dz = hn::Sqrt(hn::Max(zero, hn::Sub(hn::Sub(one, hn::Mul(dx, dx)), hn::Mul(dy, dy))));
    const V3 wi = around.toWorld(dx, dy, dz);
    const MF toward_ground = hn::AndNot(on_ground, hn::Lt(wi.y, zero));
    const VF to_ground = hn::Div(hn::Mul(Splat(0.999f), above), hn::Neg(wi.y));
    const VF t_far = hn::IfThenElse(toward_ground, hn::Min(Splat(k.ao_distance), to_ground), Splat(k.ao_distance));
    // SkyGradient::radiance, or the ground's bounce.
    const MF down = hn::Lt(wi.y, zero);
    const VF a_down = hn::Min(one, hn::Mul(Splat(-8.0f), wi.y));
    const VF a_up = hn::Sqrt(hn::Max(wi.y, zero));
    auto channel = [&](float horizon, float below, float zenith, float bounce) {
      const VF sky = hn::IfThenElse(down, Mix(Splat(horizon), Splat(below), a_down), Mix(Splat(horizon), Splat(zenith), a_up));
      return hn::IfThenElse(toward_ground, Splat(bounce), sky);
    };
    Store3(wi, S.sky_wx, S.sky_wy, S.sky_wz, at);
    Store(t_far, S.sky_t_far, at);
    Store(channel(k.horizon.x, k.below.x, k.zenith.x, k.ground_bounce.x), S.sky_lr, at);
    Store(channel(k.horizon.y, k.below.y, k.zenith.y, k.ground_bounce.y), S.sky_lg, at);
    Store(channel(k.horizon.z, k.below.z, k.zenith.z, k.ground_bounce.z), S.sky_lb, at);
    StoreMask(hn::And(sky_traced, hn::Gt(Dot3(ng, wi), zero)), S.sky_valid, at);
  }
}

// Each surface's light that needs no ray, and the shadow and sky rays it needs (see shading_lanes.h):
// the secondary rays' origin and the material's BRDF, then the sun's and the sky's lanes.
void ShadingLanes(const LaneConstants& k, SurfaceLanes& S) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  const VF zero = Splat(0.0f), one = Splat(1.0f);
  for (size_t i = 0; i < S.padded; i += lanes) {
    const V3 p = Load3(S.px, S.py, S.pz, i), ng = Load3(S.ngx, S.ngy, S.ngz, i), n = Load3(S.nx, S.ny, S.nz, i);
    const V3 wo = Neg3(Load3(S.dx, S.dy, S.dz, i));
    const V3 albedo = Load3(S.ar, S.ag, S.ab, i);
    const VF specular = Load(S.specular, i);
    const MF on_ground = LoadMask(S.on_ground, i);
    // Secondary rays start off the surface along the geometric normal (not the shading normal, which
    // can point into neighbouring triangles), by more than a hit point's float error at these
    // coordinates (a few ulps of the largest).
    const VF extent = hn::Max(hn::Max(hn::Abs(p.x), hn::Abs(p.y)), hn::Abs(p.z));
    const VF offset = hn::Add(Splat(2e-3f), hn::Mul(Splat(3e-5f), extent));
    const V3 origin = Add3(p, Scale3(offset, ng));
    const V3 diffuse = Scale3(hn::Sub(one, specular), albedo);
    Store3(origin, S.rox, S.roy, S.roz, i);
    Store3(diffuse, S.diffuse_r, S.diffuse_g, S.diffuse_b, i);
    const ReflectedLanes reflected{n, ng, wo, diffuse, hn::Gt(specular, zero), hn::Mul(specular, Splat(k.blinn_norm)),
                                   k.shininess};
    SunLanes(k, S, i, origin, on_ground, reflected);
    SkyLanes(k, S, i, origin, ng, n, diffuse, on_ground);
  }
}

// occluderLanes: the rays of one kind (sun or sky), block by block of the per-ray arrays (block r holds
// every surface's ray r), so the list comes out ascending.
template <typename FarEnd>
void ListOccluders(const LaneConstants& k, SurfaceLanes& S, const std::vector<int32_t>& traced_of_surface,
                   const std::vector<float>& wx, const std::vector<float>& wy, const std::vector<float>& wz,
                   const std::vector<int32_t>& valid_of_ray, std::vector<int32_t>& open, int rays_a_surface,
                   FarEnd far_end, int32_t* list, size_t& listed, size_t& made) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  for (int r = 0; r < rays_a_surface; ++r) {
    for (size_t i = 0; i < S.padded; i += lanes) {
      const size_t at = size_t(r) * S.stride + i;
      const MF traced = hn::And(Live(S.size, i), LoadMask(traced_of_surface, i));
      const MF valid = hn::And(traced, LoadMask(valid_of_ray, at));
      StoreMask(valid, open, at);
      if (hn::AllFalse(df, valid)) continue;
      const VF t_far = far_end(at);
      made += hn::CountTrue(df, hn::And(valid, hn::Gt(t_far, Splat(0.0f))));
      const MF hit = hn::And(valid, BoxTest(k, Load(S.rox, i), Load(S.roy, i), Load(S.roz, i), Load(wx, at),
                                            Load(wy, at), Load(wz, at), t_far));
      hn::CompressStore(hn::Iota(di, int32_t(at)), hn::RebindMask(di, hit), di, list + listed);
      listed += hn::CountTrue(df, hit);
    }
  }
}

OccluderCounts OccluderLanes(const LaneConstants& k, SurfaceLanes& S, int32_t* sun_list, int32_t* sky_list) {
  OccluderCounts c;
  const VF infinity = Splat(std::numeric_limits<float>::infinity());
  ListOccluders(k, S, S.sun_traced, S.sun_wx, S.sun_wy, S.sun_wz, S.sun_valid, S.sun_open, k.light_samples,
                [&](size_t) { return infinity; }, sun_list, c.sun, c.made);
  ListOccluders(k, S, S.sky_traced, S.sky_wx, S.sky_wy, S.sky_wz, S.sky_valid, S.sky_open, k.ao_samples,
                [&](size_t at) { return Load(S.sky_t_far, at); }, sky_list, c.sky, c.made);
  return c;
}

// The sum of the weights of a surface's open rays, ray by ray in order (as the scalar loop added them).
HWY_INLINE V3 OpenSum(const SurfaceLanes& S, size_t i, int rays_a_surface, const std::vector<int32_t>& open,
                      const std::vector<float>& r, const std::vector<float>& g, const std::vector<float>& b) {
  const VF zero = Splat(0.0f);
  V3 sum{zero, zero, zero};
  for (int ray = 0; ray < rays_a_surface; ++ray) {
    const size_t at = size_t(ray) * S.stride + i;
    sum = Select3(LoadMask(open, at), Add3(sum, Load3(r, g, b, at)), sum);
  }
  return sum;
}

void SurfaceRadianceLanes(const LaneConstants& k, SurfaceLanes& S) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  // Sun::axisRadiance() / light samples, as glm divides a vec3 by a float.
  const glm::vec3 sun_scale = k.sun_radiance / float(k.light_samples);
  const VF ao = Splat(float(k.ao_samples));
  for (size_t i = 0; i < S.padded; i += lanes) {
    const MF sun_traced = LoadMask(S.sun_traced, i), sky_traced = LoadMask(S.sky_traced, i);
    V3 sun = Load3(S.sun_r, S.sun_g, S.sun_b, i);
    if (!hn::AllFalse(df, sun_traced)) {
      const V3 traced = Mul3(OpenSum(S, i, k.light_samples, S.sun_open, S.sun_fr, S.sun_fg, S.sun_fb), Splat3(sun_scale));
      sun = Select3(sun_traced, traced, sun);
    }
    V3 sky = Load3(S.sky_r, S.sky_g, S.sky_b, i);
    if (!hn::AllFalse(df, sky_traced)) {
      const V3 scale = {hn::Div(Load(S.diffuse_r, i), ao), hn::Div(Load(S.diffuse_g, i), ao),
                        hn::Div(Load(S.diffuse_b, i), ao)};
      const V3 traced = Mul3(OpenSum(S, i, k.ao_samples, S.sky_open, S.sky_lr, S.sky_lg, S.sky_lb), scale);
      sky = Select3(sky_traced, traced, sky);
    }
    V3 radiance = Add3(sun, sky);
    const VF haze = Load(S.haze, i);
    const VF clear = hn::Sub(Splat(1.0f), haze);
    radiance = Select3(hn::Lt(haze, Splat(1.0f)), Add3(Scale3(haze, radiance), Scale3(clear, Splat3(k.horizon))), radiance);
    Store3(radiance, S.radiance_r, S.radiance_g, S.radiance_b, i);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace stirrup::render
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stirrup::render {

HWY_EXPORT(HitSurfaceLanes);
HWY_EXPORT(ShadingLanes);
HWY_EXPORT(OccluderLanes);
HWY_EXPORT(SurfaceRadianceLanes);

void SurfaceLanes::reserve(std::size_t n, int light_samples, int ao_samples) {
  size = padded = 0;
  // A batch no larger than one before, with as many rays a surface, finds every array sized (the stride
  // stays the larger batch's): nothing to resize, which was a visible part of a batch's set-up.
  const std::size_t needed = CameraLanes::paddedSize(n);
  if (needed <= stride && light_samples == reserved_light_samples && ao_samples == reserved_ao_samples) return;
  stride = light_samples == reserved_light_samples && ao_samples == reserved_ao_samples ? std::max(stride, needed) : needed;
  reserved_light_samples = light_samples, reserved_ao_samples = ao_samples;
  for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &t, &gx, &gy, &gz, &u, &v, &n0x, &n0y, &n0z, &n1x, &n1y, &n1z, &n2x,
                  &n2y, &n2z, &c0r, &c0g, &c0b, &c1r, &c1g, &c1b, &c2r, &c2g, &c2b, &px, &py, &pz, &ngx, &ngy, &ngz,
                  &nx, &ny, &nz, &ar, &ag, &ab, &specular, &depth, &ground_y, &rox, &roy, &roz, &diffuse_r,
                  &diffuse_g, &diffuse_b, &sun_r, &sun_g, &sun_b, &sky_r, &sky_g, &sky_b, &radiance_r, &radiance_g, &radiance_b})
    v->resize(stride, 0.0f);
  for (auto* v : {&tr, &tg, &tb, &haze}) v->resize(stride, 1.0f);
  for (auto* v : {&character, &on_ground, &hills, &sun_traced, &sky_traced}) v->resize(stride, 0);
  const std::size_t sun_rays = stride * std::size_t(light_samples), sky_rays = stride * std::size_t(ao_samples);
  for (auto* v : {&sun_u, &sun_v, &sun_wx, &sun_wy, &sun_wz, &sun_fr, &sun_fg, &sun_fb}) v->resize(sun_rays, 0.0f);
  sun_valid.resize(sun_rays, 0);
  sun_open.resize(sun_rays, 0);
  for (auto* v : {&sky_u, &sky_v, &sky_wx, &sky_wy, &sky_wz, &sky_t_far, &sky_lr, &sky_lg, &sky_lb})
    v->resize(sky_rays, 0.0f);
  sky_valid.resize(sky_rays, 0);
  sky_open.resize(sky_rays, 0);
}

void SurfaceLanes::setSize(std::size_t n) {
  size = n;
  padded = CameraLanes::paddedSize(n);
}

void hitSurfaceLanes(const LaneConstants& k, SurfaceLanes& surfaces) {
  HWY_DYNAMIC_DISPATCH(HitSurfaceLanes)(k, surfaces);
}
void shadingLanes(const LaneConstants& k, SurfaceLanes& surfaces) { HWY_DYNAMIC_DISPATCH(ShadingLanes)(k, surfaces); }
OccluderCounts occluderLanes(const LaneConstants& k, SurfaceLanes& surfaces, int32_t* sun_list, int32_t* sky_list) {
  return HWY_DYNAMIC_DISPATCH(OccluderLanes)(k, surfaces, sun_list, sky_list);
}
void surfaceRadianceLanes(const LaneConstants& k, SurfaceLanes& surfaces) {
  HWY_DYNAMIC_DISPATCH(SurfaceRadianceLanes)(k, surfaces);
}

}  // namespace stirrup::render
#endif  // HWY_ONCE
