// The arithmetic the SIMD kernels share (render/tracer/sample_lanes.cpp, render/tracer/shading_lanes.cpp), compiled
// once per Highway target: a file that includes it under foreach_target.h gets a copy in each target's
// namespace (Highway's "-inl.h" convention: the include guard toggles with HWY_TARGET_TOGGLE).
//
// Each function is the scalar expression it names, operation for operation and in the same order, with
// only operations IEEE 754 rounds exactly (no fused multiply-add anywhere), so every target rounds as
// the scalar code does.

#if defined(STIRRUP_RENDER_LANE_MATH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef STIRRUP_RENDER_LANE_MATH_INL_H_
#undef STIRRUP_RENDER_LANE_MATH_INL_H_
#else
#define STIRRUP_RENDER_LANE_MATH_INL_H_
#endif

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <hwy/highway.h>

#include "render/tracer/sample_lanes.h"  // LaneConstants

HWY_BEFORE_NAMESPACE();
namespace stirrup::render {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using MF = hn::Mask<DF>;

inline VF Load(const std::vector<float>& v, size_t i) { return hn::LoadU(DF(), v.data() + i); }
inline void Store(VF x, std::vector<float>& v, size_t i) { hn::StoreU(x, DF(), v.data() + i); }
inline void StoreMask(MF m, std::vector<int32_t>& v, size_t i) {
  const DI di;
  hn::StoreU(hn::VecFromMask(di, hn::RebindMask(di, m)), di, v.data() + i);
}
inline MF LoadMask(const std::vector<int32_t>& v, size_t i) {
  return hn::RebindMask(DF(), hn::MaskFromVec(hn::LoadU(DI(), v.data() + i)));
}
inline VF Splat(float x) { return hn::Set(DF(), x); }
// The lanes of the vector at i that hold one of the first n entries (the rest are padding).
inline MF Live(size_t n, size_t i) {
  const DF df;
  return i + hn::Lanes(df) <= n ? hn::Not(hn::FirstN(df, 0)) : hn::FirstN(df, n > i ? n - i : 0);
}
// x * (1 - a) + y * a: glm::mix.
inline VF Mix(VF x, VF y, VF a) { return hn::Add(hn::Mul(x, hn::Sub(Splat(1.0f), a)), hn::Mul(y, a)); }

// Three lanes of vectors: a glm::vec3 per lane.
struct V3 {
  VF x, y, z;
};
inline V3 Load3(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z, size_t i) {
  return {Load(x, i), Load(y, i), Load(z, i)};
}
inline void Store3(const V3& v, std::vector<float>& x, std::vector<float>& y, std::vector<float>& z, size_t i) {
  Store(v.x, x, i), Store(v.y, y, i), Store(v.z, z, i);
}
inline V3 Splat3(const glm::vec3& v) { return {Splat(v.x), Splat(v.y), Splat(v.z)}; }
inline V3 Add3(const V3& a, const V3& b) { return {hn::Add(a.x, b.x), hn::Add(a.y, b.y), hn::Add(a.z, b.z)}; }
inline V3 Sub3(const V3& a, const V3& b) { return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)}; }
inline V3 Mul3(const V3& a, const V3& b) { return {hn::Mul(a.x, b.x), hn::Mul(a.y, b.y), hn::Mul(a.z, b.z)}; }
inline V3 Scale3(VF s, const V3& a) { return {hn::Mul(s, a.x), hn::Mul(s, a.y), hn::Mul(s, a.z)}; }
inline V3 Neg3(const V3& a) { return {hn::Neg(a.x), hn::Neg(a.y), hn::Neg(a.z)}; }
inline V3 Select3(MF m, const V3& a, const V3& b) {
  return {hn::IfThenElse(m, a.x, b.x), hn::IfThenElse(m, a.y, b.y), hn::IfThenElse(m, a.z, b.z)};
}
// glm::dot: (x x' + y y') + z z'.
inline VF Dot3(const V3& a, const V3& b) {
  return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}
// glm::length and glm::normalize (v * (1 / sqrt(dot(v, v)))).
inline VF Length3(const V3& a) { return hn::Sqrt(Dot3(a, a)); }
inline V3 Normalize3(const V3& a) { return Scale3(hn::Div(Splat(1.0f), hn::Sqrt(Dot3(a, a))), a); }

// sinCosQuarterPi (render/tracer/lights.h): sin and cos on [-pi/4, pi/4].
inline void SinCosQuarterPi(VF x, VF& s, VF& c) {
  const VF z = hn::Mul(x, x);
  VF ps = hn::Add(hn::Mul(Splat(-1.9515295891e-4f), z), Splat(8.3321608736e-3f));
  ps = hn::Sub(hn::Mul(ps, z), Splat(1.6666654611e-1f));
  s = hn::Add(hn::Mul(hn::Mul(ps, z), x), x);
  VF pc = hn::Sub(hn::Mul(Splat(2.443315711809948e-5f), z), Splat(1.388731625493765e-3f));
  pc = hn::Add(hn::Mul(pc, z), Splat(4.166664568298827e-2f));
  c = hn::Add(hn::Sub(hn::Mul(hn::Mul(pc, z), z), hn::Mul(Splat(0.5f), z)), Splat(1.0f));
}

// unitCircle (render/tracer/lights.h): cos and sin of 2 pi u.
inline void UnitCircle(VF u, VF& cos_out, VF& sin_out) {
  const VF q = hn::Floor(hn::Add(hn::Mul(u, Splat(4.0f)), Splat(0.5f)));
  VF s, c;
  SinCosQuarterPi(hn::Mul(hn::Sub(u, hn::Mul(q, Splat(0.25f))), Splat(2.0f * 3.14159265358979323846f)), s, c);
  const VF quarter = hn::Sub(q, hn::Mul(Splat(4.0f), hn::Floor(hn::Mul(q, Splat(0.25f)))));  // q mod 4
  const MF q1 = hn::Eq(quarter, Splat(1.0f)), q2 = hn::Eq(quarter, Splat(2.0f)), q3 = hn::Eq(quarter, Splat(3.0f));
  cos_out = hn::IfThenElse(q1, hn::Neg(s), hn::IfThenElse(q2, hn::Neg(c), hn::IfThenElse(q3, s, c)));
  sin_out = hn::IfThenElse(q1, c, hn::IfThenElse(q2, hn::Neg(s), hn::IfThenElse(q3, hn::Neg(c), s)));
}

// powWhole (render/tracer/lights.h): x to a whole power by repeated squaring.
inline VF PowWhole(VF x, int n) {
  VF result = Splat(1.0f);
  for (VF base = x; n > 0; n >>= 1, base = hn::Mul(base, base))
    if (n & 1) result = hn::Mul(result, base);
  return result;
}

// Frame::around (render/tracer/lights.h): an orthonormal basis around a unit n (Duff et al. 2017).
struct Frame3 {
  V3 x, y, z;
  V3 toWorld(VF a, VF b, VF c) const {  // a x + b y + c z
    return Add3(Add3(Scale3(a, x), Scale3(b, y)), Scale3(c, z));
  }
};
inline Frame3 FrameAround(const V3& n) {
  const VF sign = hn::CopySign(Splat(1.0f), n.z);
  const VF a = hn::Div(Splat(-1.0f), hn::Add(sign, n.z));
  const VF b = hn::Mul(hn::Mul(n.x, n.y), a);
  const V3 x = {hn::Add(Splat(1.0f), hn::Mul(hn::Mul(hn::Mul(sign, n.x), n.x), a)), hn::Mul(sign, b),
                hn::Neg(hn::Mul(sign, n.x))};
  const V3 y = {b, hn::Add(sign, hn::Mul(hn::Mul(n.y, n.y), a)), hn::Neg(n.y)};
  return {x, y, n};
}

// Integrator::sunMayBeBlocked, lane by lane: the sun's axis from the origin against the characters'
// box grown by the cone's radius at the box's far corner.
inline MF SunMayBeBlocked(const LaneConstants& k, const V3& o) {
  if (k.box_empty) return hn::FirstN(DF(), 0);
  const V3 lower = Splat3(k.box_lower), upper = Splat3(k.box_upper);
  const V3 to_lower = Sub3(o, lower), to_upper = Sub3(o, upper);
  const V3 far_corner = {hn::Max(hn::Abs(to_lower.x), hn::Abs(to_upper.x)),
                         hn::Max(hn::Abs(to_lower.y), hn::Abs(to_upper.y)),
                         hn::Max(hn::Abs(to_lower.z), hn::Abs(to_upper.z))};
  const VF margin = hn::Add(hn::Mul(hn::Mul(Length3(far_corner), Splat(k.sun_tan)), Splat(1.01f)), Splat(0.1f));
  const VF o_a[3] = {o.x, o.y, o.z};
  const float lo_a[3] = {k.box_lower.x, k.box_lower.y, k.box_lower.z};
  const float up_a[3] = {k.box_upper.x, k.box_upper.y, k.box_upper.z};
  const float d_a[3] = {k.sun_axis.x, k.sun_axis.y, k.sun_axis.z};
  VF t0 = Splat(0.0f), t1 = Splat(std::numeric_limits<float>::infinity());
  MF miss = hn::FirstN(DF(), 0);
  for (int a = 0; a < 3; ++a) {
    const VF lo = hn::Sub(Splat(lo_a[a]), margin), up = hn::Add(Splat(up_a[a]), margin);
    if (d_a[a] == 0.0f) {
      miss = hn::Or(miss, hn::Or(hn::Lt(o_a[a], lo), hn::Gt(o_a[a], up)));
      continue;
    }
    const VF inv = Splat(1.0f / d_a[a]);
    const VF n0 = hn::Mul(hn::Sub(lo, o_a[a]), inv), f0 = hn::Mul(hn::Sub(up, o_a[a]), inv);
    const MF swap = hn::Gt(n0, f0);
    t0 = hn::Max(t0, hn::IfThenElse(swap, f0, n0));
    t1 = hn::Min(t1, hn::IfThenElse(swap, n0, f0));
    miss = hn::Or(miss, hn::Gt(t0, t1));  // t0 only grows and t1 only shrinks: a miss stays one
  }
  return hn::Not(miss);
}

// Slab test against the characters' box up to t_far: most rays of a review frame pass beside it, and
// this is far cheaper than a call into Embree. All three slabs are tested (a test that stopped at the
// first failed slab gives the same answer: t0 only grows and t1 only shrinks). Written so a NaN
// (0 * inf) leaves the interval unchanged, with a little slack for rounding at grazing angles. No
// characters: every ray misses.
inline MF BoxTest(const LaneConstants& k, VF ox, VF oy, VF oz, VF dx, VF dy, VF dz, VF t_far) {
  if (k.box_empty) return hn::FirstN(DF(), 0);  // no lane
  VF t0 = Splat(0.0f), t1 = t_far;
  MF miss = hn::Not(hn::Gt(t_far, Splat(0.0f)));
  const VF o[3] = {ox, oy, oz}, d[3] = {dx, dy, dz};
  const float lower[3] = {k.box_lower.x, k.box_lower.y, k.box_lower.z};
  const float upper[3] = {k.box_upper.x, k.box_upper.y, k.box_upper.z};
  for (int a = 0; a < 3; ++a) {
    const VF inv = hn::Div(Splat(1.0f), d[a]);
    const VF n0 = hn::Mul(hn::Sub(Splat(lower[a]), o[a]), inv);
    const VF f0 = hn::Mul(hn::Sub(Splat(upper[a]), o[a]), inv);
    const MF swap = hn::Gt(n0, f0);
    const VF near = hn::IfThenElse(swap, f0, n0), far = hn::IfThenElse(swap, n0, f0);
    t0 = hn::IfThenElse(hn::Gt(near, t0), near, t0);  // a NaN leaves the interval unchanged
    t1 = hn::IfThenElse(hn::Lt(far, t1), far, t1);
    miss = hn::Or(miss, hn::Gt(t0, hn::Mul(t1, Splat(1.0000004f))));
  }
  return hn::Not(miss);
}

}  // namespace HWY_NAMESPACE
}  // namespace stirrup::render
HWY_AFTER_NAMESPACE();

#endif  // include guard
