// Wall time for the timings the renderer and the program report (setup, commit, frames, movies): milliseconds since a point of
// std::chrono::steady_clock, which never goes back.
#pragma once

#include <chrono>

namespace stirrup::render {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }
inline double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace stirrup::render
