#pragma once
// How an EXR's pixels are stored: the film's pixel type and compression
// (scene `film.pixel_type`, `film.compression`, `vesper render --half`).
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vesper {

enum class ExrPixelType { Float, Half };
inline constexpr std::array<std::string_view, 2> kExrPixelTypeNames{"float", "half"};

// OpenImageIO's names for OpenEXR's codecs; dwaa at its default level (45).
enum class ExrCompression { Zip, Piz, Dwaa, None };
inline constexpr std::array<std::string_view, 4> kExrCompressionNames{"zip", "piz", "dwaa", "none"};

// The largest finite half: colour values beyond are clamped (and counted).
inline constexpr float kHalfMax = 65504.f;

// Whether a channel stays float32 in a half image: data that needs the
// precision, not colour. Colour is R, G, B, A and <layer>.R/G/B/A; a layer
// is data when one of its parts is `variance` (the variance AOV and layer
// variances), when it is Cryptomatte's (its name starts with "crypto", any
// case, or is a `cryptomatte/<key>/name` of the header plus two digits), so
// depth.Z, normal.X/Y/Z, spp, variance.R and CryptoObject00.R stay float32.
bool keeps_float32(std::string_view channel, const std::vector<std::string>& id_layer_names);

// The type names of a header's Cryptomatte layers (`cryptomatte/<key>/name`).
template <typename Map>
std::vector<std::string> cryptomatte_layer_names(const Map& metadata) {
  std::vector<std::string> names;
  for (const auto& [k, v] : metadata) {
    const std::string_view key(k);
    if (key.starts_with("cryptomatte/") && key.ends_with("/name")) names.push_back(v);
  }
  return names;
}

}  // namespace vesper
