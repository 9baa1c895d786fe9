#include "server/frame_noise.h"

#include <OpenImageIO/imageio.h>
#include <spdlog/spdlog.h>

#include <charconv>
#include <optional>
#include <string>

#include "renderer/output/metadata_keys.h"
#include "server/blob_store.h"
#include "server/locked_store.h"

namespace vesper {
namespace {

std::string text_attribute(const OIIO::ImageSpec& spec, const char* key) {
  const OIIO::ParamValue* p = spec.find_attribute(key);
  return p ? p->get_string() : std::string();
}

// vesper writes figures as double attributes (older frames: as text); a
// double's text from get_string() would lose digits, so it is read as is.
std::optional<double> number_attribute(const OIIO::ImageSpec& spec, const char* key) {
  const OIIO::ParamValue* p = spec.find_attribute(key);
  if (p && p->type() == OIIO::TypeDesc::DOUBLE) return *static_cast<const double*>(p->data());
  if (p && (p->type() == OIIO::TypeFloat || p->type() == OIIO::TypeInt))
    return double(p->get_float());
  const std::string text = text_attribute(spec, key);
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

}  // namespace

FrameNoise read_frame_noise(const std::filesystem::path& file) {
  FrameNoise noise;
  // Blobs have no extension: ask the OpenEXR reader itself, which refuses
  // anything else at once (instead of every format trying in turn).
  auto in = OIIO::ImageInput::create("openexr");
  OIIO::ImageSpec spec;
  if (!in || !in->open(file.string(), spec)) {
    OIIO::geterror();  // not an EXR: it says nothing (and no error stays pending)
    return noise;
  }
  noise.noise_reached = number_attribute(spec, metadata_key::kNoiseReached);
  noise.spp_mean = number_attribute(spec, metadata_key::kSppMean);
  noise.stop_reason = text_attribute(spec, metadata_key::kStopReason);
  in->close();
  return noise;
}

int record_frame_noise(LockedStore& store, const BlobStore& blobs) noexcept {
  int recorded = 0;
  try {
    const auto unread = store.with([](JobStore& s) { return s.outputs_without_noise(); });
    for (const JobStore::UnreadOutput& o : unread) {
      std::optional<std::filesystem::path> file;
      try {
        file = blobs.file(o.blob);
      } catch (const std::exception&) {
        // Not a blob name: the output says nothing, like a missing blob.
      }
      const FrameNoise noise = file ? read_frame_noise(*file) : FrameNoise{};
      store.with([&](JobStore& s) { s.record_frame_noise(o.job, o.frame, noise); });
      ++recorded;
    }
  } catch (const std::exception& e) {
    // The frames stay unread and are tried again after the next completion.
    spdlog::error("recording the noise of frame outputs: {}", e.what());
  }
  return recorded;
}

}  // namespace vesper
