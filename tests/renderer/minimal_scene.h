#pragma once
// A minimal valid scene (16x8, 1 spp, one diffuse material, no shapes) for
// renderer tests to modify.
#include <nlohmann/json.hpp>

namespace vesper::test {

inline nlohmann::json minimal_scene() {
  return nlohmann::json::parse(R"({
    "format": "vesper-scene/1",
    "camera": {"type": "perspective", "from": [0, 0, 4], "to": [0, 0, 0], "up": [0, 1, 0], "fov": 30},
    "film": {"width": 16, "height": 8},
    "render": {"spp": 1},
    "materials": {"m": {"type": "diffuse"}},
    "shapes": []
  })");
}

}  // namespace vesper::test
