// read_exr_all_parts(): every part of a multi-part EXR as one layered image,
// the way Nuke's Read node lists the channels of all parts.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <map>

#include "renderer/output/exr_header.h"
#include "renderer/output/exr_io.h"

namespace vesper {
namespace {

struct Part {
  std::vector<std::string> channels;
  std::vector<float> pixels;  // interleaved, the part's channels
};

// A part's channel name in the merged image (exr_io.h says the rule).
std::string merged_name(const std::string& channel, int part, const std::string& part_name) {
  const bool bare = channel.find('.') == std::string::npos;
  if (!bare || part == 0 || part_name.empty() || part_name == "rgba") return channel;
  return part_name + "." + channel;
}

Part read_part(OIIO::ImageInput& in, int part, const std::string& file) {
  const OIIO::ImageSpec& spec = in.spec();
  Part p;
  p.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
  if (!in.read_image(part, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, p.pixels.data()))
    throw ImageIoError("cannot read " + file + " (part " + std::to_string(part) +
                       "): " + in.geterror());
  const std::string name = spec.get_string_attribute("oiio:subimagename");
  for (const std::string& c : spec.channelnames) p.channels.push_back(merged_name(c, part, name));
  return p;
}

void check_same_window(const OIIO::ImageSpec& first, const OIIO::ImageSpec& spec, int part,
                       const std::string& file) {
  if (spec.x == first.x && spec.y == first.y && spec.width == first.width &&
      spec.height == first.height)
    return;
  throw ExrPartsError(file + ": part " + std::to_string(part) + " is " +
                      std::to_string(spec.width) + "x" + std::to_string(spec.height) + " at (" +
                      std::to_string(spec.x) + ", " + std::to_string(spec.y) + "), part 0 is " +
                      std::to_string(first.width) + "x" + std::to_string(first.height) + " at (" +
                      std::to_string(first.x) + ", " + std::to_string(first.y) +
                      "): the parts must cover the same pixels");
}

// Interleaves the parts' pixels into one image's.
void interleave(const std::vector<Part>& parts, LayeredImage& img) {
  const size_t pixels = size_t(img.width) * size_t(img.height), nc = img.channel_count();
  img.pixels.resize(pixels * nc);
  size_t first = 0;
  for (const Part& p : parts) {
    const size_t pc = p.channels.size();
    for (size_t i = 0; i < pixels; ++i)
      for (size_t c = 0; c < pc; ++c) img.pixels[i * nc + first + c] = p.pixels[i * pc + c];
    first += pc;
  }
}

}  // namespace

LayeredImage read_exr_all_parts(const std::filesystem::path& path) {
  const std::string file = path.string();
  auto in = OIIO::ImageInput::open(file);
  if (!in) throw ImageIoError("cannot read " + file + ": " + OIIO::geterror());
  const OIIO::ImageSpec first = in->spec();
  LayeredImage img;
  img.width = first.width;
  img.height = first.height;
  img.metadata = read_metadata(first);
  std::vector<Part> parts;
  std::map<std::string, int> part_of;  // channel -> the part that gave it
  const int count = std::max(1, first.get_int_attribute("oiio:subimages", 1));
  for (int part = 0; part < count; ++part) {
    if (!in->seek_subimage(part, 0))
      throw ImageIoError("cannot read " + file + " (part " + std::to_string(part) +
                         "): " + in->geterror());
    check_same_window(first, in->spec(), part, file);
    parts.push_back(read_part(*in, part, file));
    for (const std::string& c : parts.back().channels) {
      const auto [it, fresh] = part_of.emplace(c, part);
      if (!fresh)
        throw ExrPartsError(file + ": parts " + std::to_string(it->second) + " and " +
                            std::to_string(part) + " both give the channel '" + c +
                            "'; a channel must come from one part");
      img.channels.push_back(c);
    }
  }
  interleave(parts, img);
  return img;
}

}  // namespace vesper
