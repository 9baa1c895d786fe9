// Exact sample sums and partial renders: any split of a frame's sample range
// merges bitwise to the single render; mismatched partials are refused with
// errors that name the files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "renderer/output/exact_sum.h"
#include "renderer/output/partial_io.h"
#include "renderer/render/frame.h"
#include "renderer/scene/scene_loader.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;

namespace vesper::test {
namespace {

// ---------------------------------------------------------------- fixed point

TEST(ExactSum, ConvertsFloatsExactlyDownTo2ToTheMinus41) {
  for (float v : {1.f, -1.f, 0.5f, 3.25f, 1e-3f, -7.123456e5f, 1.1754944e-12f, 0x1p-41f,
                  -0x1.fffffep-41f * 2.f, 0x1.fffffep39f, 1e11f}) {
    EXPECT_EQ(exact_mean(to_fixed(v), 1), v) << v;
    EXPECT_EQ(fixed_to_double(to_fixed(v)), double(v)) << v;
    EXPECT_EQ(to_fixed(-v), -to_fixed(v)) << v;
  }
  EXPECT_EQ(to_fixed(0.f), 0);
  EXPECT_EQ(to_fixed(-0.f), 0);
}

TEST(ExactSum, TruncatesTinyValuesTowardZeroAndClampsHugeOnes) {
  // 2^-64 is the last fixed-point bit; below it values vanish.
  EXPECT_EQ(to_fixed(0x1p-64f), 1);
  EXPECT_EQ(to_fixed(-0x1p-64f), -1);
  EXPECT_EQ(to_fixed(0x1p-65f), 0);
  EXPECT_EQ(to_fixed(0x1.8p-64f), 1);    // 1.5 ulp -> 1 (toward zero)
  EXPECT_EQ(to_fixed(-0x1.8p-64f), -1);  // symmetric
  EXPECT_EQ(to_fixed(std::numeric_limits<float>::denorm_min()), 0);
  const ExactSum clamp = ExactSum(1) << 104;  // 2^40
  EXPECT_EQ(to_fixed(0x1p40f), clamp);
  EXPECT_EQ(to_fixed(3e38f), clamp);
  EXPECT_EQ(to_fixed(-3e38f), -clamp);
  EXPECT_EQ(to_fixed(std::numeric_limits<float>::infinity()), clamp);
  EXPECT_EQ(to_fixed(std::numeric_limits<float>::quiet_NaN()), 0);
  // The largest possible sum of kMaxExactSamples samples does not overflow.
  ExactSum s = 0;
  for (int64_t i = 0; i < 4; ++i) s += clamp * (kMaxExactSamples / 4);
  EXPECT_GT(s, 0);
  EXPECT_EQ(fixed_to_double(s), std::ldexp(1.0, 40) * double(kMaxExactSamples));
}

TEST(ExactSum, SumsDoNotDependOnTheOrder) {
  // Floats of very different magnitudes: float or double sums depend on the
  // order, the fixed-point sum does not.
  const std::vector<float> v{1e9f, 3e-7f, -1e9f, 0.1f, 7.5e5f, 1e-9f, -0.3f, 2.2e-5f};
  ExactSum forward = 0, backward = 0;
  for (float x : v) forward += to_fixed(x);
  for (auto it = v.rbegin(); it != v.rend(); ++it) backward += to_fixed(*it);
  EXPECT_EQ(forward, backward);
  ExactSum split = 0;
  for (size_t k = 0; k < v.size(); k += 3) {
    ExactSum part = 0;
    for (size_t i = k; i < std::min(v.size(), k + 3); ++i) part += to_fixed(v[i]);
    split += part;
  }
  EXPECT_EQ(forward, split);
}

// ---------------------------------------------------------------- frames

// The night room (fog, light groups, path layers, the rays_dense variant) at
// 32x24 with AOVs (the variance and spp too), 13 spp.
SceneDescription small_night_room() {
  SceneDescription d = load_scene(fs::path(VESPER_SOURCE_DIR) / "scenes/night-room/scene.json");
  d.film.width = 32;
  d.film.height = 24;
  d.render.spp = 13;
  d.render.aovs = {Aov::Albedo,         Aov::Normal,   Aov::Depth,    Aov::DiffuseDirect,
                   Aov::VolumeIndirect, Aov::Emission, Aov::Variance, Aov::Spp};
  return d;
}

Partial render_partial(const SceneDescription& d, int begin, int end, const std::string& label,
                       std::optional<uint64_t> seed = {}) {
  RenderOptions o;
  o.sample_begin = begin;
  o.sample_end = end;
  o.keep_sums = true;
  o.layer_variance = true;
  o.seed = seed;
  FrameResult f = render_frame(d, o);
  return make_partial(f.image, std::move(f.film), d.render.spp, label);
}

void expect_same_metadata_but_time(const LayeredImage& a, const LayeredImage& b) {
  auto strip = [](std::map<std::string, std::string> m) {
    m.erase("vesper:render_seconds");
    return m;
  };
  EXPECT_EQ(strip(a.metadata), strip(b.metadata));
}

class PartialFiles : public ::testing::Test {
 protected:
  TempDir temp_{"partial"};
  fs::path dir_ = temp_.path();
};

TEST_F(PartialFiles, FourUnevenRangesMergeBitwiseToTheSingleRender) {
  const SceneDescription d = small_night_room();
  RenderOptions full_options;
  full_options.keep_sums = true;
  full_options.layer_variance = true;
  const FrameResult full = render_frame(d, full_options);
  ASSERT_EQ(full.passes, 2);  // beauty + the rays_dense variant
  for (const char* ch :
       {"R", "A", "albedo.R", "normal.X", "depth.Z", "diffuse_direct.G", "fog.R", "fog.A",
        "candles.B", "lightrays.R", "surfaces.R", "rays_dense.R", "variance.R", "variance.B", "spp",
        "fog.variance.G", "rays_dense.variance.R", "albedo.variance.B"})
    ASSERT_GE(full.image.channel_index(ch), 0) << ch;
  ASSERT_EQ(full.film.sums.size(), full.image.pixels.size());
  // Asking for the sums does not change the image.
  RenderOptions no_sums;
  no_sums.layer_variance = true;
  EXPECT_EQ(render_frame(d, no_sums).image.pixels, full.image.pixels);

  const int cuts[] = {0, 1, 6, 7, 13};
  std::vector<Partial> parts;
  for (int i = 0; i < 4; ++i) {
    const fs::path file = dir_ / ("part" + std::to_string(i) + ".vpartial");
    write_partial(render_partial(d, cuts[i], cuts[i + 1], file.string()), file);
    parts.push_back(read_partial(file));
    EXPECT_EQ(parts.back().source, file.string());
  }
  std::swap(parts[0], parts[2]);  // the order of the inputs does not matter
  std::swap(parts[1], parts[3]);
  const LayeredImage merged = merge_partials(parts);
  EXPECT_EQ(merged.channels, full.image.channels);
  ASSERT_EQ(merged.pixels.size(), full.image.pixels.size());
  EXPECT_EQ(0, std::memcmp(merged.pixels.data(), full.image.pixels.data(),
                           merged.pixels.size() * sizeof(float)));
  expect_same_metadata_but_time(merged, full.image);
  EXPECT_EQ(merged.metadata.at("vesper:spp"), "13");
  EXPECT_EQ(merged.metadata.at("vesper:passes"), "2");

  // The exactness is not free: merging the partials' float means by sample
  // count (what EXR ranges allow) does not reproduce the single render.
  size_t differ = 0;
  std::vector<double> weighted(full.image.pixels.size(), 0.0);
  for (const Partial& p : parts)
    for (size_t k = 0; k < weighted.size(); ++k)
      weighted[k] += double(exact_mean(p.sums[k], p.sample_end - p.sample_begin)) *
                     (p.sample_end - p.sample_begin);
  for (size_t k = 0; k < weighted.size(); ++k)
    differ += float(weighted[k] / 13.0) != full.image.pixels[k];
  EXPECT_GT(differ, 0u);
}

TEST_F(PartialFiles, ASubRangeMergesToTheSingleRenderOfThatRange) {
  const SceneDescription d = small_night_room();
  RenderOptions o;
  o.sample_begin = 3;
  o.sample_end = 9;
  o.layer_variance = true;
  const FrameResult single = render_frame(d, o);
  const LayeredImage merged =
      merge_partials({render_partial(d, 5, 9, "b"), render_partial(d, 3, 5, "a")});
  EXPECT_EQ(merged.pixels, single.image.pixels);
  expect_same_metadata_but_time(merged, single.image);
  EXPECT_EQ(merged.metadata.at("vesper:sample_begin"), "3");
  EXPECT_EQ(merged.metadata.at("vesper:sample_end"), "9");
  EXPECT_EQ(merged.metadata.at("vesper:spp"), "6");
}

// Expects `f` to throw a PartialError whose message contains every needle.
template <typename F>
void expect_error(F f, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const PartialError& e) {
    for (const std::string& n : needles)
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos)
          << "'" << n << "' not in: " << e.what();
  }
}

TEST_F(PartialFiles, MismatchedPartialsAreRefusedNamingTheFiles) {
  SceneDescription d = small_night_room();
  d.film.width = 16;
  d.film.height = 8;
  const Partial a = render_partial(d, 0, 4, "a.vpartial");
  const Partial b = render_partial(d, 4, 13, "b.vpartial");
  EXPECT_NO_THROW(merge_partials({a, b}));
  // Overlap: both files named.
  expect_error(
      [&] {
        merge_partials({a, render_partial(d, 3, 13, "c.vpartial")});
      },
      {"c.vpartial", "a.vpartial", "overlaps", "[3, 13)", "[0, 4)"});
  expect_error([&] { merge_partials({a, a}); }, {"a.vpartial", "overlaps"});
  // Gap.
  expect_error(
      [&] {
        merge_partials({a, render_partial(d, 5, 13, "g.vpartial")});
      },
      {"[4, 5)", "missing", "a.vpartial", "g.vpartial"});
  // Another seed.
  expect_error(
      [&] {
        merge_partials({a, render_partial(d, 4, 13, "s.vpartial", 99)});
      },
      {"s.vpartial", "seed", "a.vpartial"});
  // Another scene.
  SceneDescription other = d;
  other.render.max_depth = 3;
  other.content_hash = "another-scene";
  expect_error(
      [&] {
        merge_partials({a, render_partial(other, 4, 13, "o.vpartial")});
      },
      {"o.vpartial", "scene hash", "a.vpartial"});
  // Another size.
  SceneDescription bigger = d;
  bigger.film.width = 17;
  expect_error(
      [&] {
        merge_partials({a, render_partial(bigger, 4, 13, "w.vpartial")});
      },
      {"w.vpartial", "17x8", "16x8"});
  // Other metadata (the frame number) and renderer version.
  Partial f = b;
  f.metadata["vesper:frame"] = "2";
  expect_error([&] { merge_partials({a, f}); }, {"vesper:frame", "a.vpartial"});
  Partial v = b;
  v.renderer_version = "0.0.1";
  expect_error([&] { merge_partials({a, v}); }, {"renderer version", "0.0.1"});
  expect_error([&] { merge_partials({}); }, {"no partial"});
}

std::string read_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}
void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

TEST_F(PartialFiles, DamagedFilesAreRefusedNamingTheFileAndTheProblem) {
  SceneDescription d = small_night_room();
  d.film.width = 8;
  d.film.height = 4;
  const fs::path good = dir_ / "good.vpartial";
  write_partial(render_partial(d, 0, 2, "good"), good);
  const Partial back = read_partial(good);
  EXPECT_EQ(back.width, 8);
  EXPECT_EQ(back.sample_end, 2);
  EXPECT_EQ(back.frame_spp, 13);
  for (const auto& e : fs::directory_iterator(dir_))  // no temporary left behind
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
  const std::string bytes = read_bytes(good);
  const size_t header_end = bytes.find('\n', bytes.find('\n') + 1);
  ASSERT_NE(header_end, std::string::npos);

  auto damaged = [&](const std::string& name, const std::string& content) {
    const fs::path p = dir_ / name;
    write_bytes(p, content);
    return p;
  };
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = bytes;
    const size_t at = s.find(from);
    EXPECT_LT(at, header_end) << from;
    return s.replace(at, from.size(), to);
  };

  const fs::path t1 = damaged("trunc.vpartial", bytes.substr(0, bytes.size() - 7));
  expect_error([&] { read_partial(t1); }, {t1.string(), "truncated"});
  const fs::path t2 = damaged("trunc2.vpartial", bytes.substr(0, header_end - 10));
  expect_error([&] { read_partial(t2); }, {t2.string(), "truncated"});
  const fs::path m = damaged("magic.vpartial", "P6\n" + bytes.substr(3));
  expect_error([&] { read_partial(m); }, {m.string(), "bad magic"});
  const fs::path exr = damaged("empty.vpartial", "");
  expect_error([&] { read_partial(exr); }, {exr.string(), "bad magic"});
  const fs::path k = damaged("key.vpartial", replaced("\"seed\":", "\"sede\":"));
  expect_error([&] { read_partial(k); }, {k.string(), "unknown key 'sede'"});
  const fs::path w = damaged("width.vpartial", replaced("\"width\":8", "\"width\":9"));
  expect_error([&] { read_partial(w); }, {w.string(), "size mismatch"});
  const fs::path ty = damaged("type.vpartial", replaced("\"height\":4", "\"height\":\"4\""));
  expect_error([&] { read_partial(ty); }, {ty.string(), "/height: expected an integer"});
  const fs::path j = damaged("json.vpartial", replaced("{\"channels\"", "{channels"));
  expect_error([&] { read_partial(j); }, {j.string(), "JSON"});
  const fs::path fv = damaged("format.vpartial", replaced("vesper-partial/2", "vesper-partial/9"));
  expect_error([&] { read_partial(fv); }, {fv.string(), "unsupported format"});
  std::string flipped = bytes;
  flipped[header_end + 20] = char(flipped[header_end + 20] ^ 0x40);
  const fs::path c = damaged("corrupt.vpartial", flipped);
  expect_error([&] { read_partial(c); }, {c.string(), "corrupt"});
  const fs::path extra = damaged("extra.vpartial", bytes + "xx");
  expect_error([&] { read_partial(extra); }, {extra.string(), "size mismatch"});
  expect_error([&] { read_partial(dir_ / "missing.vpartial"); }, {"missing.vpartial"});
}

}  // namespace
}  // namespace vesper::test
