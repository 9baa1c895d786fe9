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
#include "renderer/output/partial_checks.h"
#include "renderer/output/partial_crypto.h"
#include "renderer/output/range_metadata.h"
#include "renderer/sampling/sample_streams.h"

namespace vesper {
namespace {

namespace fs = std::filesystem;
using namespace partial_checks;
using nlohmann::json;

constexpr char kMagic[] = "VESPER-PARTIAL\n";
constexpr size_t kMagicSize = sizeof(kMagic) - 1;
constexpr const char* kFormat = "vesper-partial/2";
// Version 1 had no stream sums and no counts (every pixel took the whole range).
constexpr const char* kFormatV1 = "vesper-partial/1";
constexpr size_t kStreams = size_t(kSampleStreams);
constexpr const char* kEncoding = "int128-le-q64";
constexpr size_t kMaxHeaderBytes = size_t(16) << 20;
constexpr int kMaxDimension = 1 << 16;
// zlib's deflate expands at most ~1032:1: a header promising more is corrupt
// (and would otherwise make us allocate what it claims).
constexpr uint64_t kMaxZlibRatio = 1032;

// Metadata keys that render() writes and the partial carries as its own fields.
bool is_range_key(const std::string& k) {
  const auto& keys = metadata_key::kRangeKeys;
  return std::any_of(keys.begin(), keys.end(), [&](const char* r) { return k == r; });
}

// Bytes of the uncompressed body: sums, then stream sums, then counts.
size_t body_bytes(const Partial& p) {
  return pixel_count(p) *
         (p.channels.size() * 16 + kStreams * p.streamed.size() * 16 + kStreams * 4);
}

void append_counts(std::vector<unsigned char>& bytes, const std::vector<uint32_t>& counts) {
  for (uint32_t c : counts)
    for (int b = 0; b < 4; ++b) bytes.push_back((unsigned char)((c >> (8 * b)) & 0xff));
}

std::vector<uint32_t> decode_counts(const unsigned char* bytes, size_t count) {
  std::vector<uint32_t> counts(count);
  for (size_t i = 0; i < count; ++i)
    for (int b = 3; b >= 0; --b) counts[i] = (counts[i] << 8) | bytes[i * 4 + size_t(b)];
  return counts;
}

// The header's stream_channels as channel indices.
std::vector<int> streamed_indices(const Partial& p, const std::vector<std::string>& names) {
  std::vector<int> out;
  for (const std::string& n : names) {
    const auto it = std::find(p.channels.begin(), p.channels.end(), n);
    if (it == p.channels.end())
      fail(p.source, "header: /stream_channels: '" + n + "' is not one of the channels");
    const int c = int(it - p.channels.begin());
    if (std::find(out.begin(), out.end(), c) != out.end())
      fail(p.source, "header: /stream_channels: '" + n + "' is listed twice");
    out.push_back(c);
  }
  return out;
}

// A version-1 partial's counts: every pixel took its whole range.
std::vector<uint32_t> uniform_counts(const Partial& p) {
  std::vector<uint32_t> per_stream(kStreams, 0);
  for (int s = p.sample_begin; s < p.sample_end; ++s)
    ++per_stream[size_t(sample_stream(uint64_t(s)))];
  std::vector<uint32_t> counts(pixel_count(p) * kStreams);
  for (size_t i = 0; i < counts.size(); ++i) counts[i] = per_stream[i % kStreams];
  return counts;
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
Partial parse_header(const json& j, const std::string& label, SumsLayout& sums, bool& version1,
                     std::vector<std::string>& streamed, uint64_t& crypto_bytes) {
  JsonReader h(j, label, "");
  h.expect_object();
  // The format decides what the rest means, so it is checked first.
  const JsonReader format = h.child("format");
  version1 = format.as_string() == kFormatV1;
  if (format.as_string() != kFormat && !version1)
    format.fail("unsupported format '" + format.as_string() + "' (this build reads " + kFormat +
                " and " + kFormatV1 + ")");
  h.allow_keys({"format", "width", "height", "channels", "sample_begin", "sample_end", "frame_spp",
                "seed", "scene_hash", "renderer_version", "nonfinite_samples", "render_seconds",
                "metadata", "sums", "streams", "stream_channels", "cryptomatte"});
  if (!version1) {
    const JsonReader streams = h.child("streams");
    if (streams.as_integer(1, 1 << 16) != int64_t(kStreams))
      streams.fail("this build samples in " + std::to_string(kStreams) + " streams, not " +
                   streams.json().dump());
    const JsonReader names = h.array("stream_channels");
    for (size_t i = 0; i < names.size(); ++i) streamed.push_back(names.element(i).as_string());
  }
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
  if (h.has("cryptomatte"))
    p.crypto = partial_crypto::parse_header(h.object("cryptomatte"), p, crypto_bytes);
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
  if (layout.bytes > uint64_t(compressed.size()) * kMaxZlibRatio + 1024)
    fail(src, "corrupt: " + std::to_string(compressed.size()) +
                  " compressed bytes cannot hold the " + std::to_string(layout.bytes) +
                  " bytes the header promises");
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
std::string header_line(const Partial& p, size_t raw_bytes, size_t compressed_bytes, uint32_t crc,
                        size_t crypto_bytes) {
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
  h["streams"] = kStreams;
  std::vector<std::string> streamed;
  for (int c : p.streamed) streamed.push_back(p.channels[size_t(c)]);
  h["stream_channels"] = streamed;
  if (p.crypto) h["cryptomatte"] = partial_crypto::header(*p.crypto, crypto_bytes);
  h["sums"] = {{"encoding", kEncoding},
               {"compression", "zlib"},
               {"bytes", raw_bytes},
               {"compressed_bytes", compressed_bytes},
               {"crc32", crc}};
  return h.dump() + "\n";
}

}  // namespace

FilmSums Partial::film() const {
  FilmSums f;
  f.width = width;
  f.height = height;
  f.channels = channels;
  f.streamed = streamed;
  f.sums = sums;
  f.stream_sums = stream_sums;
  f.counts = counts;
  return f;
}

Partial make_partial(const LayeredImage& image, FilmSums film, int frame_spp, std::string source,
                     std::optional<CryptoFilm> crypto) {
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
  std::vector<std::string> channels = film.channels;
  if (crypto && crypto->position <= channels.size()) {
    const std::vector<std::string> names = crypto_channel_names(*crypto);
    channels.insert(channels.begin() + std::ptrdiff_t(crypto->position), names.begin(),
                    names.end());
  }
  if (channels != image.channels || film.width != image.width || film.height != image.height)
    fail(p.source, "the film's sums are not of this image (channels or size differ)");
  p.channels = film.channels;
  p.crypto = std::move(crypto);
  p.sums = std::move(film.sums);
  p.streamed = std::move(film.streamed);
  p.stream_sums = std::move(film.stream_sums);
  p.counts = std::move(film.counts);
  check_sums_size(p);
  partial_crypto::check(p);
  return p;
}

void write_partial(const Partial& p, const fs::path& path) {
  check_sums_size(p);
  partial_crypto::check(p);
  std::vector<unsigned char> raw = encode_sums(p.sums);
  const std::vector<unsigned char> streams = encode_sums(p.stream_sums);
  raw.insert(raw.end(), streams.begin(), streams.end());
  append_counts(raw, p.counts);
  const size_t fixed_bytes = raw.size();
  if (p.crypto) {
    const std::vector<unsigned char> crypto = partial_crypto::encode(*p.crypto);
    raw.insert(raw.end(), crypto.begin(), crypto.end());
  }
  uLongf compressed_size = compressBound(uLong(raw.size()));
  std::vector<unsigned char> compressed(compressed_size);
  if (compress2(compressed.data(), &compressed_size, raw.data(), uLong(raw.size()), 6) != Z_OK)
    throw PartialError("cannot write " + path.string() + ": zlib compression failed");
  compressed.resize(compressed_size);
  const std::string header =
      header_line(p, raw.size(), compressed.size(), crc_of(raw), raw.size() - fixed_bytes);

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
  bool version1 = false;
  std::vector<std::string> streamed;
  uint64_t crypto_bytes = 0;
  try {
    const std::string label = src + " header";
    p = parse_header(parse_json(line, label), label, layout, version1, streamed, crypto_bytes);
  } catch (const JsonError& e) {
    throw PartialError(e.what());
  }
  p.source = src;
  p.streamed = streamed_indices(p, streamed);
  const size_t count = sum_count(p);
  const size_t fixed = version1 ? count * 16 : body_bytes(p);
  const size_t expected = fixed + size_t(crypto_bytes);
  if (layout.bytes != expected)
    fail(src,
         "size mismatch: header says " + std::to_string(layout.bytes) + " bytes of sums, but " +
             std::to_string(p.width) + "x" + std::to_string(p.height) + " pixels x " +
             std::to_string(p.channels.size()) + " channels" +
             (version1 ? ""
                       : " with " + std::to_string(p.streamed.size()) +
                             " streamed channels and counts") +
             (p.crypto ? " and " + std::to_string(crypto_bytes) + " of Cryptomatte counts" : "") +
             " make " + std::to_string(expected));
  const std::vector<unsigned char> raw =
      decompress_sums(read_compressed_sums(f, src, layout.compressed_bytes), layout, src);
  p.sums = decode_sums(raw.data(), count);
  if (version1) {
    p.counts = uniform_counts(p);
  } else {
    const size_t streams = pixel_count(p) * kStreams * p.streamed.size();
    p.stream_sums = decode_sums(raw.data() + count * 16, streams);
    p.counts = decode_counts(raw.data() + (count + streams) * 16, pixel_count(p) * kStreams);
  }
  if (p.crypto) partial_crypto::decode(raw.data() + fixed, size_t(crypto_bytes), p, *p.crypto);
  return p;
}

}  // namespace vesper
