// relMSE of images against a reference, as DESIGN.md pins it (mean over
// pixels and RGB of (x - r)^2 / (r^2 + 0.01)), for scripts that compare
// renders made by different binaries (bench/sampler_error.sh).
//
//   ./build/bench/vesper_relmse REFERENCE.exr IMAGE.exr...   (one line per image)
#include <cstdio>
#include <exception>

#include "renderer/output/exr_io.h"
#include "renderer/output/image_metrics.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s REFERENCE.exr IMAGE.exr...\n", argv[0]);
    return 2;
  }
  try {
    const vesper::LayeredImage reference = vesper::read_exr(argv[1]);
    for (int i = 2; i < argc; ++i)
      std::printf("%.9g %s\n", vesper::relative_mse(vesper::read_exr(argv[i]), reference), argv[i]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vesper_relmse: %s\n", e.what());
    return 1;
  }
  return 0;
}
