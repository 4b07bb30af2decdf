// A crowd of four pairs for the shot's tests: two ranks of two files trotting along +X, each pair of its
// own size, profile and start phase, read as if from scenes/ so its profiles are found beside it.
#pragma once

#include <string>

#include "scene/scene.h"

namespace stirrup::render::test {

inline scene::SceneSpec crowdOfFour() {
  return scene::parseScene(nlohmann::json::parse(R"({"name": "crowd4", "frames": "1-24", "resolution": [320, 180],
    "riders": [
      {"points": [[0, -300], [3000, -300]], "speed": [[0, 300]], "profile": "thesis", "seed": 1,
       "withers_height_cm": 150, "rider_height_cm": 160, "rider_build": 0.9},
      {"points": [[0, 300], [3000, 300]], "speed": [[0, 300]], "profile": "english", "seed": 2, "start_offset_s": 0.3,
       "withers_height_cm": 170, "rider_height_cm": 185, "rider_build": 1.2},
      {"points": [[-1200, -300], [1800, -300]], "speed": [[0, 300]], "profile": "novice", "seed": 3,
       "start_offset_s": 0.6, "withers_height_cm": 160, "rider_height_cm": 170},
      {"points": [[-1200, 300], [1800, 300]], "speed": [[0, 300]], "profile": "thesis", "seed": 4,
       "start_offset_s": 0.9, "withers_height_cm": 165, "rider_height_cm": 175, "rider_build": 1.1}]})"),
                    std::string(STIRRUP_SOURCE_DIR) + "/scenes/crowd4.json");
}

}  // namespace stirrup::render::test
