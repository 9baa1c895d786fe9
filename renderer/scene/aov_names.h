#pragma once
// The names of the standard AOVs, as in render.aovs and `vesper render --aov`.
#include <iterator>
#include <optional>
#include <string_view>

#include "renderer/scene/scene_description.h"

namespace vesper {

// JSON names of the standard AOVs (render.aovs), indexed by Aov.
inline constexpr std::string_view kAovNames[] = {
    "albedo",         "normal",           "depth",           "emission",
    "diffuse_direct", "diffuse_indirect", "specular_direct", "specular_indirect",
    "volume_direct",  "volume_indirect",  "variance",        "spp",
    "cryptomatte"};
static_assert(std::size(kAovNames) == size_t(Aov::Cryptomatte) + 1);

inline std::optional<Aov> aov_from_name(std::string_view name) {
  for (size_t i = 0; i < std::size(kAovNames); ++i)
    if (kAovNames[i] == name) return Aov(i);
  return std::nullopt;
}

}  // namespace vesper
