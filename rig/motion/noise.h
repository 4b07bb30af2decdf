// Deterministic, hash-based noise for natural variation: the same seed and coordinates always give
// the same value, on any machine and in any frame order (no global RNG, no state).
#pragma once

#include <cmath>
#include <cstdint>

namespace stirrup::rig {

// A well-mixed 32-bit hash of a seed and two integer coordinates (lowbias32-style finaliser).
inline std::uint32_t hash3(std::uint32_t seed, std::int64_t a, std::int64_t b = 0) {
  std::uint32_t x = seed * 0x9E3779B9u ^ static_cast<std::uint32_t>(a) * 0x85EBCA6Bu ^
                    static_cast<std::uint32_t>(b) * 0xC2B2AE35u ^ static_cast<std::uint32_t>(a >> 32);
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x;
}

// Uniform in [-1, 1] for integer coordinates.
inline double hashSigned(std::uint32_t seed, std::int64_t a, std::int64_t b = 0) {
  return hash3(seed, a, b) / 2147483647.5 - 1.0;
}

// Smooth 1-D value noise in [-1, 1]: C1 (smoothstep between integer lattice values).
inline double valueNoise(std::uint32_t seed, double x, std::int64_t channel = 0) {
  const double i = std::floor(x);
  const double f = x - i;
  const double s = f * f * (3.0 - 2.0 * f);
  const auto k = static_cast<std::int64_t>(i);
  return hashSigned(seed, k, channel) * (1.0 - s) + hashSigned(seed, k + 1, channel) * s;
}

}  // namespace stirrup::rig
