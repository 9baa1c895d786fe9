// Fuzz target: the compositor's recipe parser (`vesper-comp/1`, as `vesper
// comp recipe.json` reads it). The documented error is CompError. Paths
// resolve in the sandbox, which holds frame.exr, frame.0001/0002.exr,
// other.0001/0002.exr, look.cube, config.ocio and an out/ folder.
#include "common/frame_pattern.h"
#include "compositor/recipe.h"
#include "compositor/rgba_image.h"
#include "tests/fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vesper;
  CompRecipe recipe;
  try {
    recipe = parse_recipe_text(fuzz::text_of(data, size), fuzz::sandbox(), "recipe.json");
  } catch (const CompError&) {
    return 0;
  }
  fuzz::note_accepted();
  // What `vesper comp` does next with an accepted recipe, before any pixels.
  if (recipe.inputs.empty() || recipe.layers.empty())
    fuzz::finding("an accepted recipe has no inputs or no layers");
  for (const CompLayer& l : recipe.layers)
    if (l.input >= recipe.inputs.size()) fuzz::finding("a layer names an input out of range");
  for (const long f : recipe.frames) (void)frame_path(recipe.outputs.image, f);
  (void)default_histogram_path(recipe.outputs);
  return 0;
}
