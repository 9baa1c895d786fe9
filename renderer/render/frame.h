#pragma once
// A whole frame as the scene file asks for it: the beauty, the requested
// AOVs, the path-selection layers (same pass) and each variant layer (its own
// render of the modified scene), merged into one multi-layer image.
#include "renderer/render/render.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

struct FrameResult {
  LayeredImage image;
  RenderStats stats;  // summed over the beauty pass and every variant pass
  int passes = 1;
  // With RenderOptions::keep_sums: the exact film state of every channel of
  // `image` (same layout and channel order, see RenderResult::film).
  FilmSums film;
  std::optional<CryptoFilm> crypto;  // RenderResult::crypto of the beauty pass
};

// `options.layers` is ignored: the layers come from desc.layers. Progress is
// reported over all passes together. `options.keep_sums` carries the exact
// sums of every pass through the same channel mapping as the image.
FrameResult render_frame(const SceneDescription& desc, const RenderOptions& options = {});

// The scene as a variant layer sees it: medium overrides applied, removed
// media dropped, lights outside the active groups switched off (their
// geometry stays, so shadows do not change).
SceneDescription apply_variant(const SceneDescription& desc, const VariantDesc& variant);

}  // namespace vesper
