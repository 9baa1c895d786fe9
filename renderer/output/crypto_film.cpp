#include "renderer/output/crypto_film.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace vesper {

CryptoIdCounts rank_crypto_ids(CryptoIdCounts counts, int depth) {
  std::sort(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
  if (counts.size() > size_t(std::max(depth, 0))) counts.resize(size_t(std::max(depth, 0)));
  return counts;
}

void CryptoFilm::add(const CryptoFilm& o) {
  if (o.depth != depth || o.types != types || o.position != position || o.pixels() != pixels() ||
      o.ids.size() != ids.size())
    throw std::invalid_argument("Cryptomatte films of different frames cannot be added");
  for (size_t p = 0; p < totals.size(); ++p) totals[p] += o.totals[p];
  for (size_t i = 0; i < ids.size(); ++i)
    for (const auto& [bits, count] : o.ids[i]) {
      auto it = std::find_if(ids[i].begin(), ids[i].end(),
                             [&](const auto& e) { return e.first == bits; });
      if (it == ids[i].end())
        ids[i].emplace_back(bits, count);
      else
        it->second += count;
    }
}

std::vector<std::string> crypto_channel_names(const std::string& type, int depth) {
  static constexpr const char* kRgba[] = {".R", ".G", ".B", ".A"};
  std::vector<std::string> names;
  for (int layer = 0; layer < (depth + 1) / 2; ++layer) {
    const std::string number = (layer < 10 ? "0" : "") + std::to_string(layer);
    for (const char* c : kRgba) names.push_back(type + number + c);
  }
  return names;
}

std::vector<std::string> crypto_channel_names(const CryptoFilm& film) {
  std::vector<std::string> names;
  for (const std::string& t : film.types)
    for (std::string& n : crypto_channel_names(t, film.depth)) names.push_back(std::move(n));
  return names;
}

void append_crypto_channels(LayeredImage& image, const CryptoFilm& film) {
  const size_t per_type = 4 * size_t((film.depth + 1) / 2);
  const size_t nt = film.types.size(), added = nt * per_type;
  const size_t nd = image.channel_count(), n = nd + added, at = film.position;
  const size_t pixels = size_t(image.width) * size_t(image.height);
  if (at > nd || film.pixels() != pixels || film.ids.size() != pixels * nt)
    throw std::invalid_argument("the Cryptomatte film is not of this image");
  std::vector<float> merged(pixels * n, 0.f);
  for (size_t p = 0; p < pixels; ++p) {
    const float* in = &image.pixels[p * nd];
    std::copy_n(in, at, &merged[p * n]);
    std::copy_n(in + at, nd - at, &merged[p * n + at + added]);
    const double total = std::max<double>(film.totals[p], 1);
    for (size_t t = 0; t < nt; ++t) {
      float* out = &merged[p * n + at + t * per_type];
      for (const auto& [bits, count] : rank_crypto_ids(film.ids[p * nt + t], film.depth)) {
        *out++ = std::bit_cast<float>(bits);
        *out++ = float(double(count) / total);
      }
    }
  }
  image.pixels = std::move(merged);
  const std::vector<std::string> names = crypto_channel_names(film);
  image.channels.insert(image.channels.begin() + std::ptrdiff_t(at), names.begin(), names.end());
}

}  // namespace vesper
