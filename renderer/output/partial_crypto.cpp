#include "renderer/output/partial_crypto.h"

#include <algorithm>
#include <set>

#include "renderer/output/partial_checks.h"

namespace vesper::partial_crypto {
namespace {

using partial_checks::fail;
using partial_checks::pixel_count;

// As render.h's kMaxCryptoDepth (output/ does not include render/).
constexpr int kMaxDepth = 200;

void put(std::vector<unsigned char>& out, uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back((unsigned char)((v >> (8 * b)) & 0xff));
}

// Reads the section's uint32s in order; running out is a PartialError.
struct Cursor {
  const unsigned char* data;
  size_t size, at = 0;
  const std::string& source;
  uint32_t next() {
    if (size - at < 4) fail(source, "corrupt: the Cryptomatte section is truncated");
    uint32_t v = 0;
    for (int b = 3; b >= 0; --b) v = (v << 8) | data[at + size_t(b)];
    at += 4;
    return v;
  }
};

// One pixel's ids of one type: distinct, each counted at least once, and no
// more samples than the pixel took.
CryptoIdCounts read_ids(Cursor& c, uint32_t total, size_t pixel) {
  const uint32_t n = c.next();
  if (n > (c.size - c.at) / 8) fail(c.source, "corrupt: the Cryptomatte section is truncated");
  CryptoIdCounts ids(n);
  uint64_t sum = 0;
  for (auto& [bits, count] : ids) {
    bits = c.next();
    count = c.next();
    sum += count;
    if (count == 0)
      fail(c.source, "corrupt: Cryptomatte id with a count of 0 in pixel " + std::to_string(pixel));
  }
  if (sum > total)
    fail(c.source, "corrupt: Cryptomatte counts of pixel " + std::to_string(pixel) + " add up to " +
                       std::to_string(sum) + ", more than its " + std::to_string(total) +
                       " samples");
  std::vector<uint32_t> sorted(n);
  std::transform(ids.begin(), ids.end(), sorted.begin(), [](const auto& e) { return e.first; });
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    fail(c.source, "corrupt: a Cryptomatte id is listed twice in pixel " + std::to_string(pixel));
  return ids;
}

}  // namespace

std::vector<unsigned char> encode(const CryptoFilm& film) {
  std::vector<unsigned char> out;
  const size_t nt = film.types.size();
  for (size_t p = 0; p < film.pixels(); ++p) {
    put(out, film.totals[p]);
    for (size_t t = 0; t < nt; ++t) {
      const CryptoIdCounts& ids = film.ids[p * nt + t];
      put(out, uint32_t(ids.size()));
      for (const auto& [bits, count] : ids) {
        put(out, bits);
        put(out, count);
      }
    }
  }
  return out;
}

nlohmann::json header(const CryptoFilm& film, size_t bytes) {
  return {
      {"depth", film.depth}, {"types", film.types}, {"position", film.position}, {"bytes", bytes}};
}

CryptoFilm parse_header(JsonReader node, const Partial& p, uint64_t& bytes) {
  node.allow_keys({"depth", "types", "position", "bytes"});
  CryptoFilm film;
  film.depth = int(node.integer("depth", 1, kMaxDepth));
  const JsonReader types = node.array("types");
  std::set<std::string> seen;
  for (size_t i = 0; i < types.size(); ++i) {
    const std::string t = types.element(i).as_string();
    if (!seen.insert(t).second) types.element(i).fail("duplicate type '" + t + "'");
    film.types.push_back(t);
  }
  if (film.types.empty()) types.fail("expected at least one type, got an empty array");
  film.position = size_t(node.integer("position", 0, int64_t(p.channels.size())));
  bytes = node.child("bytes").as_uint64();
  for (const std::string& c : crypto_channel_names(film))
    if (std::find(p.channels.begin(), p.channels.end(), c) != p.channels.end())
      node.fail_key("types", "Cryptomatte channel '" + c + "' is also one of the channels");
  return film;
}

void decode(const unsigned char* data, size_t size, const Partial& p, CryptoFilm& film) {
  Cursor c{data, size, 0, p.source};
  const size_t pixels = pixel_count(p), nt = film.types.size();
  film.totals.resize(pixels);
  film.ids.clear();
  film.ids.reserve(pixels * nt);
  for (size_t px = 0; px < pixels; ++px) {
    film.totals[px] = c.next();
    for (size_t t = 0; t < nt; ++t) film.ids.push_back(read_ids(c, film.totals[px], px));
  }
  if (c.at != size)
    fail(p.source, "size mismatch: " + std::to_string(size - c.at) +
                       " unexpected bytes after the Cryptomatte counts");
}

void check(const Partial& p) {
  if (!p.crypto) return;
  const CryptoFilm& f = *p.crypto;
  if (f.pixels() != pixel_count(p) || f.ids.size() != f.pixels() * f.types.size() ||
      f.position > p.channels.size() || f.types.empty() || f.depth < 1 || f.depth > kMaxDepth)
    fail(p.source, "the Cryptomatte counts are not of this image (size, types or position)");
}

}  // namespace vesper::partial_crypto
