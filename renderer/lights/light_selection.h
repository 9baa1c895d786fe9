#pragma once

namespace vesper {

// render.light_selection (docs/scene-format.md#render): how next-event
// estimation picks a light (light_sampler.h). Spatial weighs lights by their
// estimated contribution at the shading point (with a light tree once the
// scene has many lights); PowerUniform is the choice before it (half by
// power, half uniform, the same everywhere); Tree always uses the light
// tree (light_tree.h).
enum class LightSelection { Spatial, PowerUniform, Tree };

}  // namespace vesper
