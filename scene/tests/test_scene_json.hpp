// test_scene_json.hpp — a minimal valid scene document, for tests that change one thing in it.
#pragma once

#include <nlohmann/json.hpp>

namespace shadowref::scene::test {

inline nlohmann::json minimal_scene() {
  return nlohmann::json::parse(R"({
    "name": "minimal",
    "description": "a box over a ground plane",
    "resolution": [64, 48],
    "camera": { "position": [0, 4, 8], "target": [0, 0, 0], "up": [0, 1, 0], "fovy_deg": 45, "near": 0.1 },
    "lights": [ { "type": "point", "position": [2, 6, 1] } ],
    "objects": [
      { "name": "ground", "shape": { "type": "plane", "size": [20, 20] }, "receiver": true },
      { "name": "ball", "shape": { "type": "sphere", "radius": 1, "segments": 16 },
        "transform": { "translate": [0, 1.5, 0] } }
    ],
    "expect": { "planar": { "result": "pass" } }
  })");
}

}  // namespace shadowref::scene::test
