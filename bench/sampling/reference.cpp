#include "bench/sampling/reference.h"

#include <string>

#include "renderer/output/exr_io.h"
#include "renderer/output/film_sums.h"
#include "renderer/render/render.h"

namespace vesper::bench {
namespace {

double noise_floor(const LayeredImage& img) {
  // By name: an EXR read back may list the channels in another order.
  const char* beauty[3] = {"R", "G", "B"};
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    const int b = img.channel_index(beauty[c]), v = img.channel_index(kVarianceChannels[c]);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const double r = img.at(x, y, size_t(b));
        sum += img.at(x, y, size_t(v)) / (r * r + 0.01);
      }
  }
  return sum / (3.0 * img.width * img.height);
}

std::string cache_name(const Scene& scene, int spp, uint64_t seed) {
  return "reference-" + scene.content_hash + "-v" + VESPER_VERSION + "-" +
         std::to_string(scene.film.width) + "x" + std::to_string(scene.film.height) + "-" +
         std::to_string(spp) + "spp-seed" + std::to_string(seed) + ".exr";
}

}  // namespace

Reference load_or_render_reference(const Scene& scene, int spp, uint64_t seed,
                                   const std::optional<std::filesystem::path>& cache) {
  Reference ref;
  const std::filesystem::path file = cache ? *cache / cache_name(scene, spp, seed) : "";
  if (cache && std::filesystem::exists(file)) {
    ref.image = read_exr(file);
    ref.from_cache = true;
  } else {
    RenderOptions o;
    o.spp = spp;
    o.seed = seed;
    o.aovs = std::vector<Aov>{Aov::Variance};
    const RenderResult r = render(scene, o);
    ref.image = r.image;
    ref.seconds = r.stats.seconds;
    if (cache) {
      std::filesystem::create_directories(*cache);
      write_exr(ref.image, file);
    }
  }
  ref.noise_floor = noise_floor(ref.image);
  return ref;
}

}  // namespace vesper::bench
