// The report of a measured clip: `clip info`'s text table and its --json, each number beside its
// reference range and verdict (rig/motion/gait_reference.h) when the clip has one.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "rig/motion/clip_measure.h"
#include "rig/motion/gait_reference.h"

namespace stirrup::rig {

// Human-readable table with the reference beside each number (reference may be null).
std::string formatClipInfo(const ClipInfo& info, const GaitReference* reference);
nlohmann::json clipInfoJson(const ClipInfo& info, const GaitReference* reference);

}  // namespace stirrup::rig
