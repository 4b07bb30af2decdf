// The constants of angle and gravity the rig's files share, defined once: a file that needs pi or a
// degree takes it from here rather than a copy of its own (and a unity build, which compiles several
// files as one, finds no twin definitions). Each value is exactly the one its files used before.
#pragma once

#include <numbers>

namespace stirrup::rig {

inline constexpr double kPi = std::numbers::pi;
inline constexpr float kPiF = std::numbers::pi_v<float>;
inline constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
inline constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
inline constexpr float kRadiansPerDegreeF = std::numbers::pi_v<float> / 180.0f;

// Standard gravity (BIPM, 3rd CGPM 1901): 9.80665 m/s².
inline constexpr double kStandardGravityCmS2 = 980.665;

}  // namespace stirrup::rig
