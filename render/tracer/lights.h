// The two lights of the review look: a sun (a disc of a given angular radius, sampled as a cone so
// shadows are soft) and a sky (a vertical gradient, sampled cosine-weighted for ambient occlusion): their
// sampling and the arithmetic the lanes share. The Light interface over them is render/tracer/light.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace stirrup::render {

// An orthonormal basis around a unit vector n (Duff et al. 2017, branchless and continuous).
struct Frame {
  glm::vec3 x, y, z;  // z = n

  static Frame around(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  glm::vec3 toWorld(const glm::vec3& v) const { return v.x * x + v.y * y + v.z * z; }
};

// sin and cos of x in [-pi/4, pi/4] as polynomials (the minimax coefficients of Cephes' sinf and
// cosf, Moshier 1989; error under 2 ulp there), in plain multiplies and adds in this order: the SIMD
// lanes (render/tracer/lane_math-inl.h) evaluate the same operations, so every instruction set gets the
// same bits, which std::sin and std::cos do not promise.
inline void sinCosQuarterPi(float x, float& s, float& c) {
  const float z = x * x;
  s = ((-1.9515295891e-4f * z + 8.3321608736e-3f) * z - 1.6666654611e-1f) * z * x + x;
  c = ((2.443315711809948e-5f * z - 1.388731625493765e-3f) * z + 4.166664568298827e-2f) * z * z - 0.5f * z + 1.0f;
}

// cos and sin of 2 pi u for u in [0, 1): reduced to the nearest quarter turn q (u - q/4 is exact),
// then rotated by q quarter turns.
inline glm::vec2 unitCircle(float u) {
  const float q = std::floor(u * 4.0f + 0.5f);
  float s, c;
  sinCosQuarterPi((u - q * 0.25f) * (2.0f * std::numbers::pi_v<float>), s, c);
  switch (int(q) & 3) {
    case 1: return {-s, c};
    case 2: return {-c, -s};
    case 3: return {s, -c};
    default: return {c, s};
  }
}

// x to a whole power n >= 0 by repeated squaring, in this order (the lanes do the same).
inline float powWhole(float x, int n) {
  float result = 1.0f;
  for (float base = x; n > 0; n >>= 1, base *= base)
    if (n & 1) result *= base;
  return result;
}

// Uniform direction within the cone of half-angle acos(cos_max) around the frame's z axis: uniform
// in solid angle, which is exact for a disc of constant radiance.
inline glm::vec3 sampleCone(const Frame& axis, float cos_max, glm::vec2 u) {
  const float cos_t = 1.0f - u.x * (1.0f - cos_max);
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  const glm::vec2 circle = unitCircle(u.y);
  return axis.toWorld({sin_t * circle.x, sin_t * circle.y, cos_t});
}

// Cosine-weighted direction in the hemisphere around the frame's z axis (Malley's method over a
// concentric disc mapping, which keeps the stratification of u). The pdf is cos / pi, so the mean
// of L over these samples is the irradiance divided by pi. The disc's angle is pi/4 (b/a), or
// pi/2 - pi/4 (a/b) whose cosine and sine are the sine and cosine of pi/4 (a/b).
inline glm::vec3 sampleCosineHemisphere(const Frame& around, glm::vec2 u) {
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  constexpr float quarter_pi = std::numbers::pi_v<float> / 4.0f;
  const bool wide = std::abs(a) > std::abs(b);
  const float r = wide ? a : b;
  float s, c;
  sinCosQuarterPi(r != 0.0f ? quarter_pi * ((wide ? b : a) / r) : 0.0f, s, c);
  const float dx = r * (wide ? c : s), dy = r * (wide ? s : c);
  const float dz = std::sqrt(std::max(0.0f, 1.0f - dx * dx - dy * dy));
  return around.toWorld({dx, dy, dz});
}

struct SkyGradient {
  glm::vec3 horizon{0.60f, 0.66f, 0.74f};  // linear radiance
  glm::vec3 zenith{0.22f, 0.34f, 0.62f};
  glm::vec3 below{0.60f, 0.66f, 0.74f};     // below the horizon past the ground: the haze, as the horizon

  // Radiance from direction d (unit). The square root keeps the sky pale for the lower third, as a
  // clear sky is.
  glm::vec3 radiance(const glm::vec3& d) const {
    if (d.y < 0.0f) return glm::mix(horizon, below, std::min(1.0f, -8.0f * d.y));
    return glm::mix(horizon, zenith, std::sqrt(d.y));
  }

  // Irradiance / pi on an upward-facing surface under the full, unoccluded sky: the cosine-weighted
  // mean radiance. With t = sqrt(cos), E/pi = 2 * integral_0^1 mix(h, z, sqrt(c)) c dc = h + 0.8 (z - h).
  glm::vec3 upwardIrradianceOverPi() const { return horizon + 0.8f * (zenith - horizon); }
};

// Aerial perspective: the ground fades into the horizon's colour with distance, so every view has a
// horizon where the hazed ground meets the sky instead of a checker running to the frame's top edge.
// Transmittance is (1 - t / visibility)^3 along a perspective ray: 1 at the camera, 0.97 at 10 m,
// exactly 0 at `visibility_cm` (a polynomial, not exp(): the same bits on every SIMD target, and the
// ground ends seamlessly where it is fully hazed). An orthographic camera has no eye to measure from:
// its ground fades the same way from the camera's target to `ortho_depth_cm` behind it, and its sky
// above that line is graded by height on the film.
struct AerialPerspective {
  float visibility_cm = 60000.0f;  // perspective: the ground is fully hazed 600 m away
  float ortho_depth_cm = 1500.0f;  // orthographic: ... this far behind the camera's target

  // The fraction of the ground's own radiance that reaches the camera (the rest is the horizon's).
  static float perspective(float t, float visibility) {
    const float x = 1.0f - std::min(t / visibility, 1.0f);
    return x * x * x;
  }
  static float orthographic(float behind_target, float depth) {
    const float x = 1.0f - std::min(std::max(behind_target / depth, 0.0f), 1.0f);
    return x * x * x;
  }
};

}  // namespace stirrup::render
