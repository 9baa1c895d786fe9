// Cryptomatte in partial renders: the per-pixel counts by id travel in the
// partial's Cryptomatte section, and merging partials ranks them exactly as a
// single render does (same channels, same bits, same manifest); a damaged or
// mismatched section is refused naming the file.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "renderer/output/exr_io.h"
#include "renderer/output/partial_io.h"
#include "renderer/render/cryptomatte.h"
#include "renderer/render/frame.h"
#include "renderer/scene/scene_loader.h"
#include "tests/common/crypto_header.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;

namespace vesper::test {
namespace {

// The night room (fog, path layers and the rays_dense variant, rendered after
// the beauty: its channels come after the Crypto ones) with Cryptomatte.
SceneDescription crypto_room(int width, int height, int spp) {
  SceneDescription d = load_scene(fs::path(VESPER_SOURCE_DIR) / "scenes/night-room/scene.json");
  d.film.width = width;
  d.film.height = height;
  d.render.spp = spp;
  d.render.aovs = {Aov::Albedo, Aov::Variance, Aov::Cryptomatte};
  return d;
}

RenderOptions range_options(int begin, int end, int depth) {
  RenderOptions o;
  o.sample_begin = begin;
  o.sample_end = end;
  o.keep_sums = true;
  o.cryptomatte_depth = depth;
  return o;
}

Partial render_partial(const SceneDescription& d, int begin, int end, const std::string& label,
                       int depth = kCryptoDefaultDepth) {
  FrameResult f = render_frame(d, range_options(begin, end, depth));
  return make_partial(f.image, std::move(f.film), d.render.spp, label, std::move(f.crypto));
}

std::map<std::string, std::string> without_time(std::map<std::string, std::string> m) {
  m.erase("vesper:render_seconds");
  return m;
}

// Coverage values strictly between 0 and 1: pixels whose ranking mixes samples.
int fractional_coverages(const LayeredImage& img) {
  int n = 0;
  for (size_t c = 0; c < img.channel_count(); ++c) {
    const std::string& name = img.channels[c];
    if (name.rfind("Crypto", 0) != 0 || (name.back() != 'G' && name.back() != 'A')) continue;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) n += img.at(x, y, c) > 0.f && img.at(x, y, c) < 1.f;
  }
  return n;
}

class PartialCryptomatte : public ::testing::Test {
 protected:
  TempDir temp_{"partial-crypto"};
  fs::path dir_ = temp_.path();
};

TEST_F(PartialCryptomatte, TwoRangesMergeBitwiseToTheSingleRender) {
  const SceneDescription d = crypto_room(32, 24, 13);
  RenderOptions single;  // no sums: the ordinary render of [0, 13)
  const FrameResult full = render_frame(d, single);
  ASSERT_GE(full.image.channel_index("CryptoObject02.A"), 0);
  ASSERT_GE(full.image.channel_index("CryptoMaterial00.R"), 0);
  ASSERT_LT(full.image.channel_index("CryptoMaterial02.A"),
            full.image.channel_index("rays_dense.R"));
  ASSERT_GT(fractional_coverages(full.image), 20);

  std::vector<Partial> parts;
  for (const auto& [b, e] : {std::pair{5, 13}, std::pair{0, 5}}) {
    const fs::path file = dir_ / ("p" + std::to_string(b) + ".vpartial");
    write_partial(render_partial(d, b, e, file.string()), file);
    parts.push_back(read_partial(file));
    ASSERT_TRUE(parts.back().crypto);
    EXPECT_EQ(
        std::count(parts.back().channels.begin(), parts.back().channels.end(), "CryptoObject00.R"),
        0);
  }
  const LayeredImage merged = merge_partials(parts);
  ASSERT_EQ(merged.channels, full.image.channels);
  ASSERT_EQ(merged.pixels.size(), full.image.pixels.size());
  EXPECT_EQ(std::memcmp(merged.pixels.data(), full.image.pixels.data(),
                        merged.pixels.size() * sizeof(float)),
            0);
  EXPECT_EQ(without_time(merged.metadata), without_time(full.image.metadata));
  const auto manifests =
      std::count_if(merged.metadata.begin(), merged.metadata.end(), [](const auto& kv) {
        return kv.first.rfind("cryptomatte/", 0) == 0 && kv.first.ends_with("/manifest");
      });
  EXPECT_EQ(manifests, 2);

  // Through the EXR writer: the same channels, bits and header attributes.
  write_exr(merged, dir_ / "merged.exr");
  write_exr(full.image, dir_ / "single.exr");
  const LayeredImage a = read_exr(dir_ / "merged.exr"), b = read_exr(dir_ / "single.exr");
  ASSERT_EQ(a.channels, b.channels);
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0);
  EXPECT_EQ(without_time(a.metadata), without_time(b.metadata));
  const auto header = crypto_header(dir_ / "single.exr");
  EXPECT_EQ(manifest_count(header), 2);
  EXPECT_EQ(crypto_header(dir_ / "merged.exr"), header);
}

// The ranking is of the summed counts, not of each range's: a merge of
// partials whose own top ids differ still matches the single render (odd depth).
TEST_F(PartialCryptomatte, RanksTheSummedCountsAtAnyDepth) {
  const SceneDescription d = crypto_room(16, 12, 9);
  RenderOptions single;
  single.cryptomatte_depth = 1;
  const LayeredImage full = render_frame(d, single).image;
  EXPECT_EQ(full.channel_index("CryptoObject01.R"), -1);
  std::vector<Partial> parts;
  for (int s = 0; s < 9; ++s)
    parts.push_back(render_partial(d, s, s + 1, "p" + std::to_string(s), 1));
  const LayeredImage merged = merge_partials(parts);
  ASSERT_EQ(merged.channels, full.channels);
  EXPECT_EQ(std::memcmp(merged.pixels.data(), full.pixels.data(), full.pixels.size() * 4), 0);
}

TEST_F(PartialCryptomatte, MismatchedSectionsAreRefusedNamingBothFiles) {
  const SceneDescription d = crypto_room(8, 4, 4);
  const Partial a = render_partial(d, 0, 2, "a.vpartial");
  const Partial deeper = render_partial(d, 2, 4, "b.vpartial", 3);
  Partial none = render_partial(d, 2, 4, "c.vpartial");
  none.crypto.reset();
  for (const Partial* other : std::initializer_list<const Partial*>{&deeper, &none}) {
    try {
      merge_partials({a, *other});
      FAIL() << other->source << " accepted";
    } catch (const PartialError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind(other->source + ": Cryptomatte", 0), 0u) << m;
      EXPECT_NE(m.find("a.vpartial"), std::string::npos) << m;
    }
  }
}

class DamagedCryptoSection : public PartialCryptomatte {
 protected:
  void SetUp() override {
    write_partial(render_partial(crypto_room(8, 4, 4), 0, 4, "good"), dir_ / "good.vpartial");
    std::ifstream in(dir_ / "good.vpartial", std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    bytes_ = ss.str();
    header_end_ = bytes_.find('\n', bytes_.find('\n') + 1);
  }
  // The file with `from` in its header replaced by `to`; the error reading it.
  std::string error_with(const std::string& from, const std::string& to) {
    std::string s = bytes_;
    const size_t at = s.find(from);
    EXPECT_LT(at, header_end_) << from;
    if (at >= header_end_) return "";
    const fs::path p = dir_ / "bad.vpartial";
    std::ofstream(p, std::ios::binary) << s.replace(at, from.size(), to);
    try {
      read_partial(p);
    } catch (const PartialError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(p.string(), 0), 0u) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "accepted with " << to;
    return "";
  }
  // `p` written and read back: the error, or "" if read.
  std::string read_error(const Partial& p) {
    const fs::path file = dir_ / "semantic.vpartial";
    write_partial(p, file);
    try {
      read_partial(file);
    } catch (const PartialError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(file.string(), 0), 0u) << e.what();
      return e.what();
    }
    return "";
  }
  std::string bytes_;
  size_t header_end_ = 0;
};

TEST_F(DamagedCryptoSection, HeaderErrorsNameTheJsonPath) {
  ASSERT_TRUE(read_partial(dir_ / "good.vpartial").crypto);
  EXPECT_NE(error_with("\"depth\":6", "\"dpeth\":6").find("/cryptomatte/dpeth: unknown key"),
            std::string::npos);
  EXPECT_NE(error_with("\"depth\":6", "\"depth\":0").find("/cryptomatte/depth"), std::string::npos);
  const size_t at = bytes_.find("\"position\":");
  ASSERT_LT(at, header_end_);
  const std::string position = bytes_.substr(at, bytes_.find_first_of(",}", at) - at);
  EXPECT_NE(error_with(position, "\"position\":999").find("/cryptomatte/position"),
            std::string::npos);
  EXPECT_NE(error_with("\"types\":[\"CryptoObject\",", "\"types\":[\"CryptoMaterial\",")
                .find("/cryptomatte/types"),
            std::string::npos);
  // A section size that does not add up with the rest of the body.
  const size_t b = bytes_.find("\"cryptomatte\":{\"bytes\":");
  ASSERT_LT(b, header_end_);
  const std::string size = bytes_.substr(b, bytes_.find(',', b) - b);
  EXPECT_NE(error_with(size, "\"cryptomatte\":{\"bytes\":8").find("size mismatch"),
            std::string::npos);
}

TEST_F(DamagedCryptoSection, InconsistentCountsAreCorrupt) {
  Partial p = read_partial(dir_ / "good.vpartial");
  ASSERT_EQ(read_error(p), "");
  Partial over = p;  // more samples on one id than the pixel took
  over.crypto->ids[0] = {{7u, over.crypto->totals[0] + 1}};
  EXPECT_NE(read_error(over).find("corrupt: Cryptomatte counts of pixel 0"), std::string::npos);
  Partial twice = p;
  twice.crypto->ids[1] = {{7u, 1u}, {7u, 1u}};
  EXPECT_NE(read_error(twice).find("listed twice"), std::string::npos);
  Partial zero = p;
  zero.crypto->ids[2] = {{7u, 0u}};
  EXPECT_NE(read_error(zero).find("count of 0"), std::string::npos);
}

}  // namespace
}  // namespace vesper::test
