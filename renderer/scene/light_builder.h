#pragma once
// Scene-description lights (world units) -> render-space lights.
#include <optional>

#include "renderer/core/accel.h"
#include "renderer/lights/light.h"
#include "renderer/scene/render_space.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

// A render-space light and the ways rays other than shadow rays reach it.
struct RenderLight {
  Light light;
  // Lights that are also a surface camera and BSDF rays hit (quads); the
  // caller sets `light` to the light's index.
  std::optional<AccelQuad> surface;
  bool at_infinity = false;  // rays that escape the scene reach it (environment, sun disk)
};

RenderLight make_render_light(const LightDesc& desc, const RenderSpace& space);

}  // namespace vesper
