// Fuzz target: the renderer's scene parser (`vesper-scene/1`), as a farm
// worker loads a submitted scene (`vesper render --scene-dir-only`). The
// documented error is SceneError. A scene it accepts must also build
// (build_scene throws nothing) into a render-space scene whose camera and
// volume transforms are finite: a NaN there reaches every pixel.
#include <cmath>

#include "renderer/scene/scene.h"
#include "renderer/scene/scene_loader.h"
#include "tests/fuzz/fuzz_target.h"
#include "tests/fuzz/scene_assets.h"

namespace vesper::fuzz {
namespace {

bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_camera(const Camera& c) {
  if (!finite(c.position) || !finite(c.right) || !finite(c.up) || !finite(c.forward) ||
      !std::isfinite(c.tan_half_x) || !std::isfinite(c.tan_half_y) ||
      !std::isfinite(c.lens_radius) || !std::isfinite(c.focus_distance))
    finding("an accepted scene has a camera with a NaN or infinite value");
}

void check_media(const MediaSet& media) {
  for (const Medium& m : media.media())
    if (const auto* g = std::get_if<GridMedium>(&m))
      for (const Transformf* t : {&g->render_to_index, &g->render_to_emission_index})
        for (const Matrix4T<float>* mat : {&t->matrix(), &t->inverse_matrix()})
          for (const float v : mat->m)
            if (!std::isfinite(v))
              finding(
                  "an accepted scene has a volume whose render-to-index transform is not "
                  "finite");
}

}  // namespace
}  // namespace vesper::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vesper;
  static const std::filesystem::path file = fuzz::scene_sandbox() / "scene.json";
  SceneDescription desc;
  try {
    desc = parse_scene_text(fuzz::text_of(data, size), file, {.scene_dir_only = true});
  } catch (const SceneError&) {
    return 0;
  }
  fuzz::note_accepted();
  const Scene scene = build_scene(desc);
  if (!std::isfinite(scene.unit_scale) || !(scene.unit_scale > 0) || !std::isfinite(scene.radius))
    fuzz::finding("an accepted scene has a non-finite render space");
  fuzz::check_camera(scene.camera);
  fuzz::check_media(scene.media);
  return 0;
}
