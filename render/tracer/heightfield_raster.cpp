// Highway compiles this file once per target (foreach_target.h re-includes it): the kernels that test
// a batch's samples against one cell run in SIMD lanes; HWY_ONCE marks the part compiled once.
#include "render/tracer/heightfield_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "render/tracer/heightfield_raster.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "render/tracer/lane_math-inl.h"

#ifndef STIRRUP_RENDER_HEIGHTFIELD_RASTER_CONSTANTS
#define STIRRUP_RENDER_HEIGHTFIELD_RASTER_CONSTANTS
namespace stirrup::render {
constexpr float kRasterInf = std::numeric_limits<float>::infinity();
// The nearest a visible point can be to a perspective camera's plane (cm): a ray meets nothing
// nearer (a ground this near the lens is not a view). Where a cell or block crosses this plane, its
// box on the image plane is that of its part beyond it.
constexpr float kRasterNearPlaneCm = 0.01f;
// How far an edge function's rounding can move it, relative to the size of its terms: its normal is a
// cross product of two vertices relative to the eye (a few ulps of their product), then a dot product.
constexpr float kEdgeSlack = 1e-5f;
}  // namespace stirrup::render
#endif

HWY_BEFORE_NAMESPACE();
namespace stirrup::render {
namespace HWY_NAMESPACE {

// Each sample's point on the image plane and what its edge functions read: its direction (a
// perspective camera) or its point (an orthographic one). Padding never meets a cell (NaN).
void RasterSampleLanes(const RasterCamera& c, const CameraLanes& L, std::size_t n, HeightfieldRaster::Scratch& s) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  const VF nan = Splat(std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < L.padded; i += lanes) {
    const MF live = hn::RebindMask(df, hn::Lt(hn::Iota(di, int32_t(i)), hn::Set(di, int32_t(n))));
    VF sx, sy, qx, qy, qz;
    if (c.perspective) {
      qx = Load(L.dx, i), qy = Load(L.dy, i), qz = Load(L.dz, i);
      const VF w = hn::Add(hn::Add(hn::Mul(qx, Splat(c.forward.x)), hn::Mul(qy, Splat(c.forward.y))), hn::Mul(qz, Splat(c.forward.z)));
      sx = hn::Div(hn::Add(hn::Add(hn::Mul(qx, Splat(c.right.x)), hn::Mul(qy, Splat(c.right.y))), hn::Mul(qz, Splat(c.right.z))), w);
      sy = hn::Div(hn::Add(hn::Add(hn::Mul(qx, Splat(c.up.x)), hn::Mul(qy, Splat(c.up.y))), hn::Mul(qz, Splat(c.up.z))), w);
      Store(Splat(0.0f), s.ox, i), Store(Splat(0.0f), s.oy, i), Store(Splat(0.0f), s.oz, i);
    } else {
      const VF ox = hn::Sub(Load(L.ox, i), Splat(c.eye.x)), oy = hn::Sub(Load(L.oy, i), Splat(c.eye.y));
      const VF oz = hn::Sub(Load(L.oz, i), Splat(c.eye.z));
      sx = hn::Add(hn::Add(hn::Mul(ox, Splat(c.right.x)), hn::Mul(oy, Splat(c.right.y))), hn::Mul(oz, Splat(c.right.z)));
      sy = hn::Add(hn::Add(hn::Mul(ox, Splat(c.up.x)), hn::Mul(oy, Splat(c.up.y))), hn::Mul(oz, Splat(c.up.z)));
      qx = sx, qy = sy, qz = Splat(1.0f);
      Store(ox, s.ox, i), Store(oy, s.oy, i), Store(oz, s.oz, i);
    }
    Store(hn::IfThenElse(live, sx, nan), s.sx, i), Store(hn::IfThenElse(live, sy, nan), s.sy, i);
    Store(qx, s.qx, i), Store(qy, s.qy, i), Store(qz, s.qz, i);
    Store(Load(L.t_leave, i), s.best, i);
    hn::StoreU(hn::Set(di, -1), di, s.cell.data() + i);
    hn::StoreU(hn::Zero(di), di, s.second.data() + i);
  }
}

// One cell against every sample of the batch: inside its box on the image plane, nearer than the
// sample's hit so far, inside one of its triangles by the edge functions, and met within [t_enter,
// the hit so far] (the first hit at t_leave itself, later ones only nearer).
void RasterCellLanes(const RasterCell& c, const CameraLanes& L, size_t begin, size_t end, HeightfieldRaster::Scratch& s) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  const VF zero = Splat(0.0f);
  auto dot = [](const float (&n)[3], VF x, VF y, VF z) {
    return hn::Add(hn::Add(hn::Mul(Splat(n[0]), x), hn::Mul(Splat(n[1]), y)), hn::Mul(Splat(n[2]), z));
  };
  for (size_t i = begin; i < end; i += lanes) {
    const VF sx = Load(s.sx, i), sy = Load(s.sy, i);
    VF best = Load(s.best, i);
    const MF in_box = hn::And(hn::And(hn::Ge(sx, Splat(c.x0)), hn::Le(sx, Splat(c.x1))),
                              hn::And(hn::And(hn::Ge(sy, Splat(c.y0)), hn::Le(sy, Splat(c.y1))), hn::Le(Splat(c.near), best)));
    if (hn::AllFalse(df, in_box)) continue;
    const VF qx = Load(s.qx, i), qy = Load(s.qy, i), qz = Load(s.qz, i);
    // Each edge's function, and the most its rounding can move it (kEdgeSlack of its terms' size): a
    // sample within that of an edge counts as on both sides, so where rounding would put a ray near a
    // vertex outside every triangle around it, it is inside some (two triangles may both take a ray:
    // the nearer hit wins).
    auto edge = [&](const float (&n)[3], VF& e, VF& slack) {
      const VF tx = hn::Mul(Splat(n[0]), qx), ty = hn::Mul(Splat(n[1]), qy), tz = hn::Mul(Splat(n[2]), qz);
      e = hn::Add(hn::Add(tx, ty), tz);
      slack = hn::Mul(Splat(kEdgeSlack), hn::Add(hn::Add(hn::Abs(tx), hn::Abs(ty)), hn::Abs(tz)));
    };
    VF e_ab, e_ac, e_bd, e_cd, e_ad, s_ab, s_ac, s_bd, s_cd, s_ad;
    edge(c.n_ab, e_ab, s_ab), edge(c.n_ac, e_ac, s_ac), edge(c.n_bd, e_bd, s_bd), edge(c.n_cd, e_cd, s_cd);
    edge(c.n_ad, e_ad, s_ad);
    const auto ge = [](VF e, VF slack) { return hn::Ge(e, hn::Neg(slack)); };  // e >= 0, within its rounding
    const auto le = [](VF e, VF slack) { return hn::Le(e, slack); };
    const MF in1 = hn::Or(hn::And(hn::And(ge(e_ac, s_ac), ge(e_cd, s_cd)), le(e_ad, s_ad)),
                          hn::And(hn::And(le(e_ac, s_ac), le(e_cd, s_cd)), ge(e_ad, s_ad)));
    const MF in2 = hn::Or(hn::And(hn::And(ge(e_ad, s_ad), le(e_bd, s_bd)), le(e_ab, s_ab)),
                          hn::And(hn::And(le(e_ad, s_ad), ge(e_bd, s_bd)), ge(e_ab, s_ab)));
    const MF any = hn::And(in_box, hn::Or(in1, in2));
    if (hn::AllFalse(df, any)) continue;
    const VF dx = Load(L.dx, i), dy = Load(L.dy, i), dz = Load(L.dz, i);
    const VF ox = Load(s.ox, i), oy = Load(s.oy, i), oz = Load(s.oz, i);
    const VF t_enter = Load(L.t_enter, i);
    auto cell = hn::LoadU(di, s.cell.data() + i), second = hn::LoadU(di, s.second.data() + i);
    auto consider = [&](MF inside, const float (&n)[3], float h, int32_t which) {
      const VF t = hn::Div(hn::Sub(Splat(h), dot(n, ox, oy, oz)), dot(n, dx, dy, dz));
      const MF first = hn::RebindMask(df, hn::Lt(cell, hn::Zero(di)));
      const MF nearer = hn::Or(hn::Lt(t, best), hn::And(first, hn::Eq(t, best)));
      const MF take = hn::And(hn::And(inside, hn::Ge(t, t_enter)), nearer);
      best = hn::IfThenElse(take, t, best);
      const auto take_i = hn::RebindMask(di, take);
      cell = hn::IfThenElse(take_i, hn::Set(di, c.index), cell);
      second = hn::IfThenElse(take_i, hn::Set(di, which), second);
    };
    consider(hn::And(in_box, in1), c.n1, c.h1, 0);
    consider(hn::And(in_box, in2), c.n2, c.h2, 1);
    Store(best, s.best, i);
    hn::StoreU(cell, di, s.cell.data() + i), hn::StoreU(second, di, s.second.data() + i);
  }
}


// The cells of one row of a block on the image plane, 16 at a time: their boxes (widened), those that
// meet the screen, and the nearest any ray meets them. A cell with a corner nearer a perspective
// camera's plane than kNearPlaneCm is listed apart (its box needs the near plane's clipping).
void RasterRowLanes(const RasterCamera& c, const RasterRow& row, RasterRowOut& out) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  out.shown = 0, out.crossing = 0;
  for (int32_t first = 0; first < row.cells; first += int32_t(lanes)) {
    const MF live = hn::FirstN(df, size_t(row.cells - first));
    const size_t a = row.first_vertex + size_t(first);
    struct Q {
      VF x, y, z;
    };
    auto corner = [&](size_t at) {
      return Q{hn::Sub(hn::LoadU(df, row.x + at), Splat(c.eye.x)), hn::Sub(hn::LoadU(df, row.y + at), Splat(c.eye.y)),
               hn::Sub(hn::LoadU(df, row.z + at), Splat(c.eye.z))};
    };
    const Q q[4] = {corner(a), corner(a + 1), corner(a + row.row_vertices), corner(a + row.row_vertices + 1)};
    auto dot = [](const Q& p, const glm::vec3& v) {
      return hn::Add(hn::Add(hn::Mul(p.x, Splat(v.x)), hn::Mul(p.y, Splat(v.y))), hn::Mul(p.z, Splat(v.z)));
    };
    VF x0 = Splat(kRasterInf), y0 = Splat(kRasterInf), x1 = Splat(-kRasterInf), y1 = Splat(-kRasterInf);
    VF w_min = Splat(kRasterInf);
    for (const Q& p : q) {
      const VF w = dot(p, c.forward);
      w_min = hn::Min(w_min, w);
      VF x = dot(p, c.right), y = dot(p, c.up);
      if (c.perspective) x = hn::Div(x, w), y = hn::Div(y, w);
      x0 = hn::Min(x0, x), x1 = hn::Max(x1, x), y0 = hn::Min(y0, y), y1 = hn::Max(y1, y);
    }
    // Widened by far more than a projection's rounding (Box::widen).
    const VF sx = hn::Add(hn::Mul(Splat(1e-5f), hn::Add(hn::Abs(x0), hn::Abs(x1))), Splat(1e-7f));
    const VF sy = hn::Add(hn::Mul(Splat(1e-5f), hn::Add(hn::Abs(y0), hn::Abs(y1))), Splat(1e-7f));
    x0 = hn::Sub(x0, sx), x1 = hn::Add(x1, sx), y0 = hn::Sub(y0, sy), y1 = hn::Add(y1, sy);
    const MF meets = hn::And(hn::And(hn::Le(x0, Splat(row.screen_x1)), hn::Le(Splat(row.screen_x0), x1)),
                             hn::And(hn::Le(y0, Splat(row.screen_y1)), hn::Le(Splat(row.screen_y0), y1)));
    VF near;
    MF crossing = hn::FirstN(df, 0);  // none
    if (c.perspective) {
      crossing = hn::And(live, hn::Lt(w_min, Splat(kRasterNearPlaneCm)));
      // The nearest point of the cell's box to the eye.
      auto clamp0 = [&](VF a0, VF a1, VF a2, VF a3) {
        const VF lo = hn::Min(hn::Min(a0, a1), hn::Min(a2, a3)), hi = hn::Max(hn::Max(a0, a1), hn::Max(a2, a3));
        return hn::Min(hn::Max(Splat(0.0f), lo), hi);
      };
      const VF cx = clamp0(q[0].x, q[1].x, q[2].x, q[3].x), cy = clamp0(q[0].y, q[1].y, q[2].y, q[3].y);
      const VF cz = clamp0(q[0].z, q[1].z, q[2].z, q[3].z);
      near = hn::Sqrt(hn::Add(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)), hn::Mul(cz, cz)));
    } else {
      near = w_min;
    }
    near = hn::Mul(near, Splat(1.0f - 1e-5f));
    const MF shown = hn::AndNot(crossing, hn::And(live, meets));
    const auto index = hn::Iota(di, row.first_cell + first);
    const auto shown_i = hn::RebindMask(di, shown);
    const size_t k = size_t(out.shown);
    hn::CompressStore(index, shown_i, di, out.index + k);
    hn::CompressStore(x0, shown, df, out.x0 + k), hn::CompressStore(y0, shown, df, out.y0 + k);
    hn::CompressStore(x1, shown, df, out.x1 + k), hn::CompressStore(y1, shown, df, out.y1 + k);
    hn::CompressStore(near, shown, df, out.near + k);
    out.shown += int32_t(hn::CountTrue(df, shown));
    out.crossing += int32_t(hn::CompressStore(index, hn::RebindMask(di, crossing), di, out.crossing_index + out.crossing));
  }
}


// The edge functions and triangle planes of up to 16 cells at once (the scalar expressions of
// glm::cross and glm::dot, operation for operation): each edge's from its lower vertex first, so a
// cell and its neighbour compute the edge they share bit for bit alike.
void RasterSetupLanes(const RasterCamera& c, const float* vx, const float* vy, const float* vz, std::size_t nx,
                      RasterCellSetup& out) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  for (int32_t first = 0; first < out.count; first += int32_t(lanes)) {
    const auto a = hn::LoadU(di, out.vertex + first);
    struct V {
      VF x, y, z;
    };
    auto corner = [&](int32_t offset) {
      const auto at = hn::Add(a, hn::Set(di, offset));
      return V{hn::Sub(hn::GatherIndex(df, vx, at), Splat(c.eye.x)), hn::Sub(hn::GatherIndex(df, vy, at), Splat(c.eye.y)),
               hn::Sub(hn::GatherIndex(df, vz, at), Splat(c.eye.z))};
    };
    const V pa = corner(0), pb = corner(1), pc = corner(int32_t(nx)), pd = corner(int32_t(nx) + 1);
    auto cross = [](const V& x, const V& y) {
      return V{hn::Sub(hn::Mul(x.y, y.z), hn::Mul(y.y, x.z)), hn::Sub(hn::Mul(x.z, y.x), hn::Mul(y.z, x.x)),
               hn::Sub(hn::Mul(x.x, y.y), hn::Mul(y.x, x.y))};
    };
    auto sub = [](const V& x, const V& y) { return V{hn::Sub(x.x, y.x), hn::Sub(x.y, y.y), hn::Sub(x.z, y.z)}; };
    auto dot = [](const V& x, const V& y) {
      return hn::Add(hn::Add(hn::Mul(x.x, y.x), hn::Mul(x.y, y.y)), hn::Mul(x.z, y.z));
    };
    V e[5];
    if (c.perspective) {
      // p x q as p x (q - p): the same plane, without the cancellation of two long, nearly parallel
      // vectors' products.
      e[0] = cross(pa, sub(pb, pa)), e[1] = cross(pa, sub(pc, pa)), e[2] = cross(pb, sub(pd, pb));
      e[3] = cross(pc, sub(pd, pc)), e[4] = cross(pa, sub(pd, pa));
    } else {
      // On the image plane: E = (q - p) x (s - p) for the edge p -> q and the sample's point s.
      const V right{Splat(c.right.x), Splat(c.right.y), Splat(c.right.z)}, up{Splat(c.up.x), Splat(c.up.y), Splat(c.up.z)};
      auto edge = [&](const V& p3, const V& q3) {
        const VF px = dot(p3, right), py = dot(p3, up), qx = dot(q3, right), qy = dot(q3, up);
        return V{hn::Sub(py, qy), hn::Sub(qx, px), hn::Sub(hn::Mul(px, qy), hn::Mul(py, qx))};
      };
      e[0] = edge(pa, pb), e[1] = edge(pa, pc), e[2] = edge(pb, pd), e[3] = edge(pc, pd), e[4] = edge(pa, pd);
    }
    const V n1 = cross(sub(pc, pa), sub(pd, pa)), n2 = cross(sub(pd, pa), sub(pb, pa));
    const V all[7] = {e[0], e[1], e[2], e[3], e[4], n1, n2};
    for (int k = 0; k < 7; ++k) {
      hn::StoreU(all[k].x, df, out.n[3 * k] + first), hn::StoreU(all[k].y, df, out.n[3 * k + 1] + first);
      hn::StoreU(all[k].z, df, out.n[3 * k + 2] + first);
    }
    hn::StoreU(dot(n1, pa), df, out.h1 + first), hn::StoreU(dot(n2, pa), df, out.h2 + first);
  }
}


// The hits as Embree's quad hits (HeightfieldRaster::trace): the cell's column and row from its index
// (the float quotient is exact to within one, cells < 2^24, and the remainder says which way to
// correct it, as GroundHitLanes does), the hit's place across and along the cell, its distance.
void RasterHitLanes(const float* xs, const float* zs, int32_t cells_a_row, const HeightfieldRaster::Scratch& s,
                    CameraLanes& L, unsigned* geom, unsigned* prim, float* u, float* v) {
  const DF df;
  const DI di;
  const size_t lanes = hn::Lanes(df);
  const auto row = hn::Set(di, cells_a_row);
  const VF per_row = Splat(1.0f / float(cells_a_row));
  const auto one_i = hn::Set(di, 1);
  for (size_t i = 0; i < L.padded; i += lanes) {
    const auto cell = hn::LoadU(di, s.cell.data() + i);
    const auto hit_i = hn::Gt(cell, hn::Set(di, -1));
    const MF hit = hn::RebindMask(df, hit_i);
    if (hn::AllFalse(df, hit)) continue;
    const auto c = hn::IfThenElseZero(hit_i, cell);
    auto j = hn::ConvertTo(di, hn::Floor(hn::Mul(hn::ConvertTo(df, c), per_row)));
    const auto rest = hn::Sub(c, hn::Mul(j, row));
    j = hn::IfThenElse(hn::Lt(rest, hn::Zero(di)), hn::Sub(j, one_i), j);
    j = hn::IfThenElse(hn::Lt(hn::Sub(c, hn::Mul(j, row)), row), j, hn::Add(j, one_i));
    const auto col = hn::Sub(c, hn::Mul(j, row));
    const VF x0 = hn::GatherIndex(df, xs, col), x1 = hn::GatherIndex(df, xs, hn::Add(col, one_i));
    const VF z0 = hn::GatherIndex(df, zs, j), z1 = hn::GatherIndex(df, zs, hn::Add(j, one_i));
    const VF t = Load(s.best, i);
    const VF hx = hn::Add(Load(L.ox, i), hn::Mul(t, Load(L.dx, i))), hz = hn::Add(Load(L.oz, i), hn::Mul(t, Load(L.dz, i)));
    const VF zero = Splat(0.0f), one = Splat(1.0f);
    const VF across = hn::Min(hn::Max(hn::Div(hn::Sub(hx, x0), hn::Sub(x1, x0)), zero), one);
    const VF along = hn::Min(hn::Max(hn::Div(hn::Sub(hz, z0), hn::Sub(z1, z0)), zero), one);
    hn::BlendedStore(hn::Zero(di), hit_i, di, reinterpret_cast<int32_t*>(geom) + i);
    hn::BlendedStore(c, hit_i, di, reinterpret_cast<int32_t*>(prim) + i);
    hn::BlendedStore(across, hit, df, u + i), hn::BlendedStore(hn::Sub(one, along), hit, df, v + i);
    hn::BlendedStore(t, hit, df, L.t_leave.data() + i);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace stirrup::render
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stirrup::render {

HWY_EXPORT(RasterSampleLanes);
HWY_EXPORT(RasterCellLanes);
HWY_EXPORT(RasterRowLanes);
HWY_EXPORT(RasterSetupLanes);
HWY_EXPORT(RasterHitLanes);

namespace {

constexpr float kInf = kRasterInf;
constexpr unsigned kNoHit = 0xFFFFFFFFu;  // RTC_INVALID_GEOMETRY_ID
constexpr float kNearPlaneCm = kRasterNearPlaneCm;

// A box on the image plane, widened by far more than a projection's rounding (a relative 1e-5).
struct Box {
  float x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  void add(float x, float y) { x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y); }
  void widen() {
    const float sx = 1e-5f * (std::abs(x0) + std::abs(x1)) + 1e-7f, sy = 1e-5f * (std::abs(y0) + std::abs(y1)) + 1e-7f;
    x0 -= sx, x1 += sx, y0 -= sy, y1 += sy;
  }
  bool meets(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

// The box on the image plane of the convex hull of points relative to the eye (with the edges that
// join them: where an edge crosses the near plane, its point there), beyond a perspective camera's
// near plane. Empty when no part is beyond it.
template <std::size_t N, std::size_t E>
Box imageBox(const HeightfieldRaster::Frame& f, const glm::vec3 (&q)[N], const int (&edges)[E][2]) {
  Box box;
  if (!f.perspective) {
    for (const glm::vec3& p : q) box.add(glm::dot(p, f.right), glm::dot(p, f.up));
    return box;
  }
  float w[N];
  for (std::size_t i = 0; i < N; ++i) {
    w[i] = glm::dot(q[i], f.forward);
    if (w[i] >= kNearPlaneCm) box.add(glm::dot(q[i], f.right) / w[i], glm::dot(q[i], f.up) / w[i]);
  }
  for (const auto& e : edges) {
    const float wa = w[e[0]], wb = w[e[1]];
    if ((wa < kNearPlaneCm) == (wb < kNearPlaneCm)) continue;
    const glm::vec3 p = q[e[0]] + (q[e[1]] - q[e[0]]) * ((kNearPlaneCm - wa) / (wb - wa));
    box.add(glm::dot(p, f.right) / kNearPlaneCm, glm::dot(p, f.up) / kNearPlaneCm);
  }
  return box;
}

// The twelve edges of a box's corners (corner c: x from bit 0, y bit 1, z bit 2), and a cell's four
// sides and diagonal (corners a b c d).
constexpr int kBoxEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
constexpr int kCellEdges[5][2] = {{0, 1}, {0, 2}, {1, 3}, {2, 3}, {0, 3}};

}  // namespace

HeightfieldRaster::HeightfieldRaster(const TerrainMesh& mesh) {
  if (mesh.xs.size() < 2 || mesh.zs.size() < 2 || mesh.positions.size() != mesh.xs.size() * mesh.zs.size())
    throw std::invalid_argument("HeightfieldRaster: expected a grid of at least 2 x 2 vertices, row by row");
  if ((mesh.xs.size() - 1) * (mesh.zs.size() - 1) >= (std::size_t(1) << 31))
    throw std::invalid_argument("HeightfieldRaster: expected fewer than 2^31 cells");
  nx_ = int32_t(mesh.xs.size()), nz_ = int32_t(mesh.zs.size());
  xs_.assign(mesh.xs.begin(), mesh.xs.end());
  zs_.assign(mesh.zs.begin(), mesh.zs.end());
  positions_ = mesh.positions;
  // Padded: RasterRowLanes reads whole vectors from a row's last cell on.
  for (auto* a : {&vx_, &vy_, &vz_}) a->reserve(positions_.size() + 64);
  for (const glm::vec3& p : positions_) vx_.push_back(p.x), vy_.push_back(p.y), vz_.push_back(p.z);
  for (auto* a : {&vx_, &vy_, &vz_}) a->resize(positions_.size() + 64, 0.0f);
  bx_ = (nx_ - 1 + kBlockCells - 1) / kBlockCells, bz_ = (nz_ - 1 + kBlockCells - 1) / kBlockCells;
  block_low_.assign(std::size_t(bx_) * std::size_t(bz_), kInf);
  block_high_.assign(std::size_t(bx_) * std::size_t(bz_), -kInf);
  for (int32_t j = 0; j < nz_; ++j) {
    // A vertex on a block's edge belongs to the blocks on both sides.
    const int32_t bj_lo = std::max(0, (j - 1) / kBlockCells), bj_hi = std::min(bz_ - 1, j / kBlockCells);
    for (int32_t i = 0; i < nx_; ++i) {
      const int32_t bi_lo = std::max(0, (i - 1) / kBlockCells), bi_hi = std::min(bx_ - 1, i / kBlockCells);
      const float h = positions_[std::size_t(j) * std::size_t(nx_) + std::size_t(i)].y;
      for (int32_t bj = bj_lo; bj <= bj_hi; ++bj) {
        for (int32_t bi = bi_lo; bi <= bi_hi; ++bi) {
          const std::size_t b = std::size_t(bj) * std::size_t(bx_) + std::size_t(bi);
          block_low_[b] = std::min(block_low_[b], h), block_high_[b] = std::max(block_high_[b], h);
        }
      }
    }
  }
}

HeightfieldRaster::Frame HeightfieldRaster::prepare(const LaneConstants& k, int width, int height,
                                                    double max_cells_a_pixel) const {
  Frame f;
  f.max_cells_a_pixel = max_cells_a_pixel;
  f.perspective = k.perspective;
  f.eye = k.position, f.forward = k.forward, f.right = k.right, f.up = k.up;
  f.pixel_dx = k.pixel_dx, f.pixel_dy = k.pixel_dy, f.half_width = k.half_width, f.half_height = k.half_height;
  // The screen on the image plane, with two pixels for the reach of the pixel filter's samples.
  Box screen;
  screen.add(-k.half_width - 2.0f * k.pixel_dx, k.half_height + 2.0f * k.pixel_dy);
  screen.add(float(width) * k.pixel_dx - k.half_width + 2.0f * k.pixel_dx,
             k.half_height - float(height) * k.pixel_dy - 2.0f * k.pixel_dy);
  // The bins a box on the image plane meets (a sample can lie 1.5 pixels beyond its pixel's corner).
  f.bins_x = (width + kBinPixels - 1) / kBinPixels, f.bins_y = (height + kBinPixels - 1) / kBinPixels;
  f.bin_embree.assign(std::size_t(f.bins_x) * std::size_t(f.bins_y), 0);
  const auto binRange = [&](float x0, float y0, float x1, float y1, int& bx0, int& bx1, int& by0, int& by1) {
    const float px0 = (x0 + f.half_width) / f.pixel_dx - 1.5f, px1 = (x1 + f.half_width) / f.pixel_dx + 1.5f;
    const float py0 = (f.half_height - y1) / f.pixel_dy - 1.5f, py1 = (f.half_height - y0) / f.pixel_dy + 1.5f;
    bx0 = int(std::clamp(std::floor(px0 / float(kBinPixels)), 0.0f, float(f.bins_x - 1)));
    bx1 = int(std::clamp(std::floor(px1 / float(kBinPixels)), 0.0f, float(f.bins_x - 1)));
    by0 = int(std::clamp(std::floor(py0 / float(kBinPixels)), 0.0f, float(f.bins_y - 1)));
    by1 = int(std::clamp(std::floor(py1 / float(kBinPixels)), 0.0f, float(f.bins_y - 1)));
  };
  // The blocks on screen and within sight, nearest first.
  struct Seen {
    float near;
    int32_t index;
  };
  std::vector<Seen> seen;
  for (int32_t bj = 0; bj < bz_; ++bj) {
    const float z0 = zs_[std::size_t(bj * kBlockCells)], z1 = zs_[std::size_t(std::min(nz_ - 1, (bj + 1) * kBlockCells))];
    for (int32_t bi = 0; bi < bx_; ++bi) {
      const int32_t index = bj * bx_ + bi;
      const float x0 = xs_[std::size_t(bi * kBlockCells)], x1 = xs_[std::size_t(std::min(nx_ - 1, (bi + 1) * kBlockCells))];
      const float y0 = block_low_[std::size_t(index)], y1 = block_high_[std::size_t(index)];
      // Beyond sight: the box's nearest point farther than any ray goes.
      const glm::vec3 nearest(std::clamp(f.eye.x, x0, x1), std::clamp(f.eye.y, y0, y1), std::clamp(f.eye.z, z0, z1));
      const float near = k.perspective ? glm::length(nearest - f.eye) : 0.0f;
      if (near > k.t_visible) continue;
      glm::vec3 corners[8];
      for (int c = 0; c < 8; ++c) corners[c] = glm::vec3(c & 1 ? x1 : x0, c & 2 ? y1 : y0, c & 4 ? z1 : z0) - f.eye;
      Box box = imageBox(f, corners, kBoxEdges);
      if (box.x0 > box.x1) continue;  // wholly behind the camera
      box.widen();
      if (!box.meets(screen)) continue;
      float ortho_near = kInf;
      for (const glm::vec3& c : corners) ortho_near = std::min(ortho_near, glm::dot(c, f.forward));
      // A block whose cells are many to a pixel on screen (a distant grid) is left to Embree, and so
      // are the bins its box meets: each of its cells would cost a setup for a sample or two.
      const float pixels = (std::min(box.x1, screen.x1) - std::max(box.x0, screen.x0)) / f.pixel_dx *
                           ((std::min(box.y1, screen.y1) - std::max(box.y0, screen.y0)) / f.pixel_dy);
      const float cells = float((std::min(nx_ - 1, (bi + 1) * kBlockCells) - bi * kBlockCells) *
                                (std::min(nz_ - 1, (bj + 1) * kBlockCells) - bj * kBlockCells));
      if (cells > float(f.max_cells_a_pixel) * pixels) {
        int bx0, bx1, by0, by1;
        binRange(box.x0, box.y0, box.x1, box.y1, bx0, bx1, by0, by1);
        for (int by = by0; by <= by1; ++by)
          for (int bx = bx0; bx <= bx1; ++bx) f.bin_embree[std::size_t(by * f.bins_x + bx)] = 1;
        continue;
      }
      seen.push_back({k.perspective ? near : ortho_near, index});
    }
  }
  // Visited in one order by every batch: a batch stops at the first block beyond all its samples'
  // hits, and a sample tests only the cells nearer than its hit so far.
  std::sort(seen.begin(), seen.end(), [](const Seen& a, const Seen& b) {
    return a.near < b.near || (a.near == b.near && a.index < b.index);
  });
  const std::size_t nx = std::size_t(nx_);
  const RasterCamera camera{f.perspective, f.eye, f.forward, f.right, f.up};
  RasterRow row;
  row.x = vx_.data(), row.y = vy_.data(), row.z = vz_.data(), row.row_vertices = nx;
  row.screen_x0 = screen.x0, row.screen_y0 = screen.y0, row.screen_x1 = screen.x1, row.screen_y1 = screen.y1;
  RasterRowOut out;
  for (const Seen& block : seen) {
    const int32_t bi = block.index % bx_, bj = block.index / bx_;
    const int32_t i_end = std::min(nx_ - 1, (bi + 1) * kBlockCells), j_end = std::min(nz_ - 1, (bj + 1) * kBlockCells);
    const float block_near = block.near * (1.0f - 1e-5f);
    for (int32_t j = bj * kBlockCells; j < j_end; ++j) {
      row.first_vertex = std::size_t(j) * nx + std::size_t(bi * kBlockCells);
      row.first_cell = j * (nx_ - 1) + bi * kBlockCells, row.cells = i_end - bi * kBlockCells;
      HWY_DYNAMIC_DISPATCH(RasterRowLanes)(camera, row, out);
      for (int32_t m = 0; m < out.shown; ++m)
        f.cells.push_back({out.index[m], out.x0[m], out.y0[m], out.x1[m], out.y1[m], out.near[m], block_near});
      for (int32_t m = 0; m < out.crossing; ++m) {
        // Across the near plane: the box of the part beyond it.
        const int32_t index = out.crossing_index[m];
        const std::size_t a = std::size_t(index / (nx_ - 1)) * nx + std::size_t(index % (nx_ - 1));
        const glm::vec3 q[4] = {positions_[a] - f.eye, positions_[a + 1] - f.eye, positions_[a + nx] - f.eye,
                                positions_[a + nx + 1] - f.eye};
        Box cell = imageBox(f, q, kCellEdges);
        if (cell.x0 > cell.x1) continue;
        cell.widen();
        if (!cell.meets(screen)) continue;
        const glm::vec3 lo = glm::min(glm::min(q[0], q[1]), glm::min(q[2], q[3]));
        const glm::vec3 hi = glm::max(glm::max(q[0], q[1]), glm::max(q[2], q[3]));
        const float near = glm::length(glm::clamp(glm::vec3(0.0f), lo, hi));
        f.cells.push_back({index, cell.x0, cell.y0, cell.x1, cell.y1, near * (1.0f - 1e-5f), block_near});
      }
    }
  }
  f.bin_start.assign(std::size_t(f.bins_x) * std::size_t(f.bins_y) + 1, 0u);
  for (const Frame::Cell& c : f.cells) {
    int bx0, bx1, by0, by1;
    binRange(c.x0, c.y0, c.x1, c.y1, bx0, bx1, by0, by1);
    for (int by = by0; by <= by1; ++by)
      for (int bx = bx0; bx <= bx1; ++bx) ++f.bin_start[std::size_t(by * f.bins_x + bx) + 1];
  }
  for (std::size_t b = 1; b < f.bin_start.size(); ++b) f.bin_start[b] += f.bin_start[b - 1];
  f.bin_cells.resize(f.bin_start.back());
  std::vector<uint32_t> fill(f.bin_start.begin(), f.bin_start.end() - 1);
  for (std::size_t c = 0; c < f.cells.size(); ++c) {
    int bx0, bx1, by0, by1;
    binRange(f.cells[c].x0, f.cells[c].y0, f.cells[c].x1, f.cells[c].y1, bx0, bx1, by0, by1);
    for (int by = by0; by <= by1; ++by)
      for (int bx = bx0; bx <= bx1; ++bx) f.bin_cells[fill[std::size_t(by * f.bins_x + bx)]++] = uint32_t(c);
  }
  return f;
}

bool HeightfieldRaster::trace(const Frame& f, int x0, int tile_width, int y0, int first, int count, int spp,
                              CameraLanes& L, Scratch& s, unsigned* geom, unsigned* prim, float* u, float* v) const {
  const std::size_t n = std::size_t(count) * std::size_t(spp);
  // Where the cells are small on screen, many to a sample, Embree's tree of them does better.
  const int row_first = first / tile_width, row_last = (first + count - 1) / tile_width;
  const int bin_x0 = std::max(0, x0 / kBinPixels), bin_x1 = std::min(f.bins_x - 1, (x0 + tile_width - 1) / kBinPixels);
  const int bin_y0 = std::max(0, (y0 + row_first) / kBinPixels), bin_y1 = std::min(f.bins_y - 1, (y0 + row_last) / kBinPixels);
  for (int by = bin_y0; by <= bin_y1; ++by)
    for (int bx = bin_x0; bx <= bin_x1; ++bx)
      if (f.bin_embree[std::size_t(by * f.bins_x + bx)]) return false;
  std::fill_n(geom, L.padded, kNoHit);
  for (auto* a : {&s.sx, &s.sy, &s.qx, &s.qy, &s.qz, &s.ox, &s.oy, &s.oz, &s.best}) a->resize(L.padded);
  s.cell.resize(L.padded), s.second.resize(L.padded);
  const RasterCamera camera{f.perspective, f.eye, f.forward, f.right, f.up};
  HWY_DYNAMIC_DISPATCH(RasterSampleLanes)(camera, L, n, s);
  // The batch's box on the image plane (of the samples that can meet the mesh), and how far they look.
  Box batch;
  float reach = 0.0f;
  for (std::size_t k = 0; k < n; ++k) {
    if (!(L.t_enter[k] <= L.t_leave[k])) continue;
    batch.add(s.sx[k], s.sy[k]);
    reach = std::max(reach, L.t_leave[k]);
  }
  if (batch.x0 > batch.x1) return true;
  // The cells of the bins the batch's pixels meet, each once, in the frame's order (each bin's list
  // ascends; merged, without repeats).
  s.candidates.clear();
  for (int by = bin_y0; by <= bin_y1; ++by) {
    for (int bx = bin_x0; bx <= bin_x1; ++bx) {
      const std::size_t b = std::size_t(by * f.bins_x + bx);
      const auto begin = f.bin_cells.begin() + f.bin_start[b], end = f.bin_cells.begin() + f.bin_start[b + 1];
      if (s.candidates.empty()) {
        s.candidates.assign(begin, end);
        continue;
      }
      s.merged.resize(s.candidates.size() + std::size_t(end - begin));
      s.merged.erase(std::set_union(s.candidates.begin(), s.candidates.end(), begin, end, s.merged.begin()), s.merged.end());
      s.candidates.swap(s.merged);
    }
  }
  const std::size_t nx = std::size_t(nx_);
  const int32_t cells_a_row = nx_ - 1;
  // The cells that meet the batch, set up 16 at a time, then each against the samples of the rows its
  // box can hold (a sample lies within 1.5 pixels of its pixel's corner), in whole vectors.
  RasterCellSetup& setup = s.setup;
  const Frame::Cell* pending[16];
  setup.count = 0;
  const auto flush = [&] {
    if (setup.count == 0) return;
    HWY_DYNAMIC_DISPATCH(RasterSetupLanes)(camera, vx_.data(), vy_.data(), vz_.data(), nx, setup);
    for (int32_t m = 0; m < setup.count; ++m) {
      const Frame::Cell& fc = *pending[m];
      RasterCell cell{fc.x0, fc.y0, fc.x1, fc.y1, fc.near, fc.index};
      float* to[7] = {cell.n_ab, cell.n_ac, cell.n_bd, cell.n_cd, cell.n_ad, cell.n1, cell.n2};
      for (int k = 0; k < 7; ++k)
        for (int c = 0; c < 3; ++c) to[k][c] = setup.n[3 * k + c][m];
      cell.h1 = setup.h1[m], cell.h2 = setup.h2[m];
      const int py0 = std::max(y0 + row_first, int(std::floor((f.half_height - fc.y1) / f.pixel_dy - 1.5f)));
      const int py1 = std::min(y0 + row_last, int(std::ceil((f.half_height - fc.y0) / f.pixel_dy + 0.5f)));
      if (py0 > py1) continue;
      const std::size_t pixel_begin = std::size_t(std::max(first, (py0 - y0) * tile_width) - first);
      const std::size_t pixel_end = std::size_t(std::min(first + count, (py1 - y0 + 1) * tile_width) - first);
      const std::size_t begin = pixel_begin * std::size_t(spp) / CameraLanes::kPad * CameraLanes::kPad;
      const std::size_t end = std::min(L.padded, CameraLanes::paddedSize(pixel_end * std::size_t(spp)));
      HWY_DYNAMIC_DISPATCH(RasterCellLanes)(cell, L, begin, end, s);
    }
    setup.count = 0;
  };
  for (const uint32_t candidate : s.candidates) {
    const Frame::Cell& fc = f.cells[candidate];
    if (fc.block_near > reach) {
      // Blocks nearest first: once a block is beyond every sample's hit so far, so are the rest.
      flush();
      reach = 0.0f;
      for (std::size_t k = 0; k < n; ++k)
        if (L.t_enter[k] <= L.t_leave[k]) reach = std::max(reach, s.best[k]);
      if (fc.block_near > reach) break;
    }
    if (fc.near > reach || !Box{fc.x0, fc.y0, fc.x1, fc.y1}.meets(batch)) continue;
    const int32_t i = fc.index % cells_a_row, j = fc.index / cells_a_row;
    setup.vertex[setup.count] = j * nx_ + i;
    pending[setup.count++] = &fc;
    if (setup.count == 16) flush();
  }
  flush();
  // The hits as Embree's quad hits.
  HWY_DYNAMIC_DISPATCH(RasterHitLanes)(xs_.data(), zs_.data(), cells_a_row, s, L, geom, prim, u, v);
  return true;
}

}  // namespace stirrup::render

#endif  // HWY_ONCE
