// merge_partials(): the exact union of partial renders of one frame.
#include <algorithm>
#include <numeric>
#include <optional>
#include <set>

#include "renderer/output/partial_checks.h"
#include "renderer/output/partial_crypto.h"
#include "renderer/output/partial_io.h"
#include "renderer/output/range_metadata.h"

namespace vesper {
namespace {

using namespace partial_checks;

// Metadata that differs between the partials of one frame (metadata_keys.h).
bool is_per_range_figure(const std::string& k) {
  const auto& keys = metadata_key::kPerRangeFigures;
  return std::any_of(keys.begin(), keys.end(), [&](const char* r) { return k == r; });
}

// Both carry Cryptomatte counts of the same depth, types and place, or neither does.
void check_same_crypto(const Partial& p, const Partial& ref) {
  auto text = [](const Partial& x) {
    if (!x.crypto) return std::string("none");
    std::string types;
    for (const std::string& t : x.crypto->types) types += (types.empty() ? "" : ",") + t;
    return types + " of depth " + std::to_string(x.crypto->depth) + " after channel " +
           std::to_string(x.crypto->position);
  };
  const std::string mine = text(p), theirs = text(ref);
  if (mine != theirs)
    fail(p.source, "Cryptomatte " + mine + " differs from " + ref.source + "'s " + theirs +
                       ": not partials of one frame");
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
  check_same_crypto(p, ref);
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
    if (is_per_range_figure(k)) continue;
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

LayeredImage merge_partials(const std::vector<Partial>& parts) {
  if (parts.empty()) throw PartialError("merge: no partial renders given");
  const Partial& ref = parts.front();
  for (const Partial& p : parts) {
    check_sums_size(p);
    partial_crypto::check(p);
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

  FilmSums total = ref.film();
  std::optional<CryptoFilm> crypto = ref.crypto;
  uint64_t nonfinite = ref.nonfinite_samples;
  double seconds = ref.render_seconds;
  std::set<std::string> stop_reasons;
  for (size_t i : order) {  // integer sums: the order does not matter
    const Partial& p = parts[i];
    if (const auto it = p.metadata.find(metadata_key::kStopReason); it != p.metadata.end())
      stop_reasons.insert(it->second);
    if (&p == &ref) continue;
    if (p.streamed != ref.streamed)
      fail(p.source, "streamed channels (for the variance) differ from " + ref.source +
                         "'s: not partials of one frame");
    total.add(p.film());
    if (crypto) crypto->add(*p.crypto);
    nonfinite += p.nonfinite_samples;
    seconds += p.render_seconds;
  }

  LayeredImage img = resolve_image(total);
  if (crypto) append_crypto_channels(img, *crypto);  // as render() does
  img.metadata = ref.metadata;
  set_range_metadata(img.metadata, {.scene_hash = ref.scene_hash,
                                    .renderer_version = ref.renderer_version,
                                    .spp = int(count),
                                    .sample_begin = begin,
                                    .sample_end = end,
                                    .seed = ref.seed,
                                    .render_seconds = seconds,
                                    .nonfinite_samples = nonfinite});
  if (ref.metadata.count(metadata_key::kSppMean)) set_noise_metadata(img.metadata, total);
  if (!stop_reasons.empty()) {
    std::string joined;
    for (const std::string& r : stop_reasons) joined += (joined.empty() ? "" : ",") + r;
    img.metadata[metadata_key::kStopReason] = joined;
  }
  img.metadata.erase(metadata_key::kSamplingPasses);  // per partial, not a frame figure
  return img;
}

}  // namespace vesper
