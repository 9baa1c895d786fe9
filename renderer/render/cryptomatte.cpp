#include "renderer/render/cryptomatte.h"

#include <algorithm>
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

}  // namespace

CryptoFilm append_cryptomatte(LayeredImage& image, const Scene& scene, const CryptoCounts& counts,
                              int depth) {
  const std::vector<CryptoType> types = crypto_types(scene);
  CryptoFilm film;
  film.depth = depth;
  film.position = image.channel_count();
  const size_t pixels = size_t(image.width) * size_t(image.height);
  film.totals.resize(pixels);
  film.ids.reserve(pixels * types.size());
  for (size_t p = 0; p < pixels; ++p) {
    film.totals[p] = counts.total(p);
    for (const CryptoType& t : types) film.ids.push_back(id_counts(t, counts.shapes(p)));
  }
  for (const CryptoType& t : types) {
    film.types.push_back(t.name);
    add_metadata(image.metadata, t);
  }
  append_crypto_channels(image, film);
  return film;
}

}  // namespace vesper
