#include "renderer/render/cryptomatte.h"

#include <algorithm>
#include <bit>
#include <nlohmann/json.hpp>

#include "renderer/output/cryptomatte_id.h"

namespace vesper {
namespace {

// One Cryptomatte type: its name, the id bits of its names, and which of them
// each shape counts toward.
struct CryptoType {
  std::string name;
  std::vector<std::string> names;
  std::vector<uint32_t> bits;      // parallel to names
  std::vector<uint32_t> of_shape;  // shape index -> index into names
};

CryptoType make_type(std::string type, std::vector<std::string> names,
                     std::vector<uint32_t> of_shape) {
  CryptoType t{std::move(type), std::move(names), {}, std::move(of_shape)};
  for (const std::string& n : t.names) t.bits.push_back(crypto_id_bits(n));
  return t;
}

std::vector<CryptoType> crypto_types(const Scene& scene) {
  std::vector<uint32_t> identity(scene.shape_names.size());
  for (size_t i = 0; i < identity.size(); ++i) identity[i] = uint32_t(i);
  return {make_type(kCryptoObject, scene.shape_names, std::move(identity)),
          make_type(kCryptoMaterial, scene.material_names, scene.shape_materials)};
}

// The pixel's counts by id: shapes with the same material add up.
CryptoIdCounts id_counts(const CryptoType& t, const std::vector<CryptoCounts::Entry>& shapes) {
  CryptoIdCounts out;
  for (const CryptoCounts::Entry& e : shapes) {
    const uint32_t bits = t.bits[t.of_shape[e.shape]];
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == bits; });
    if (it == out.end())
      out.emplace_back(bits, e.count);
    else
      it->second += e.count;
  }
  return out;
}

void add_metadata(std::map<std::string, std::string>& meta, const CryptoType& t) {
  const std::string prefix = "cryptomatte/" + crypto_metadata_key(t.name) + "/";
  nlohmann::json manifest = nlohmann::json::object();
  for (size_t i = 0; i < t.names.size(); ++i) manifest[t.names[i]] = crypto_hex(t.bits[i]);
  meta[prefix + "name"] = t.name;
  meta[prefix + "hash"] = "MurmurHash3_32";
  meta[prefix + "conversion"] = "uint32_to_float32";
  meta[prefix + "manifest"] = manifest.dump();
}

std::vector<std::string> channel_names(const std::string& type, int depth) {
  static constexpr const char* kRgba[] = {".R", ".G", ".B", ".A"};
  std::vector<std::string> names;
  for (int layer = 0; layer < (depth + 1) / 2; ++layer) {
    const std::string number = (layer < 10 ? "0" : "") + std::to_string(layer);
    for (const char* c : kRgba) names.push_back(type + number + c);
  }
  return names;
}

}  // namespace

CryptoIdCounts rank_crypto_ids(CryptoIdCounts counts, int depth) {
  std::sort(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  if (counts.size() > size_t(std::max(depth, 0))) counts.resize(size_t(std::max(depth, 0)));
  return counts;
}

void append_cryptomatte(LayeredImage& image, const Scene& scene, const CryptoCounts& counts,
                        int depth) {
  const std::vector<CryptoType> types = crypto_types(scene);
  const size_t per_type = 4 * size_t((depth + 1) / 2);
  const size_t nd = image.channel_count(), n = nd + types.size() * per_type;
  const size_t pixels = size_t(image.width) * size_t(image.height);
  std::vector<float> merged(pixels * n, 0.f);
  for (size_t p = 0; p < pixels; ++p) {
    std::copy_n(&image.pixels[p * nd], nd, &merged[p * n]);
    const double total = std::max<double>(counts.total(p), 1);
    for (size_t t = 0; t < types.size(); ++t) {
      float* out = &merged[p * n + nd + t * per_type];
      for (const auto& [bits, count] :
           rank_crypto_ids(id_counts(types[t], counts.shapes(p)), depth)) {
        *out++ = std::bit_cast<float>(bits);
        *out++ = float(double(count) / total);
      }
    }
  }
  image.pixels = std::move(merged);
  for (const CryptoType& t : types) {
    for (std::string& c : channel_names(t.name, depth)) image.channels.push_back(std::move(c));
    add_metadata(image.metadata, t);
  }
}

}  // namespace vesper
