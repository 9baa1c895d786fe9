#pragma once
// The renderer's value types read with the common JsonReader (common/ knows
// no renderer types): Vec3d as [x, y, z] and Rgb as [r, g, b], each component
// checked and reported at its own JSON path. Used by the scene loader and the
// compositor's recipe (tints, CDL).
#include <string_view>

#include "common/json_reader.h"
#include "renderer/math/rgb.h"
#include "renderer/math/vec.h"

namespace vesper {

// This node as [x, y, z] (finite numbers).
Vec3d as_vec3(const JsonReader& node);
// This node as [r, g, b], each in `component_range` and representable as a float.
Rgb as_rgb(const JsonReader& node, const Range& component_range);

// Object keys (recorded as known to `node`, like JsonReader's own getters).
Vec3d read_vec3(JsonReader& node, std::string_view key);
Rgb read_rgb(JsonReader& node, std::string_view key, const Range& component_range);
Rgb read_rgb(JsonReader& node, std::string_view key, Rgb fallback, const Range& component_range);

}  // namespace vesper
