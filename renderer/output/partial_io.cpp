#include "renderer/output/partial_io.h"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <set>
#include <sstream>
#include <system_error>

#include "common/json_parse.h"
#include "common/json_reader.h"
#include "renderer/output/range_metadata.h"

namespace vesper {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr char kMagic[] = "VESPER-PARTIAL\n";
constexpr size_t kMagicSize = sizeof(kMagic) - 1;
constexpr const char* kFormat = "vesper-partial/1";
constexpr const char* kEncoding = "int128-le-q64";
constexpr size_t kMaxHeaderBytes = size_t(16) << 20;
constexpr int kMaxDimension = 1 << 16;

// Metadata keys that render() writes and the partial carries as its own fields.
bool is_range_key(const std::string& k) {
  const auto& keys = metadata_key::kRangeKeys;
  return std::any_of(keys.begin(), keys.end(), [&](const char* r) { return k == r; });
}

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw PartialError(source + ": " + what);
}

std::string range_text(const Partial& p) {
  return "[" + std::to_string(p.sample_begin) + ", " + std::to_string(p.sample_end) + ")";
}

size_t sum_count(int width, int height, size_t channels) {
  return size_t(width) * size_t(height) * channels;
}

// Two's complement, little endian, 16 bytes per sum.
std::vector<unsigned char> encode_sums(const std::vector<ExactSum>& sums) {
  std::vector<unsigned char> bytes(sums.size() * 16);
  for (size_t i = 0; i < sums.size(); ++i) {
    auto u = static_cast<unsigned __int128>(sums[i]);
    for (int b = 0; b < 16; ++b, u >>= 8) bytes[i * 16 + size_t(b)] = (unsigned char)(u & 0xff);
  }
  return bytes;
}

std::vector<ExactSum> decode_sums(const unsigned char* bytes, size_t count) {
  std::vector<ExactSum> sums(count);
  for (size_t i = 0; i < count; ++i) {
    unsigned __int128 u = 0;
    for (int b = 15; b >= 0; --b) u = (u << 8) | bytes[i * 16 + size_t(b)];
    sums[i] = static_cast<ExactSum>(u);
  }
  return sums;
}

uint32_t crc_of(const std::vector<unsigned char>& bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  size_t done = 0;
  while (done < bytes.size()) {  // crc32 takes uInt lengths
    const size_t n = std::min<size_t>(bytes.size() - done, size_t(1) << 30);
    crc = crc32(crc, bytes.data() + done, uInt(n));
    done += n;
  }
  return uint32_t(crc);
}

// The "sums" object of the header: how the sums that follow it are stored.
struct SumsLayout {
  uint64_t bytes = 0, compressed_bytes = 0, crc32 = 0;
};

// A string field that must be `expected` (a format this build reads).
void expect_supported(const JsonReader& node, const char* what, const char* expected) {
  const std::string got = node.as_string();
  if (got != expected)
    node.fail(std::string("unsupported ") + what + " '" + got + "' (expected " + expected + ")");
}

SumsLayout parse_sums_layout(JsonReader s) {
  s.allow_keys({"encoding", "compression", "bytes", "compressed_bytes", "crc32"});
  expect_supported(s.child("encoding"), "encoding", kEncoding);
  expect_supported(s.child("compression"), "compression", "zlib");
  return {s.child("bytes").as_uint64(), s.child("compressed_bytes").as_uint64(),
          s.child("crc32").as_uint64()};
}

void parse_channels(const JsonReader& channels, Partial& p) {
  std::set<std::string> seen;
  for (size_t i = 0; i < channels.size(); ++i) {
    const JsonReader c = channels.element(i);
    const std::string name = c.as_string();
    if (!seen.insert(name).second) c.fail("duplicate channel '" + name + "'");
    p.channels.push_back(name);
  }
  if (p.channels.empty()) channels.fail("expected at least one channel, got an empty array");
}

void parse_metadata(const JsonReader& meta, Partial& p) {
  for (const auto& [k, v] : meta.json().items()) {
    const JsonReader value(v, meta.file(), meta.key_path(k));
    if (is_range_key(k)) value.fail("'" + k + "' is a header field, not metadata");
    p.metadata[k] = value.as_string(/*allow_empty=*/true);
  }
}

void parse_sample_range(JsonReader& h, Partial& p) {
  p.sample_begin = int(h.integer("sample_begin", 0, std::numeric_limits<int>::max()));
  p.sample_end = int(h.integer("sample_end", 0, std::numeric_limits<int>::max()));
  if (p.sample_end <= p.sample_begin)
    h.fail_key("sample_end", "empty sample range " + range_text(p));
  if (int64_t(p.sample_end) - p.sample_begin > kMaxExactSamples)
    h.fail_key("sample_end", "sample range " + range_text(p) + " longer than " +
                                 std::to_string(kMaxExactSamples) + " samples");
}

// The header line (docs/partial-format.md): everything but the sums. Throws
// JsonError naming `label` and the JSON path of the offending key.
Partial parse_header(const json& j, const std::string& label, SumsLayout& sums) {
  JsonReader h(j, label, "");
  h.expect_object();
  // The format decides what the rest means, so it is checked first.
  const JsonReader format = h.child("format");
  if (format.as_string() != kFormat)
    format.fail("unsupported format '" + format.as_string() + "' (this build reads " + kFormat +
                ")");
  h.allow_keys({"format", "width", "height", "channels", "sample_begin", "sample_end", "frame_spp",
                "seed", "scene_hash", "renderer_version", "nonfinite_samples", "render_seconds",
                "metadata", "sums"});
  Partial p;
  p.width = int(h.integer("width", 1, kMaxDimension));
  p.height = int(h.integer("height", 1, kMaxDimension));
  parse_channels(h.array("channels"), p);
  parse_sample_range(h, p);
  p.frame_spp = int(h.integer("frame_spp", 0, std::numeric_limits<int>::max()));
  p.seed = h.child("seed").as_uint64();
  p.scene_hash = h.child("scene_hash").as_string(/*allow_empty=*/true);
  p.renderer_version = h.child("renderer_version").as_string(/*allow_empty=*/true);
  p.nonfinite_samples = h.child("nonfinite_samples").as_uint64();
  p.render_seconds = h.number("render_seconds");
  parse_metadata(h.object("metadata"), p);
  sums = parse_sums_layout(h.object("sums"));
  return p;
}

// The magic line and the header line; the stream is left at the sums.
std::string read_header_line(std::ifstream& f, const std::string& src) {
  char magic[kMagicSize] = {};
  f.read(magic, std::streamsize(kMagicSize));
  if (size_t(f.gcount()) != kMagicSize || std::memcmp(magic, kMagic, kMagicSize) != 0)
    fail(src, "not a vesper partial render (bad magic: expected the first line 'VESPER-PARTIAL')");
  std::string line;
  if (!std::getline(f, line) || f.eof()) fail(src, "truncated: the header line is incomplete");
  if (line.size() > kMaxHeaderBytes) fail(src, "header line longer than 16 MiB");
  return line;
}

// The rest of the file: exactly the compressed sums.
std::vector<unsigned char> read_compressed_sums(std::ifstream& f, const std::string& src,
                                                uint64_t compressed_bytes) {
  const std::streampos body = f.tellg();
  f.seekg(0, std::ios::end);
  const uint64_t available = uint64_t(f.tellg() - body);
  if (available < compressed_bytes)
    fail(src, "truncated: expected " + std::to_string(compressed_bytes) +
                  " bytes of compressed sums, found " + std::to_string(available));
  if (available > compressed_bytes)
    fail(src, "size mismatch: " + std::to_string(available - compressed_bytes) +
                  " unexpected bytes after the compressed sums");
  std::vector<unsigned char> compressed(compressed_bytes);
  f.seekg(body);
  f.read(reinterpret_cast<char*>(compressed.data()), std::streamsize(compressed.size()));
  if (uint64_t(f.gcount()) != compressed_bytes) fail(src, "read error in the compressed sums");
  return compressed;
}

std::vector<unsigned char> decompress_sums(const std::vector<unsigned char>& compressed,
                                           const SumsLayout& layout, const std::string& src) {
  std::vector<unsigned char> raw(layout.bytes);
  uLongf raw_size = uLongf(layout.bytes);
  const int zr = uncompress(raw.data(), &raw_size, compressed.data(), uLong(compressed.size()));
  if (zr != Z_OK || raw_size != layout.bytes)
    fail(src, "corrupt: the compressed sums do not decompress to " + std::to_string(layout.bytes) +
                  " bytes (zlib: " + (zr == Z_OK ? "short output" : zError(zr)) + ")");
  if (crc_of(raw) != layout.crc32)
    fail(src, "corrupt: CRC-32 of the sums does not match the header");
  return raw;
}

// The header and the compressed sums of one partial.
std::string header_line(const Partial& p, size_t raw_bytes, size_t compressed_bytes, uint32_t crc) {
  json h;
  h["format"] = kFormat;
  h["width"] = p.width;
  h["height"] = p.height;
  h["channels"] = p.channels;
  h["sample_begin"] = p.sample_begin;
  h["sample_end"] = p.sample_end;
  h["frame_spp"] = p.frame_spp;
  h["seed"] = p.seed;
  h["scene_hash"] = p.scene_hash;
  h["renderer_version"] = p.renderer_version;
  h["nonfinite_samples"] = p.nonfinite_samples;
  h["render_seconds"] = p.render_seconds;
  h["metadata"] = p.metadata;
  h["sums"] = {{"encoding", kEncoding},
               {"compression", "zlib"},
               {"bytes", raw_bytes},
               {"compressed_bytes", compressed_bytes},
               {"crc32", crc}};
  return h.dump() + "\n";
}

void check_sums_size(const Partial& p) {
  if (p.sums.size() != sum_count(p.width, p.height, p.channels.size()))
    fail(p.source, "holds " + std::to_string(p.sums.size()) + " sums, expected " +
                       std::to_string(p.width) + "x" + std::to_string(p.height) + "x" +
                       std::to_string(p.channels.size()) + " = " +
                       std::to_string(sum_count(p.width, p.height, p.channels.size())));
}

// `p` must be a partial of the same frame as `ref`; the error names both.
void check_same_frame(const Partial& p, const Partial& ref) {
  auto differ = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
    fail(p.source, what + " " + mine + " differs from " + ref.source + "'s " + theirs +
                       ": not partials of one frame");
  };
  if (p.width != ref.width || p.height != ref.height)
    differ("image size", std::to_string(p.width) + "x" + std::to_string(p.height),
           std::to_string(ref.width) + "x" + std::to_string(ref.height));
  if (p.channels != ref.channels) {
    auto join = [](const std::vector<std::string>& v) {
      std::string s;
      for (const auto& c : v) s += (s.empty() ? "" : ",") + c;
      return s;
    };
    differ("channel list", join(p.channels), join(ref.channels));
  }
  if (p.seed != ref.seed) differ("seed", std::to_string(p.seed), std::to_string(ref.seed));
  if (p.scene_hash != ref.scene_hash)
    differ("scene hash", p.scene_hash, ref.scene_hash + " (a different scene)");
  if (p.renderer_version != ref.renderer_version)
    differ("renderer version", p.renderer_version, ref.renderer_version);
  if (p.frame_spp != ref.frame_spp)
    differ("frame spp", std::to_string(p.frame_spp), std::to_string(ref.frame_spp));
  std::set<std::string> keys;
  for (const auto& [k, v] : p.metadata) keys.insert(k);
  for (const auto& [k, v] : ref.metadata) keys.insert(k);
  for (const std::string& k : keys) {
    const auto a = p.metadata.find(k), b = ref.metadata.find(k);
    const std::string va = a == p.metadata.end() ? "(absent)" : "'" + a->second + "'";
    const std::string vb = b == ref.metadata.end() ? "(absent)" : "'" + b->second + "'";
    if (va != vb) differ("metadata " + k, va, vb);
  }
}

// The partials in sample order; their ranges must tile one contiguous range
// [begin, end) without overlap.
std::vector<size_t> tiling_order(const std::vector<Partial>& parts) {
  std::vector<size_t> order(parts.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return parts[a].sample_begin < parts[b].sample_begin;
  });
  for (size_t i = 1; i < order.size(); ++i) {
    const Partial& prev = parts[order[i - 1]];
    const Partial& next = parts[order[i]];
    if (next.sample_begin < prev.sample_end)
      throw PartialError(next.source + ": sample range " + range_text(next) + " overlaps " +
                         prev.source + "'s " + range_text(prev) +
                         ": a sample would be counted twice");
    if (next.sample_begin > prev.sample_end)
      throw PartialError("samples [" + std::to_string(prev.sample_end) + ", " +
                         std::to_string(next.sample_begin) + ") are missing between " +
                         prev.source + " " + range_text(prev) + " and " + next.source + " " +
                         range_text(next) + ": the ranges must tile one contiguous range");
  }
  return order;
}

}  // namespace

Partial make_partial(const LayeredImage& image, std::vector<ExactSum> sums, int frame_spp,
                     std::string source) {
  Partial p;
  p.source = std::move(source);
  p.width = image.width;
  p.height = image.height;
  p.channels = image.channels;
  p.frame_spp = frame_spp;
  auto key = [&](const char* k) -> const std::string& {
    const auto it = image.metadata.find(k);
    if (it == image.metadata.end()) fail(p.source, std::string("image metadata lacks ") + k);
    return it->second;
  };
  try {
    p.sample_begin = std::stoi(key(metadata_key::kSampleBegin));
    p.sample_end = std::stoi(key(metadata_key::kSampleEnd));
    p.seed = std::stoull(key(metadata_key::kSeed));
    p.nonfinite_samples = std::stoull(key(metadata_key::kNonfiniteSamples));
    p.render_seconds = std::stod(key(metadata_key::kRenderSeconds));
  } catch (const std::logic_error& e) {  // std::stoi & co.
    fail(p.source, std::string("image metadata: bad number: ") + e.what());
  }
  p.scene_hash = key(metadata_key::kSceneHash);
  p.renderer_version = key(metadata_key::kRendererVersion);
  for (const auto& [k, v] : image.metadata)
    if (!is_range_key(k)) p.metadata[k] = v;
  p.sums = std::move(sums);
  check_sums_size(p);
  return p;
}

void write_partial(const Partial& p, const fs::path& path) {
  check_sums_size(p);
  const std::vector<unsigned char> raw = encode_sums(p.sums);
  uLongf compressed_size = compressBound(uLong(raw.size()));
  std::vector<unsigned char> compressed(compressed_size);
  if (compress2(compressed.data(), &compressed_size, raw.data(), uLong(raw.size()), 6) != Z_OK)
    throw PartialError("cannot write " + path.string() + ": zlib compression failed");
  compressed.resize(compressed_size);
  const std::string header = header_line(p, raw.size(), compressed.size(), crc_of(raw));

  const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw PartialError("cannot write " + path.string() + ": cannot create " + tmp.string());
    f.write(kMagic, std::streamsize(kMagicSize));
    f.write(header.data(), std::streamsize(header.size()));
    f.write(reinterpret_cast<const char*>(compressed.data()), std::streamsize(compressed.size()));
    f.flush();
    if (!f) {
      f.close();
      std::error_code ec;
      fs::remove(tmp, ec);
      throw PartialError("cannot write " + path.string() + ": write failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw PartialError("cannot move the finished partial to " + path.string() + ": " +
                       ec.message());
  }
}

Partial read_partial(const fs::path& path) {
  const std::string src = path.string();
  std::ifstream f(path, std::ios::binary);
  if (!f) fail(src, "cannot open for reading");
  const std::string line = read_header_line(f, src);
  Partial p;
  SumsLayout layout;
  try {
    const std::string label = src + " header";
    p = parse_header(parse_json(line, label), label, layout);
  } catch (const JsonError& e) {
    throw PartialError(e.what());
  }
  p.source = src;
  const size_t count = sum_count(p.width, p.height, p.channels.size());
  if (layout.bytes != uint64_t(count) * 16)
    fail(src, "size mismatch: header says " + std::to_string(layout.bytes) +
                  " bytes of sums, but " + std::to_string(p.width) + "x" +
                  std::to_string(p.height) + " pixels x " + std::to_string(p.channels.size()) +
                  " channels x 16 bytes = " + std::to_string(count * 16));
  const std::vector<unsigned char> raw =
      decompress_sums(read_compressed_sums(f, src, layout.compressed_bytes), layout, src);
  p.sums = decode_sums(raw.data(), count);
  return p;
}

LayeredImage merge_partials(const std::vector<Partial>& parts) {
  if (parts.empty()) throw PartialError("merge: no partial renders given");
  const Partial& ref = parts.front();
  for (const Partial& p : parts) {
    check_sums_size(p);
    if (p.sample_end <= p.sample_begin) fail(p.source, "empty sample range " + range_text(p));
    if (&p != &ref) check_same_frame(p, ref);
  }
  const std::vector<size_t> order = tiling_order(parts);
  const int begin = parts[order.front()].sample_begin;
  const int end = parts[order.back()].sample_end;
  const int64_t count = int64_t(end) - begin;
  if (count > kMaxExactSamples)
    throw PartialError("merge: " + std::to_string(count) + " samples per pixel; at most " +
                       std::to_string(kMaxExactSamples) + " fit the exact sums");

  std::vector<ExactSum> total(ref.sums.size(), 0);
  uint64_t nonfinite = 0;
  double seconds = 0;
  for (size_t i : order) {  // integer sums: the order does not matter
    const Partial& p = parts[i];
    for (size_t k = 0; k < total.size(); ++k) total[k] += p.sums[k];
    nonfinite += p.nonfinite_samples;
    seconds += p.render_seconds;
  }

  LayeredImage img;
  img.width = ref.width;
  img.height = ref.height;
  img.channels = ref.channels;
  img.pixels.resize(total.size());
  for (size_t k = 0; k < total.size(); ++k) img.pixels[k] = exact_mean(total[k], count);
  img.metadata = ref.metadata;
  set_range_metadata(img.metadata, {.scene_hash = ref.scene_hash,
                                    .renderer_version = ref.renderer_version,
                                    .spp = int(count),
                                    .sample_begin = begin,
                                    .sample_end = end,
                                    .seed = ref.seed,
                                    .render_seconds = seconds,
                                    .nonfinite_samples = nonfinite});
  return img;
}

}  // namespace vesper
