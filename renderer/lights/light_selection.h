#pragma once

namespace vesper {

// render.light_selection (docs/scene-format.md#render): how next-event
// estimation picks a light (light_sampler.h). Spatial weighs lights by their
// estimated contribution at the shading point; PowerUniform is the choice
// before it (half by power, half uniform, the same everywhere).
enum class LightSelection { Spatial, PowerUniform };

}  // namespace vesper
