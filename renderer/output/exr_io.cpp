#include "renderer/output/exr_io.h"

#include <OpenImageIO/imageio.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <system_error>

#include "renderer/output/exr_encoding.h"
#include "renderer/output/exr_header.h"
#include "renderer/output/metadata_keys.h"

namespace vesper {
namespace {

// The metadata value for `key`, one of `names`; the first (the default) when absent.
template <size_t N>
std::string_view encoding_choice(const LayeredImage& image, const char* key,
                                 const std::array<std::string_view, N>& names,
                                 const std::string& file) {
  const auto it = image.metadata.find(key);
  if (it == image.metadata.end()) return names[0];
  for (std::string_view n : names)
    if (n == it->second) return n;
  std::string known;
  for (std::string_view n : names) known += (known.empty() ? "" : ", ") + std::string(n);
  throw ImageIoError("cannot write " + file + ": metadata '" + key + "': expected one of " + known +
                     ", got '" + it->second + "'");
}

// Clamps the half channels' values into half's finite range, counting them.
uint64_t clamp_for_half(std::vector<float>& pixels, const std::vector<bool>& half, size_t nc) {
  uint64_t clamped = 0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    if (!half[i % nc]) continue;
    float& v = pixels[i];
    if (std::isnan(v)) {
      v = 0.f;
      ++clamped;
    } else if (std::fabs(v) > kHalfMax) {
      v = std::copysign(kHalfMax, v);
      ++clamped;
    }
  }
  return clamped;
}

// The spec with per-channel formats: colour channels half when asked.
OIIO::ImageSpec make_spec(const LayeredImage& image, bool half, std::vector<bool>& half_channels) {
  OIIO::ImageSpec spec(image.width, image.height, int(image.channel_count()),
                       OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  spec.alpha_channel = image.channel_index("A");
  spec.z_channel = -1;
  half_channels.assign(image.channel_count(), false);
  if (!half) return spec;
  const std::vector<std::string> ids = cryptomatte_layer_names(image.metadata);
  spec.channelformats.resize(image.channel_count(), OIIO::TypeDesc::FLOAT);
  for (size_t c = 0; c < image.channel_count(); ++c) {
    half_channels[c] = !keeps_float32(image.channels[c], ids);
    if (half_channels[c]) spec.channelformats[c] = OIIO::TypeDesc::HALF;
  }
  return spec;
}

void write_file(const OIIO::ImageSpec& spec, const float* pixels, const std::string& tmp,
                const std::string& file) {
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) throw ImageIoError("cannot create an OpenEXR writer: " + OIIO::geterror());
  if (!out->open(tmp, spec)) throw ImageIoError("cannot write " + file + ": " + out->geterror());
  const bool ok = out->write_image(OIIO::TypeDesc::FLOAT, pixels);
  const bool closed = out->close();
  if (!ok || !closed) {
    const std::string err = out->geterror();
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw ImageIoError("cannot write " + file + ": " + err);
  }
}

}  // namespace

ExrWriteReport write_exr(const LayeredImage& image, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string file = path.string();
  const bool half =
      encoding_choice(image, metadata_key::kPixelType, kExrPixelTypeNames, file) == "half";
  const std::string_view compression =
      encoding_choice(image, metadata_key::kCompression, kExrCompressionNames, file);
  std::vector<bool> half_channels;
  OIIO::ImageSpec spec = make_spec(image, half, half_channels);
  spec.attribute("compression", std::string(compression));

  ExrWriteReport report;
  std::vector<float> clamped;  // a copy only when half channels need it
  const bool any_half =
      std::find(half_channels.begin(), half_channels.end(), true) != half_channels.end();
  if (any_half) {
    clamped = image.pixels;
    report.half_clamped = clamp_for_half(clamped, half_channels, image.channel_count());
  }
  auto metadata = image.metadata;
  if (report.half_clamped > 0) {
    metadata[metadata_key::kHalfClamped] = std::to_string(report.half_clamped);
    spdlog::warn("{}: {} values beyond the half range (±65504) or not finite were clamped", file,
                 report.half_clamped);
  }
  put_metadata(spec, metadata, file);

  const fs::path tmp = file + ".tmp-" + std::to_string(::getpid());
  write_file(spec, any_half ? clamped.data() : image.pixels.data(), tmp.string(), file);
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw ImageIoError("cannot move the finished image to " + file + ": " + ec.message());
  }
  return report;
}

namespace {

std::unique_ptr<OIIO::ImageInput> open_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw ImageIoError("cannot read " + path.string() + ": " + OIIO::geterror());
  return in;
}

}  // namespace

LayeredImage read_exr(const std::filesystem::path& path) {
  auto in = open_image(path);
  const OIIO::ImageSpec& spec = in->spec();
  LayeredImage img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.channelnames;
  img.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
    throw ImageIoError("cannot read " + path.string() + ": " + in->geterror());
  img.metadata = read_metadata(spec);
  in->close();
  return img;
}

std::map<std::string, std::string> read_exr_metadata(const std::filesystem::path& path) {
  return read_metadata(open_image(path)->spec());
}

}  // namespace vesper
