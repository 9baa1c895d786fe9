#include "renderer/output/exr_io.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <system_error>

#include "renderer/output/metadata_keys.h"

namespace vesper {

void write_exr(const LayeredImage& image, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
  OIIO::ImageSpec spec(image.width, image.height, int(image.channel_count()),
                       OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  spec.alpha_channel = image.channel_index("A");
  spec.z_channel = -1;
  spec.attribute("compression", "zip");
  for (const auto& [k, v] : image.metadata) spec.attribute(k, v);

  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) throw ImageIoError("cannot create an OpenEXR writer: " + OIIO::geterror());
  if (!out->open(tmp.string(), spec))
    throw ImageIoError("cannot write " + path.string() + ": " + out->geterror());
  const bool ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  const bool closed = out->close();
  if (!ok || !closed) {
    const std::string err = out->geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw ImageIoError("cannot write " + path.string() + ": " + err);
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw ImageIoError("cannot move the finished image to " + path.string() + ": " + ec.message());
  }
}

namespace {

std::unique_ptr<OIIO::ImageInput> open_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw ImageIoError("cannot read " + path.string() + ": " + OIIO::geterror());
  return in;
}

std::map<std::string, std::string> vesper_metadata(const OIIO::ImageSpec& spec) {
  std::map<std::string, std::string> out;
  for (const auto& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind(metadata_key::kPrefix, 0) == 0) out[name] = p.get_string();
  }
  return out;
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
  img.metadata = vesper_metadata(spec);
  in->close();
  return img;
}

std::map<std::string, std::string> read_exr_metadata(const std::filesystem::path& path) {
  return vesper_metadata(open_image(path)->spec());
}

}  // namespace vesper
