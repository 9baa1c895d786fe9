#include "renderer/scene/environment_image.h"

#include <cmath>
#include <limits>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include "renderer/scene/scene_loader.h"

namespace vesper {
namespace {

enum class Encoding { Linear, Srgb, Gamma };

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// How the stored values map to linear light. OIIO tags what it knows in
// "oiio:ColorSpace"; untagged integer images are almost always sRGB-encoded.
Encoding encoding_of(const OIIO::ImageSpec& spec, float& gamma) {
  const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
  gamma = spec.get_float_attribute("oiio:Gamma", 1.f);
  if (OIIO::Strutil::iequals(cs, "sRGB")) return Encoding::Srgb;
  if (OIIO::Strutil::istarts_with(cs, "GammaCorrected") && gamma > 0) return Encoding::Gamma;
  if (OIIO::Strutil::icontains(cs, "linear") || OIIO::Strutil::icontains(cs, "lin_")) {
    return Encoding::Linear;
  }
  const OIIO::TypeDesc f = spec.format;
  const bool is_float = f.basetype == OIIO::TypeDesc::FLOAT || f.basetype == OIIO::TypeDesc::HALF ||
                        f.basetype == OIIO::TypeDesc::DOUBLE;
  return is_float ? Encoding::Linear : Encoding::Srgb;
}

const char* channel_name(int c) { return c == 0 ? "R" : (c == 1 ? "G" : "B"); }

}  // namespace

EnvironmentImage load_environment_image(const std::filesystem::path& path,
                                        const std::string& scene_file,
                                        const std::string& json_path) {
  // Built by appending: `"'" + std::string` trips GCC 12's false -Wrestrict (PR 105329).
  std::string where(1, '\'');
  where.append(path.string()).push_back('\'');
  auto fail = [&](const std::string& message) -> void {
    throw SceneError(scene_file, json_path, message);
  };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("environment image not found: " + where);

  auto in = OIIO::ImageInput::open(path.string());
  if (!in) fail("cannot read environment image " + where + ": " + OIIO::geterror());
  const OIIO::ImageSpec spec = in->spec();
  const int width = spec.width, height = spec.height, nch = spec.nchannels;
  if (width <= 0 || height <= 0 || nch <= 0) {
    fail("environment image " + where + " is empty");
  }
  // OpenImageIO also opens volumes (an OpenVDB file is width x height x
  // depth voxels): read as one image, they overran the buffer below.
  if (spec.depth > 1) {
    fail("environment image " + where + " is a volume (" + std::to_string(spec.depth) +
         " slices deep), not a 2D image");
  }
  if (uint64_t(width) * uint64_t(height) > uint64_t(std::numeric_limits<int32_t>::max())) {
    fail("environment image " + where + " is too large");
  }
  // Only the colour channels are needed; grey (+alpha) needs just channel 0.
  const int read_channels = nch >= 3 ? 3 : 1;
  std::vector<float> data(size_t(width) * size_t(height) * size_t(read_channels));
  if (!in->read_image(0, 0, 0, read_channels, OIIO::TypeDesc::FLOAT, data.data())) {
    fail("cannot read environment image " + where + ": " + in->geterror());
  }
  in->close();

  float gamma = 1.f;
  const Encoding encoding = encoding_of(spec, gamma);
  EnvironmentImage image;
  image.width = width;
  image.height = height;
  image.pixels.resize(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      Rgb& px = image.pixels[i];
      for (int c = 0; c < 3; ++c) {
        float v = data[i * size_t(read_channels) + size_t(read_channels == 3 ? c : 0)];
        if (!std::isfinite(v) || v < 0.f) {
          fail("environment image " + where + " has " +
               (std::isnan(v) ? std::string("NaN")
                              : (std::isinf(v) ? std::string("Inf")
                                               : "negative value " + std::to_string(v))) +
               " at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
               channel_name(c) + " (expected finite, non-negative radiance)");
        }
        if (encoding == Encoding::Srgb) v = srgb_to_linear(v);
        if (encoding == Encoding::Gamma) v = std::pow(v, gamma);
        px[c] = v;
      }
    }
  }
  return image;
}

}  // namespace vesper
