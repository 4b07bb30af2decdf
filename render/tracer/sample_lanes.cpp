// Highway compiles this file once per target (foreach_target.h re-includes it); HWY_ONCE marks the
// part compiled once: the dispatch tables and the entry points of sample_lanes.h.
#include "render/tracer/sample_lanes.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/tracer/sample_lanes.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "render/tracer/lane_math-inl.h"

HWY_BEFORE_NAMESPACE();
namespace stirrup::render {
namespace HWY_NAMESPACE {

// Inverse CDF of the tent filter of radius 1: warping stratified points through it keeps their
// stratification and gives every sample the same weight, so no pixel reads another's samples.
// u < 0.5 ? sqrt(2u) - 1 : 1 - sqrt(2 - 2u).
VF TentOffset(VF u) {
  const VF low = hn::Sub(hn::Sqrt(hn::Mul(Splat(2.0f), u)), Splat(1.0f));
  const VF high = hn::Sub(Splat(1.0f), hn::Sqrt(hn::Sub(Splat(2.0f), hn::Mul(Splat(2.0f), u))));
  return hn::IfThenElse(hn::Lt(u, Splat(0.5f)), low, high);
}

// v - 2 floor(v / 2) for a whole v: its parity, 0 or 1.
VF Parity(VF v) { return hn::Sub(v, hn::Mul(Splat(2.0f), hn::Floor(hn::Mul(v, Splat(0.5f))))); }

// filteredChecker (integrator.cpp), lane by lane.
VF Checker(VF s, VF t, VF width) {
  const VF half = hn::Mul(Splat(0.5f), width);
  // Sharp: the parity of floor(s) + floor(t).
  const VF ps = Parity(hn::Floor(s)), pt = Parity(hn::Floor(t));
  const VF sharp = hn::Sub(hn::Add(ps, pt), hn::Mul(hn::Mul(Splat(2.0f), ps), pt));
  auto integral = [](VF x) {
    const VF f = hn::Floor(hn::Mul(x, Splat(0.5f)));
    const VF rest = hn::Sub(hn::Sub(hn::Mul(x, Splat(0.5f)), f), Splat(0.5f));
    return hn::Add(f, hn::Mul(Splat(2.0f), hn::Max(rest, Splat(0.0f))));
  };
  auto box = [&](VF x) {
    x = hn::Sub(x, hn::Mul(Splat(2.0f), hn::Floor(hn::Mul(x, Splat(0.5f)))));
    return hn::Div(hn::Sub(integral(hn::Add(x, half)), integral(hn::Sub(x, half))), hn::Mul(Splat(2.0f), half));
  };
  const VF ss = box(s), tt = box(t);
  const VF odd = hn::Sub(hn::Add(ss, tt), hn::Mul(hn::Mul(Splat(2.0f), ss), tt));
  const VF x = hn::Mul(hn::Sub(width, Splat(kCheckerFadeStart)), Splat(1.0f / (kCheckerFadeEnd - kCheckerFadeStart)));
  const VF contrast = hn::Sub(Splat(1.0f), hn::Mul(hn::Mul(x, x), hn::Sub(Splat(3.0f), hn::Mul(Splat(2.0f), x))));
  const VF faded = hn::Add(Splat(0.5f), hn::Mul(hn::Sub(odd, Splat(0.5f)), contrast));
  VF out = hn::IfThenElse(hn::Le(width, Splat(kCheckerFadeStart)), odd, faded);
  out = hn::IfThenElse(hn::Ge(width, Splat(kCheckerFadeEnd)), Splat(0.5f), out);
  return hn::IfThenElse(hn::Lt(half, Splat(1e-4f)), sharp, out);
}

void CheckerLanes(const float* s, const float* t, const float* width, float* out, size_t n) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    hn::StoreU(Checker(hn::LoadU(df, s + i), hn::LoadU(df, t + i), hn::LoadU(df, width + i)), df, out + i);
  if (i < n) {  // the tail through a padded copy
    alignas(64) float bs[64] = {}, bt[64] = {}, bw[64] = {}, bo[64];
    for (size_t j = i; j < n; ++j) bs[j - i] = s[j], bt[j - i] = t[j], bw[j - i] = width[j];
    hn::StoreU(Checker(hn::LoadU(df, bs), hn::LoadU(df, bt), hn::LoadU(df, bw)), df, bo);
    for (size_t j = i; j < n; ++j) out[j] = bo[j - i];
  }
}

void CameraRayLanes(const LaneConstants& k, CameraLanes& L, bool flat_ground) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  const VF inf = Splat(std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < L.padded; i += lanes) {
    const VF px = hn::Add(Load(L.cx, i), TentOffset(Load(L.ux, i)));
    const VF py = hn::Add(Load(L.cy, i), TentOffset(Load(L.uy, i)));
    // CameraFrame::rayFromPixel.
    const VF x = hn::Sub(hn::Mul(px, Splat(k.pixel_dx)), Splat(k.half_width));
    const VF y = hn::Sub(Splat(k.half_height), hn::Mul(py, Splat(k.pixel_dy)));
    VF ox, oy, oz, dx, dy, dz;
    if (k.perspective) {
      const VF ex = hn::Add(hn::Add(Splat(k.forward.x), hn::Mul(x, Splat(k.right.x))), hn::Mul(y, Splat(k.up.x)));
      const VF ey = hn::Add(hn::Add(Splat(k.forward.y), hn::Mul(x, Splat(k.right.y))), hn::Mul(y, Splat(k.up.y)));
      const VF ez = hn::Add(hn::Add(Splat(k.forward.z), hn::Mul(x, Splat(k.right.z))), hn::Mul(y, Splat(k.up.z)));
      const VF inv = hn::Div(Splat(1.0f), hn::Sqrt(hn::Add(hn::Add(hn::Mul(ex, ex), hn::Mul(ey, ey)), hn::Mul(ez, ez))));
      ox = Splat(k.position.x), oy = Splat(k.position.y), oz = Splat(k.position.z);
      dx = hn::Mul(ex, inv), dy = hn::Mul(ey, inv), dz = hn::Mul(ez, inv);
    } else {
      ox = hn::Add(hn::Add(Splat(k.position.x), hn::Mul(x, Splat(k.right.x))), hn::Mul(y, Splat(k.up.x)));
      oy = hn::Add(hn::Add(Splat(k.position.y), hn::Mul(x, Splat(k.right.y))), hn::Mul(y, Splat(k.up.y)));
      oz = hn::Add(hn::Add(Splat(k.position.z), hn::Mul(x, Splat(k.right.z))), hn::Mul(y, Splat(k.up.z)));
      dx = Splat(k.forward.x), dy = Splat(k.forward.y), dz = Splat(k.forward.z);
    }
    Store(ox, L.ox, i), Store(oy, L.oy, i), Store(oz, L.oz, i);
    Store(dx, L.dx, i), Store(dy, L.dy, i), Store(dz, L.dz, i);
    if (!flat_ground) {
      Store(inf, L.t_ground, i);
      // Between heights low and high: t = (h - o.y) / d.y, both ends ordered and clipped to
      // [0, t_visible]; a level ray is inside the slab along its whole length, or nowhere.
      const MF level = hn::Eq(dy, Splat(0.0f));
      const VF safe = hn::IfThenElse(level, Splat(1.0f), dy);
      const VF ta = hn::Div(hn::Sub(Splat(k.slab_low), oy), safe), tb = hn::Div(hn::Sub(Splat(k.slab_high), oy), safe);
      VF t0 = hn::Max(Splat(0.0f), hn::Min(ta, tb)), t1 = hn::Min(Splat(k.t_visible), hn::Max(ta, tb));
      const MF inside = hn::And(hn::Ge(oy, Splat(k.slab_low)), hn::Le(oy, Splat(k.slab_high)));
      t0 = hn::IfThenElse(level, hn::IfThenElse(inside, Splat(0.0f), inf), t0);
      t1 = hn::IfThenElse(level, hn::IfThenElse(inside, Splat(k.t_visible), Splat(0.0f)), t1);
      Store(t0, L.t_enter, i), Store(t1, L.t_leave, i);
      continue;
    }
    // The plane y = 0: t = -o.y / d.y, kept when 0 < t < t_visible and the hit is on the square.
    const VF t = hn::Div(hn::Neg(oy), dy);
    const VF hx = hn::Add(ox, hn::Mul(t, dx)), hz = hn::Add(oz, hn::Mul(t, dz));
    const VF extent = Splat(k.ground_extent);
    MF on = hn::And(hn::Ne(dy, Splat(0.0f)), hn::And(hn::Gt(t, Splat(0.0f)), hn::Lt(t, Splat(k.t_visible))));
    on = hn::And(on, hn::And(hn::Le(hn::Abs(hx), extent), hn::Le(hn::Abs(hz), extent)));
    const VF t_ground = hn::IfThenElse(on, t, inf);
    Store(t_ground, L.t_ground, i);
    StoreMask(BoxTest(k, ox, oy, oz, dx, dy, dz, t_ground), L.may_hit, i);
  }
}

void BoxTestLanes(const LaneConstants& k, CameraLanes& L) {
  const DF df;
  for (size_t i = 0; i < L.padded; i += hn::Lanes(df)) {
    StoreMask(BoxTest(k, Load(L.ox, i), Load(L.oy, i), Load(L.oz, i), Load(L.dx, i), Load(L.dy, i), Load(L.dz, i),
                      Load(L.t_ground, i)),
              L.may_hit, i);
  }
}

// The samples j < n for which `take` (a mask of the vector at i) holds, ascending, into out; how many.
template <typename Take>
size_t ListSamples(size_t n, size_t padded, int32_t* out, Take take) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  size_t count = 0;
  for (size_t i = 0; i < padded; i += lanes) {
    const MF m = hn::And(Live(n, i), take(i));
    hn::CompressStore(hn::Iota(di, int32_t(i)), hn::RebindMask(di, m), di, out + count);
    count += hn::CountTrue(df, m);
  }
  return count;
}

size_t ListMayHit(const CameraLanes& L, int32_t* out) {
  return ListSamples(L.size, L.padded, out, [&](size_t i) { return LoadMask(L.may_hit, i); });
}

size_t ListSurfaceSamples(const CameraLanes& L, int32_t* out) {
  const DI di;
  const VF inf = Splat(std::numeric_limits<float>::infinity());
  return ListSamples(L.size, L.padded, out, [&](size_t i) {
    const MF character = hn::RebindMask(DF(), hn::Gt(hn::LoadU(di, L.hit_ray.data() + i), hn::Set(di, -1)));
    // Not Ne, which is false for a NaN on x86: the scalar sort took a NaN distance for a surface.
    return hn::AndNot(LoadMask(L.open, i), hn::Or(character, hn::Not(hn::Eq(Load(L.t_ground, i), inf))));
  });
}

// AerialPerspective::perspective and ::orthographic.
VF Haze(const LaneConstants& k, VF t) {
  if (k.perspective) {
    const VF x = hn::Sub(Splat(1.0f), hn::Min(hn::Div(t, Splat(k.haze_visibility)), Splat(1.0f)));
    return hn::Mul(hn::Mul(x, x), x);
  }
  const VF behind = hn::Sub(t, Splat(k.target_distance));
  const VF x = hn::Sub(Splat(1.0f),
                       hn::Min(hn::Max(hn::Div(behind, Splat(k.haze_ortho_depth)), Splat(0.0f)), Splat(1.0f)));
  return hn::Mul(hn::Mul(x, x), x);
}

// The ground's look at sample i, stored: its filtered checker's albedo at (px, pz) for a footprint
// stretched by the view's cosine with the ground, and the haze at distance t.
struct GroundLook {
  VF ar, ag, ab, haze;
};
GroundLook StoreGroundLook(const LaneConstants& k, CameraLanes& L, size_t i, VF t, VF px, VF pz, VF cos_view) {
  const VF footprint = hn::Add(Splat(k.footprint_at_0), hn::Mul(Splat(k.footprint_per_cm), t));
  const VF width = hn::Div(hn::Div(footprint, cos_view), Splat(k.square_cm));
  const VF odd = Checker(hn::Div(px, Splat(k.square_cm)), hn::Div(pz, Splat(k.square_cm)), width);
  const GroundLook g = {Mix(Splat(k.color_a.x), Splat(k.color_b.x), odd), Mix(Splat(k.color_a.y), Splat(k.color_b.y), odd),
                        Mix(Splat(k.color_a.z), Splat(k.color_b.z), odd), Haze(k, t)};
  Store(g.ar, L.albedo_r, i), Store(g.ag, L.albedo_g, i), Store(g.ab, L.albedo_b, i);
  Store(g.haze, L.haze, i);
  return g;
}

// Open ground's light (r, g, b) at sample i, faded into the horizon by the haze, stored.
void StoreOpenLight(const LaneConstants& k, CameraLanes& L, size_t i, VF haze, VF r, VF g, VF b) {
  const MF hazed = hn::Lt(haze, Splat(1.0f));
  const VF clear = hn::Sub(Splat(1.0f), haze);
  auto fade = [&](VF c, float horizon) {
    return hn::IfThenElse(hazed, hn::Add(hn::Mul(c, haze), hn::Mul(Splat(horizon), clear)), c);
  };
  Store(fade(r, k.horizon.x), L.radiance_r, i);
  Store(fade(g, k.horizon.y), L.radiance_g, i);
  Store(fade(b, k.horizon.z), L.radiance_b, i);
}

void GroundLanes(const LaneConstants& k, CameraLanes& L) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  const VF inf = Splat(std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < L.padded; i += lanes) {
    const VF t = Load(L.t_shade, i);
    const MF ground = hn::Lt(t, inf);
    if (hn::AllFalse(df, ground)) {
      StoreMask(ground, L.open, i);
      continue;
    }
    const VF ox = Load(L.ox, i), oz = Load(L.oz, i), dx = Load(L.dx, i), dy = Load(L.dy, i), dz = Load(L.dz, i);
    // The plane's surface (Integrator::gatherSurface reads it from here): the point (y exactly 0), the
    // footprint, the checker.
    const VF px = hn::Add(ox, hn::Mul(t, dx)), pz = hn::Add(oz, hn::Mul(t, dz));
    const GroundLook look = StoreGroundLook(k, L, i, t, px, pz, hn::Max(hn::Abs(dy), Splat(0.02f)));
    const VF ar = look.ar, ag = look.ag, ab = look.ab, haze = look.haze;
    // CameraFrame::viewDepthF(p).
    const VF depth = hn::Add(hn::Add(hn::Mul(hn::Sub(px, Splat(k.position.x)), Splat(k.forward.x)),
                                     hn::Mul(hn::Sub(Splat(0.0f), Splat(k.position.y)), Splat(k.forward.y))),
                             hn::Mul(hn::Sub(pz, Splat(k.position.z)), Splat(k.forward.z)));
    Store(depth, L.depth, i);
    // Open ground, seen from above: the shadow rays' origin (as ShadingLanes makes it) outside the
    // sun's rectangle, and farther than ao_distance from the characters' box.
    const VF offset = hn::Add(Splat(2e-3f), hn::Mul(Splat(3e-5f), hn::Max(hn::Max(hn::Abs(px), Splat(0.0f)), hn::Abs(pz))));
    MF open = hn::And(ground, hn::Le(dy, Splat(0.0f)));
    if (!k.sun_region || !k.open_ground_shortcuts) {
      open = hn::FirstN(df, 0);  // none: without the rectangle every point takes the full test
    } else {
      open = hn::And(open, hn::Ge(offset, Splat(k.ground_floor)));
      const MF outside = hn::Or(hn::Or(hn::Lt(px, Splat(k.sun_lower_x)), hn::Gt(px, Splat(k.sun_upper_x))),
                                hn::Or(hn::Lt(pz, Splat(k.sun_lower_z)), hn::Gt(pz, Splat(k.sun_upper_z))));
      open = hn::And(open, outside);
    }
    if (!k.box_empty) {  // farther than ao_distance from the characters' box (as ShadingLanes tests it)
      const VF ex = hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.x), px), hn::Sub(px, Splat(k.box_upper.x))), Splat(0.0f));
      const VF ey = hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.y), offset), hn::Sub(offset, Splat(k.box_upper.y))), Splat(0.0f));
      const VF ez = hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.z), pz), hn::Sub(pz, Splat(k.box_upper.z))), Splat(0.0f));
      const VF distance = hn::Sqrt(hn::Add(hn::Add(hn::Mul(ex, ex), hn::Mul(ey, ey)), hn::Mul(ez, ez)));
      open = hn::And(open, hn::Gt(distance, Splat(k.ao_distance)));
    }
    StoreMask(open, L.open, i);
    if (hn::AllFalse(df, open)) continue;
    // Its light: (albedo cos) sun + albedo sky, then the haze.
    const VF cos_n = Splat(k.sun_y > 0.0f ? k.sun_y : 0.0f);
    const VF ar2 = hn::Add(hn::Mul(hn::Mul(ar, cos_n), Splat(k.sun_radiance.x)), hn::Mul(ar, Splat(k.sky_irradiance.x)));
    const VF ag2 = hn::Add(hn::Mul(hn::Mul(ag, cos_n), Splat(k.sun_radiance.y)), hn::Mul(ag, Splat(k.sky_irradiance.y)));
    const VF ab2 = hn::Add(hn::Mul(hn::Mul(ab, cos_n), Splat(k.sun_radiance.z)), hn::Mul(ab, Splat(k.sky_irradiance.z)));
    StoreOpenLight(k, L, i, haze, ar2, ag2, ab2);
  }
}

// The heightfield's hits as Embree left them in the stream (GroundHits), lane by lane: t_ground, and the
// normal interpolated from the hit triangle's vertex normals: groundTriangleHit's triangle and
// barycentrics, b0 = 1 - b1 - b2, then b0 n0 + b1 n1 + b2 n2, in that order (so every target rounds
// alike). The triangle's vertices come from the grid, not from the index buffer: cell q of a row of
// nx - 1 cells is (i, j) = (q mod (nx - 1), q div (nx - 1)), its corner a = j nx + i = q + j, and its
// triangles are (a, a + nx, a + nx + 1) and (a, a + nx + 1, a + 1) (makeTerrainMesh), which spares three
// gathers a vector that each of the normals' nine gathers waited on. A miss reads cell 0 (Embree leaves
// a miss's cell as it was) and stores a zero normal.
void GroundHitLanes(const GroundHits& h, CameraLanes& L) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  const VF inf = Splat(std::numeric_limits<float>::infinity());
  const VF one = Splat(1.0f);
  const auto invalid = hn::Set(di, int32_t(-1));  // RTC_INVALID_GEOMETRY_ID
  const auto row = hn::Set(di, int32_t(h.row_vertices));
  const auto cells_a_row = hn::Set(di, int32_t(h.row_vertices) - 1);
  const VF per_row = Splat(1.0f / float(h.row_vertices - 1));
  const auto int_one = hn::Set(di, 1);
  const auto three = hn::Set(di, 3);
  const float* normals = reinterpret_cast<const float*>(h.normals);
  for (size_t i = 0; i < L.padded; i += lanes) {
    const auto geom = hn::LoadU(di, reinterpret_cast<const int32_t*>(h.geom) + i);
    const MF hit = hn::RebindMask(df, hn::Ne(geom, invalid));
    Store(hn::IfThenElse(hit, Load(L.t_leave, i), inf), L.t_ground, i);
    if (hn::AllFalse(df, hit)) continue;
    const auto cell = hn::IfThenElseZero(hn::RebindMask(di, hit), hn::LoadU(di, reinterpret_cast<const int32_t*>(h.prim) + i));
    // The cell's row: the float quotient is exact to within one (cells < 2^24), so the remainder
    // says which way to correct it, if at all.
    auto j = hn::ConvertTo(di, hn::Floor(hn::Mul(hn::ConvertTo(df, cell), per_row)));
    const auto rest = hn::Sub(cell, hn::Mul(j, cells_a_row));
    j = hn::IfThenElse(hn::Lt(rest, hn::Zero(di)), hn::Sub(j, int_one), j);
    j = hn::IfThenElse(hn::Lt(rest, cells_a_row), j, hn::Add(j, int_one));
    const auto a = hn::Add(cell, j);
    const VF u = hn::LoadU(df, h.u + i), v = hn::LoadU(df, h.v + i);
    // groundTriangleHit: the quad's first triangle where u + v <= 1, else its second.
    const MF first = hn::Le(hn::Add(u, v), one);
    const auto first_i = hn::RebindMask(di, first);
    const VF b1 = hn::IfThenElse(first, hn::Sub(hn::Sub(one, u), v), hn::Sub(one, v));
    const VF b2 = hn::IfThenElse(first, u, hn::Sub(hn::Add(u, v), one));
    const VF b0 = hn::Sub(hn::Sub(one, b1), b2);
    const auto d = hn::Add(hn::Add(a, row), int_one);
    const auto v1 = hn::IfThenElse(first_i, hn::Add(a, row), d);
    const auto v2 = hn::IfThenElse(first_i, d, hn::Add(a, int_one));
    auto vertexNormal = [&](const decltype(a)& vertex) {
      const auto at = hn::Mul(vertex, three);
      return V3{hn::GatherIndex(df, normals, at), hn::GatherIndex(df, normals, hn::Add(at, int_one)),
                hn::GatherIndex(df, normals, hn::Add(at, hn::Set(di, 2)))};
    };
    const V3 n = Add3(Add3(Scale3(b0, vertexNormal(a)), Scale3(b1, vertexNormal(v1))), Scale3(b2, vertexNormal(v2)));
    Store(hn::IfThenElseZero(hit, n.x), L.gnx, i), Store(hn::IfThenElseZero(hit, n.y), L.gny, i);
    Store(hn::IfThenElseZero(hit, n.z), L.gnz, i);
  }
}

// GroundLanes over a heightfield. What differs from the plane: the point keeps its height, the
// normal comes from the lanes (made unit here), the footprint stretches by the view's angle to that
// normal, and the shadow rays' origin (as ShadingLanes makes it) is lifted along the normal. Open
// ground takes exactly the light the surface path would give it untraced: (albedo cos) sun + albedo sky.
void TerrainGroundLanes(const LaneConstants& k, CameraLanes& L) {
  const DF df;
  const size_t lanes = hn::Lanes(df);
  const VF inf = Splat(std::numeric_limits<float>::infinity());
  const VF zero = Splat(0.0f);
  for (size_t i = 0; i < L.padded; i += lanes) {
    const VF t = Load(L.t_shade, i);
    const MF ground = hn::Lt(t, inf);
    if (hn::AllFalse(df, ground)) {
      StoreMask(ground, L.open, i);
      continue;
    }
    const VF dx = Load(L.dx, i), dy = Load(L.dy, i), dz = Load(L.dz, i);
    const VF px = hn::Add(Load(L.ox, i), hn::Mul(t, dx)), py = hn::Add(Load(L.oy, i), hn::Mul(t, dy));
    const VF pz = hn::Add(Load(L.oz, i), hn::Mul(t, dz));
    VF nx = Load(L.gnx, i), ny = Load(L.gny, i), nz = Load(L.gnz, i);
    const VF length = hn::Sqrt(hn::Add(hn::Add(hn::Mul(nx, nx), hn::Mul(ny, ny)), hn::Mul(nz, nz)));
    const MF usable = hn::Gt(length, zero);
    nx = hn::IfThenElse(usable, hn::Div(nx, length), zero);
    ny = hn::IfThenElse(usable, hn::Div(ny, length), Splat(1.0f));
    nz = hn::IfThenElse(usable, hn::Div(nz, length), zero);
    Store(nx, L.gnx, i), Store(ny, L.gny, i), Store(nz, L.gnz, i);
    const VF cos_view = hn::Max(hn::Abs(hn::Add(hn::Add(hn::Mul(nx, dx), hn::Mul(ny, dy)), hn::Mul(nz, dz))), Splat(0.02f));
    const GroundLook look = StoreGroundLook(k, L, i, t, px, pz, cos_view);
    const VF ar = look.ar, ag = look.ag, ab = look.ab, haze = look.haze;
    const VF depth = hn::Add(hn::Add(hn::Mul(hn::Sub(px, Splat(k.position.x)), Splat(k.forward.x)),
                                     hn::Mul(hn::Sub(py, Splat(k.position.y)), Splat(k.forward.y))),
                             hn::Mul(hn::Sub(pz, Splat(k.position.z)), Splat(k.forward.z)));
    Store(depth, L.depth, i);
    // The hills' horizon map (SunHorizon::open for a point on the mesh, in floats: laneView), with the
    // secondary rays' slack (Integrator's secondaryRaySlack: their offset and the last bits of p).
    const VF extent = hn::Max(hn::Max(hn::Abs(px), hn::Abs(py)), hn::Abs(pz));
    const VF slack = hn::Add(Splat(3e-3f), hn::Mul(Splat(4e-5f), extent));
    MF hills_open = hn::And(ground, hn::Le(slack, Splat(k.hills.max_slack)));
    if (!k.hills.everywhere_open) {
      if (!k.hills.clear) {
        hills_open = hn::FirstN(df, 0);
      } else {
        const DI di;
        const VF fx = hn::Mul(hn::Sub(px, Splat(k.hills.x0)), Splat(k.hills.inv_texel));
        const VF fz = hn::Mul(hn::Sub(pz, Splat(k.hills.z0)), Splat(k.hills.inv_texel));
        const MF inside = hn::And(hn::And(hn::Ge(fx, zero), hn::Ge(fz, zero)),
                                  hn::And(hn::Lt(fx, Splat(float(k.hills.nx))), hn::Lt(fz, Splat(float(k.hills.nz)))));
        hills_open = hn::And(hills_open, inside);
        const auto texel = hn::Add(hn::Mul(hn::ConvertTo(di, fz), hn::Set(di, k.hills.nx)), hn::ConvertTo(di, fx));
        const auto safe = hn::IfThenElseZero(hn::RebindMask(di, hills_open), texel);
        const VF clear = hn::GatherIndex(df, k.hills.clear, safe);
        const VF above = hn::Sub(py, hn::Add(slack, Splat(k.hills.height_margin)));
        hills_open = hn::And(hills_open, hn::Gt(above, clear));
      }
    }
    StoreMask(hills_open, L.hills_open, i);
    MF open = hn::And(hn::And(ground, hn::Gt(ny, zero)), hills_open);
    if (!k.sun_region || !k.open_ground_shortcuts) {
      open = hn::FirstN(df, 0);
    } else {
      // ShadingLanes' origin: p lifted along the (geometric = shading) normal.
      const VF extent = hn::Max(hn::Max(hn::Abs(px), hn::Abs(py)), hn::Abs(pz));
      const VF offset = hn::Add(Splat(2e-3f), hn::Mul(Splat(3e-5f), extent));
      const VF rx = hn::Add(px, hn::Mul(offset, nx)), ry = hn::Add(py, hn::Mul(offset, ny));
      const VF rz = hn::Add(pz, hn::Mul(offset, nz));
      // The sun is open outside its rectangle (ShadingLanes' shortcut) or wherever the full test
      // against the characters' box says so (what ShadingLanes tests inside it): a low sun's rectangle
      // is long, and its oblique shadow fills little of it.
      const MF outside = hn::Or(hn::Or(hn::Lt(rx, Splat(k.sun_lower_x)), hn::Gt(rx, Splat(k.sun_upper_x))),
                                hn::Or(hn::Lt(rz, Splat(k.sun_lower_z)), hn::Gt(rz, Splat(k.sun_upper_z))));
      const MF excluded = hn::And(hn::Ge(ry, Splat(k.ground_floor)), outside);
      open = hn::And(open, hn::Or(excluded, hn::Not(SunMayBeBlocked(k, V3{rx, ry, rz}))));
      if (!k.box_empty) {  // farther than ao_distance from the characters' box (as ShadingLanes tests it)
        const VF ex = hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.x), rx), hn::Sub(rx, Splat(k.box_upper.x))), zero);
        const VF ey = hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.y), ry), hn::Sub(ry, Splat(k.box_upper.y))), zero);
        const VF ez = hn::Max(hn::Max(hn::Sub(Splat(k.box_lower.z), rz), hn::Sub(rz, Splat(k.box_upper.z))), zero);
        const VF distance = hn::Sqrt(hn::Add(hn::Add(hn::Mul(ex, ex), hn::Mul(ey, ey)), hn::Mul(ez, ez)));
        open = hn::And(open, hn::Gt(distance, Splat(k.ao_distance)));
      }
    }
    StoreMask(open, L.open, i);
    if (hn::AllFalse(df, open)) continue;
    // ShadingLanes' reflected(sun axis): cos with the normal, nothing when the sun is below the surface.
    const VF cos_n = hn::Add(hn::Add(hn::Mul(nx, Splat(k.sun_axis.x)), hn::Mul(ny, Splat(k.sun_axis.y))),
                             hn::Mul(nz, Splat(k.sun_axis.z)));
    const MF lit = hn::Gt(cos_n, zero);
    auto sun = [&](VF a, float radiance) { return hn::IfThenElse(lit, hn::Mul(hn::Mul(cos_n, a), Splat(radiance)), zero); };
    const VF ar2 = hn::Add(sun(ar, k.sun_radiance.x), hn::Mul(ar, Splat(k.sky_irradiance.x)));
    const VF ag2 = hn::Add(sun(ag, k.sun_radiance.y), hn::Mul(ag, Splat(k.sky_irradiance.y)));
    const VF ab2 = hn::Add(sun(ab, k.sun_radiance.z), hn::Mul(ab, Splat(k.sky_irradiance.z)));
    StoreOpenLight(k, L, i, haze, ar2, ag2, ab2);
  }
}

void SkyLanes(const LaneConstants& k, CameraLanes& L) {
  const size_t lanes = hn::Lanes(DF());
  for (size_t i = 0; i < L.padded; i += lanes) {
    VF dy = Load(L.dy, i);
    if (!k.perspective) {
      // Integrator::background: graded by the origin's height above the ground's far line.
      const VF line = hn::Sub(Splat(k.sky_floor), hn::Mul(Splat(k.t_visible), dy));
      const VF above = hn::Div(hn::Sub(Load(L.oy, i), line), hn::Mul(Splat(2.0f), Splat(k.half_height)));
      const VF graded = hn::Min(hn::Max(above, Splat(0.0f)), Splat(1.0f));
      dy = hn::IfThenElse(hn::Lt(dy, Splat(0.0f)), graded, dy);
    }
    // SkyGradient::radiance.
    const MF down = hn::Lt(dy, Splat(0.0f));
    const VF a_down = hn::Min(Splat(1.0f), hn::Mul(Splat(-8.0f), dy));
    const VF a_up = hn::Sqrt(hn::Max(dy, Splat(0.0f)));
    auto channel = [&](float horizon, float below, float zenith) {
      return hn::IfThenElse(down, Mix(Splat(horizon), Splat(below), a_down), Mix(Splat(horizon), Splat(zenith), a_up));
    };
    Store(channel(k.horizon.x, k.below.x, k.zenith.x), L.sky_r, i);
    Store(channel(k.horizon.y, k.below.y, k.zenith.y), L.sky_g, i);
    Store(channel(k.horizon.z, k.below.z, k.zenith.z), L.sky_b, i);
  }
}

using DU = hn::RebindToUnsigned<DF>;
using VU = hn::Vec<DU>;
using DU64 = hn::Repartition<uint64_t, DF>;
using VU64 = hn::Vec<DU64>;

// permuteIndex (render/tracer/sampler.h), without its loop's exit: one round of the hashed bijection of
// [0, w] (Kensler 2013, "Correlated Multi-Jittered Sampling").
VU PermuteRound(VU i, VU seed, VU w) {
  const DU du;
  auto keep = [&](VU x) { return hn::And(x, w); };
  i = hn::Xor(i, seed);
  i = hn::Mul(i, hn::Set(du, 0xe170893du));
  i = hn::Xor(i, hn::ShiftRight<16>(seed));
  i = hn::Xor(i, hn::ShiftRight<4>(keep(i)));
  i = hn::Xor(i, hn::ShiftRight<8>(seed));
  i = hn::Mul(i, hn::Set(du, 0x0929eb3fu));
  i = hn::Xor(i, hn::ShiftRight<23>(seed));
  i = hn::Xor(i, hn::ShiftRight<1>(keep(i)));
  i = hn::Mul(i, hn::Or(hn::Set(du, 1u), hn::ShiftRight<27>(seed)));
  i = hn::Mul(i, hn::Set(du, 0x6935fa69u));
  i = hn::Xor(i, hn::ShiftRight<11>(keep(i)));
  i = hn::Mul(i, hn::Set(du, 0x74dcb303u));
  i = hn::Xor(i, hn::ShiftRight<2>(keep(i)));
  i = hn::Mul(i, hn::Set(du, 0x9e501cc3u));
  i = hn::Xor(i, hn::ShiftRight<2>(keep(i)));
  i = hn::Mul(i, hn::Set(du, 0xc860a3dfu));
  i = keep(i);
  return hn::Xor(i, hn::ShiftRight<5>(i));
}

// permuteIndex: rounds until every lane is below count (cycle walking; lanes already there keep
// their value), then (i + offset) mod count. Counts are far below 2^31, so signed compares serve.
VU Permute(VU i, VU seed, VU w, VU count, VU offset) {
  const DU du;
  const DI di;
  auto atOrAbove = [&](VU x) { return hn::RebindMask(du, hn::Not(hn::Lt(hn::BitCast(di, x), hn::BitCast(di, count)))); };
  i = PermuteRound(i, seed, w);
  for (auto pending = atOrAbove(i); !hn::AllFalse(du, pending); pending = atOrAbove(i))
    i = hn::IfThenElse(pending, PermuteRound(i, seed, w), i);
  const VU r = hn::Add(i, offset);
  return hn::IfThenElse(atOrAbove(r), hn::Sub(r, count), r);
}

// a * c modulo 2^64: AVX-512 multiplies 64-bit lanes (vpmullq); the other targets build it from 32-bit
// products, lo(a) lo(c) + (hi(a) lo(c) + lo(a) hi(c)) 2^32. The same bits either way.
VU64 Mul64(VU64 a, uint64_t c) {
  const DU64 d64;
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  return hn::Mul(a, hn::Set(d64, c));
#else
  const hn::Repartition<uint32_t, DU64> d32;
  const auto c_lo = hn::BitCast(d32, hn::Set(d64, c & 0xffffffffu)), c_hi = hn::BitCast(d32, hn::Set(d64, c >> 32));
  const auto a32 = hn::BitCast(d32, a);
  const VU64 low = hn::MulEven(a32, c_lo);
  const VU64 cross = hn::Add(hn::MulEven(hn::BitCast(d32, hn::ShiftRight<32>(a)), c_lo), hn::MulEven(a32, c_hi));
  return hn::Add(low, hn::ShiftLeft<32>(cross));
#endif
}

// mixBits (render/tracer/sampler.h).
VU64 MixBits(VU64 v) {
  v = hn::Xor(v, hn::ShiftRight<33>(v));
  v = Mul64(v, 0xff51afd7ed558ccdull);
  v = hn::Xor(v, hn::ShiftRight<33>(v));
  v = Mul64(v, 0xc4ceb9fe1a85ec53ull);
  return hn::Xor(v, hn::ShiftRight<33>(v));
}

// Stratified2D::operator[], lane by lane.
void StratifiedPointLanes(const Stratified2D::Layout& L, const StratifiedLanes& P, size_t first, size_t n, float* u_out,
                          float* v_out) {
  const DF df;
  const DU du;
  const DI di;
  const DU64 d64;
  const hn::Half<DU> dh;
  const size_t lanes = hn::Lanes(df), half = hn::Lanes(d64);
  const VU count = hn::Set(du, L.count), w = hn::Set(du, L.mask);
  const VF below_one = Splat(0x1.fffffep-1f);
  auto toFloat = [&](VU x) { return hn::ConvertTo(df, hn::BitCast(di, x)); };  // x < 2^24: exact
  for (size_t k = first; k < first + n; k += lanes) {
    // Below count, as every point a caller asks for is; the padding after the last point may hold
    // anything, and cycle walking ends only from an index below count.
    const VU index = hn::Min(hn::LoadU(du, P.index.data() + k), hn::Set(du, L.count > 0 ? L.count - 1 : 0u));
    VU cell = hn::Zero(du);
    if (L.count > 1)
      cell = Permute(index, hn::LoadU(du, P.seed.data() + k), w, count, hn::LoadU(du, P.offset.data() + k));
    // The jitter: split2D(hashSampleOf(pixel_hash, index)), in 64-bit lanes, half a vector at a time.
    auto jitterBits = [&](VU64 index64, size_t at) {
      return MixBits(hn::Xor(hn::LoadU(d64, P.pixel_hash.data() + at), Mul64(index64, 0xd1b54a32d192ed03ull)));
    };
    const VU64 h_lo = jitterBits(hn::PromoteTo(d64, hn::LowerHalf(dh, index)), k);
    const VU64 h_hi = jitterBits(hn::PromoteTo(d64, hn::UpperHalf(dh, index)), k + half);
    auto narrow = [&](VU64 lo, VU64 hi) { return hn::ConcatEven(du, hn::BitCast(du, hi), hn::BitCast(du, lo)); };
    const VU64 mask24 = hn::Set(d64, 0xffffffull);
    const VF jx = hn::Mul(toFloat(narrow(hn::ShiftRight<40>(h_lo), hn::ShiftRight<40>(h_hi))), Splat(0x1p-24f));
    const VF jy = hn::Mul(toFloat(narrow(hn::And(hn::ShiftRight<8>(h_lo), mask24), hn::And(hn::ShiftRight<8>(h_hi), mask24))),
                          Splat(0x1p-24f));
    VF u, v;
    if (L.side != 0) {
      VU row;
      if (L.side_shift >= 0) {
        row = hn::ShiftRightSame(cell, L.side_shift);
      } else {  // cell / side in floats: exact for counts below 2^24
        row = hn::BitCast(du, hn::ConvertTo(di, hn::Floor(hn::Div(toFloat(cell), Splat(float(L.side))))));
      }
      const VU col = hn::Sub(cell, hn::Mul(row, hn::Set(du, L.side)));
      u = hn::Mul(hn::Add(toFloat(col), jx), Splat(L.inv_side));
      v = hn::Mul(hn::Add(toFloat(row), jy), Splat(L.inv_side));
    } else {
      const VU row = Permute(cell, hn::LoadU(du, P.row_seed.data() + k), w, count, hn::LoadU(du, P.row_offset.data() + k));
      u = hn::Mul(hn::Add(toFloat(cell), jx), Splat(L.inv_count));
      v = hn::Mul(hn::Add(toFloat(row), jy), Splat(L.inv_count));
    }
    hn::StoreU(hn::Min(u, below_one), df, u_out + k);
    hn::StoreU(hn::Min(v, below_one), df, v_out + k);
  }
}

// fastMod(a, d, m) (render/tracer/sampler.h) for a, d below 2^32, in 64-bit lanes: the high 64 bits of
// (m a mod 2^64) d, from 32-bit products.
VU64 FastMod(VU64 a, uint32_t d, uint64_t m) {
  const DU64 d64;
  const hn::Repartition<uint32_t, DU64> d32;
  const VU64 low = Mul64(a, m);
  const auto dd = hn::BitCast(d32, hn::Set(d64, d));
  const VU64 lo = hn::MulEven(hn::BitCast(d32, low), dd);                        // lo32(low) d
  const VU64 hi = hn::MulEven(hn::BitCast(d32, hn::ShiftRight<32>(low)), dd);    // hi32(low) d
  return hn::ShiftRight<32>(hn::Add(hi, hn::ShiftRight<32>(lo)));
}

// Stratified2D(PixelSampler(x, y, frame), layout, dim).pixelPart(), lane by lane: hashPixel's first
// round (of the pixel alone) is shared by the jitter's hash and the permutation's seed.
void PixelPartLanes(const Stratified2D::Layout& L, uint32_t dim, uint32_t frame, const uint32_t* x, const uint32_t* y,
                    size_t n, StratifiedLanes& out) {
  const DU du;
  const DU64 d64;
  const hn::Half<DU> dh;
  const size_t lanes = hn::Lanes(du), half = hn::Lanes(d64);
  const bool permuted = L.count > 1;  // one point needs no permutation: seed and offsets 0
  const uint64_t jitter_key = uint64_t(frame) << 32 | (dim * 4 + 3), seed_key = uint64_t(frame) << 32 | dim;
  const uint64_t seed_sample = uint64_t(0xffffffffu) * 0xd1b54a32d192ed03ull;  // hashSampleOf's sample 0xffffffff
  auto narrow = [&](VU64 lo, VU64 hi) { return hn::ConcatEven(du, hn::BitCast(du, hi), hn::BitCast(du, lo)); };
  for (size_t k = 0; k < n; k += lanes) {
    const VU vx = hn::LoadU(du, x + k), vy = hn::LoadU(du, y + k);
    VU64 seeds[2], offsets[2], row_offsets[2];
    for (size_t h = 0; h < 2; ++h) {
      const VU64 px = hn::PromoteTo(d64, h == 0 ? hn::LowerHalf(dh, vx) : hn::UpperHalf(dh, vx));
      const VU64 py = hn::PromoteTo(d64, h == 0 ? hn::LowerHalf(dh, vy) : hn::UpperHalf(dh, vy));
      const VU64 pixel = MixBits(hn::Xor(hn::Or(hn::ShiftLeft<32>(px), py), hn::Set(d64, 0x9e3779b97f4a7c15ull)));
      hn::StoreU(MixBits(hn::Xor(pixel, hn::Set(d64, jitter_key))), d64, out.pixel_hash.data() + k + h * half);
      seeds[h] = offsets[h] = row_offsets[h] = hn::Zero(d64);
      if (!permuted) continue;
      const VU64 seed_hash = MixBits(hn::Xor(MixBits(hn::Xor(pixel, hn::Set(d64, seed_key))), hn::Set(d64, seed_sample)));
      seeds[h] = hn::And(seed_hash, hn::Set(d64, 0xffffffffull));
      offsets[h] = FastMod(seeds[h], L.count, L.mod_multiplier);
      row_offsets[h] = FastMod(hn::Xor(seeds[h], hn::Set(d64, 0x5bd1e995ull)), L.count, L.mod_multiplier);
    }
    const VU seed = narrow(seeds[0], seeds[1]);
    hn::StoreU(seed, du, out.seed.data() + k);
    hn::StoreU(hn::Xor(seed, hn::Set(du, 0x5bd1e995u)), du, out.row_seed.data() + k);
    hn::StoreU(narrow(offsets[0], offsets[1]), du, out.offset.data() + k);
    hn::StoreU(narrow(row_offsets[0], row_offsets[1]), du, out.row_offset.data() + k);
    hn::StoreU(hn::Zero(du), du, out.index.data() + k);
  }
}

// Which target this copy was compiled for.
int64_t CompiledTarget() { return HWY_TARGET; }

}  // namespace HWY_NAMESPACE
}  // namespace stirrup::render
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stirrup::render {

HWY_EXPORT(CameraRayLanes);
HWY_EXPORT(BoxTestLanes);
HWY_EXPORT(ListMayHit);
HWY_EXPORT(ListSurfaceSamples);
HWY_EXPORT(GroundLanes);
HWY_EXPORT(TerrainGroundLanes);
HWY_EXPORT(GroundHitLanes);
HWY_EXPORT(SkyLanes);
HWY_EXPORT(CheckerLanes);
HWY_EXPORT(CompiledTarget);
HWY_EXPORT(StratifiedPointLanes);
HWY_EXPORT(PixelPartLanes);

void StratifiedLanes::resize(std::size_t n) {
  pixel_hash.resize(n, 0);
  for (auto* v : {&index, &seed, &row_seed, &offset, &row_offset}) v->resize(n, 0u);
}

void stratifiedLanes(const Stratified2D::Layout& layout, const StratifiedLanes& points, std::size_t first,
                     std::size_t n, float* u, float* v) {
  HWY_DYNAMIC_DISPATCH(StratifiedPointLanes)(layout, points, first, n, u, v);
}

void pixelPartLanes(const Stratified2D::Layout& layout, SampleDimension dim, uint32_t frame, const uint32_t* x,
                    const uint32_t* y, std::size_t n, StratifiedLanes& parts) {
  if (n % CameraLanes::kPad != 0 || parts.pixel_hash.size() < n)
    throw std::invalid_argument("pixelPartLanes: expected a whole number of CameraLanes::kPad pixels, and room for them");
  HWY_DYNAMIC_DISPATCH(PixelPartLanes)(layout, uint32_t(dim), frame, x, y, n, parts);
}

void CameraLanes::resize(std::size_t n) {
  size = n;
  padded = paddedSize(n);
  for (auto* v : {&ux, &uy, &cx, &cy, &ox, &oy, &oz, &dx, &dy, &dz, &t_ground, &t_shade, &albedo_r, &albedo_g,
                  &albedo_b, &haze, &depth, &radiance_r, &radiance_g, &radiance_b, &sky_r, &sky_g, &sky_b, &gnx, &gny, &gnz,
                  &t_enter, &t_leave})
    v->resize(padded, 0.0f);
  may_hit.resize(padded, 0);
  hit_ray.resize(padded, -1);
  open.resize(padded, 0);
  hills_open.resize(padded, 0);
}

void cameraRayLanes(const LaneConstants& k, CameraLanes& lanes, bool flat_ground) {
  HWY_DYNAMIC_DISPATCH(CameraRayLanes)(k, lanes, flat_ground);
}
void boxTestLanes(const LaneConstants& k, CameraLanes& lanes) { HWY_DYNAMIC_DISPATCH(BoxTestLanes)(k, lanes); }
std::size_t listMayHit(const CameraLanes& lanes, int32_t* out) { return HWY_DYNAMIC_DISPATCH(ListMayHit)(lanes, out); }
std::size_t listSurfaceSamples(const CameraLanes& lanes, int32_t* out) {
  return HWY_DYNAMIC_DISPATCH(ListSurfaceSamples)(lanes, out);
}

void groundLanes(const LaneConstants& k, CameraLanes& lanes) { HWY_DYNAMIC_DISPATCH(GroundLanes)(k, lanes); }
void terrainGroundLanes(const LaneConstants& k, CameraLanes& lanes) {
  HWY_DYNAMIC_DISPATCH(TerrainGroundLanes)(k, lanes);
}
void groundHitLanes(const GroundHits& hits, CameraLanes& lanes) { HWY_DYNAMIC_DISPATCH(GroundHitLanes)(hits, lanes); }
void skyLanes(const LaneConstants& k, CameraLanes& lanes) { HWY_DYNAMIC_DISPATCH(SkyLanes)(k, lanes); }
void filteredCheckerLanes(const float* s, const float* t, const float* width, float* out, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(CheckerLanes)(s, t, width, out, n);
}

std::string simdTargetName() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(CompiledTarget)()); }

std::vector<std::string> simdTargets() {
  std::vector<std::string> names;
  for (int64_t target : hwy::SupportedAndGeneratedTargets()) names.emplace_back(hwy::TargetName(target));
  return names;
}

void pinSimdTarget(const std::string& name) {
  hwy::SetSupportedTargetsForTest(0);  // back to what the CPU has
  if (name.empty() || name == "best") return;
  std::string known;
  for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
    if (name == hwy::TargetName(target)) {
      hwy::SetSupportedTargetsForTest(target);
      return;
    }
    known += (known.empty() ? "" : ", ") + std::string(hwy::TargetName(target));
  }
  throw std::invalid_argument("SIMD target \"" + name + "\": expected one of " + known + " or best");
}

}  // namespace stirrup::render
#endif  // HWY_ONCE
