// Cryptomatte: the coverage decoded from the ranked (id, coverage) channels
// matches the analytic coverage of quads split at known pixel positions, ids
// rank by coverage and the depth keeps the largest, the manifest names every
// id found, and without the AOV nothing changes.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <bit>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "renderer/output/cryptomatte_id.h"
#include "renderer/output/exr_io.h"
#include "renderer/render/cryptomatte.h"
#include "renderer/render/render.h"
#include "scene_fixtures.h"
#include "tests/common/temp_dir.h"

namespace vesper::test {
namespace {

constexpr double kCameraDistance = 4, kFovDegrees = 30;

// A camera looking down -z at the plane z = 0; w x h pixels, box filter.
SceneDescription plane_scene(int w, int h, int spp) {
  SceneDescription d = empty_scene(w, h, spp, 1);
  d.camera.from = {0, 0, kCameraDistance};
  d.camera.to = {0, 0, 0};
  d.camera.fov_degrees = kFovDegrees;
  d.film.filter = FilterType::Box;
  return d;
}

// World x on the plane z = 0 seen at raster x (pixels from the left edge).
double world_x(const SceneDescription& d, double raster_x) {
  const double t = std::tan(kFovDegrees * 0.5 * M_PI / 180.0);
  const double aspect = double(d.film.width) / double(d.film.height);
  const double tan_half_x = aspect >= 1 ? t * aspect : t;
  return (2 * raster_x / d.film.width - 1) * tan_half_x * kCameraDistance;
}

// A named quad on z = 0 spanning raster columns [x0, x1) and every row.
void add_strip(SceneDescription& d, const std::string& name, double x0, double x1,
               uint32_t material) {
  const double a = world_x(d, x0), b = world_x(d, x1);
  add_quad(d, {a, -10, 0}, {b - a, 0, 0}, {0, 20, 0}, material);
  d.shapes.back().name = name;
}

// The same strip as two triangles of a mesh.
void add_mesh_strip(SceneDescription& d, const std::string& name, double x0, double x1,
                    uint32_t material) {
  const double a = world_x(d, x0), b = world_x(d, x1);
  MeshShapeDesc mesh;
  mesh.positions = {{a, -10, 0}, {b, -10, 0}, {b, 10, 0}, {a, 10, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.source = "inline";
  d.shapes.push_back({std::move(mesh), material, name});
}

// The matte of one name: the sum over ranks of the coverage paired with its id.
float matte(const LayeredImage& img, const std::string& type, const std::string& name, int x,
            int y) {
  const float id = crypto_id(name);
  float sum = 0;
  for (int layer = 0;; ++layer) {
    const std::string prefix = type + "0" + std::to_string(layer) + ".";
    const int r = img.channel_index(prefix + "R");
    if (r < 0) break;
    for (int pair = 0; pair < 2; ++pair)
      if (std::bit_cast<uint32_t>(img.at(x, y, size_t(r + 2 * pair))) ==
          std::bit_cast<uint32_t>(id))
        sum += img.at(x, y, size_t(r + 2 * pair + 1));
  }
  return sum;
}

float coverage_sum(const LayeredImage& img, const std::string& type, int x, int y) {
  float sum = 0;
  for (size_t c = 0; c < img.channel_count(); ++c)
    if (img.channels[c].rfind(type, 0) == 0 &&
        (img.channels[c].back() == 'G' || img.channels[c].back() == 'A'))
      sum += img.at(x, y, c);
  return sum;
}

// Columns: "left" (red) [0, 3.5), "right_a" (blue) [3.5, 5), "right_b" (blue,
// a mesh) [5, 6.5), background from 6.5. Column 3 is split half/half between two
// objects, column 6 between an object and the background.
SceneDescription split_scene(int spp) {
  SceneDescription d = plane_scene(8, 4, spp);
  const uint32_t red = add_material(d, "red", DiffuseMaterialDesc{Rgb(0.7f, 0.1f, 0.1f)});
  const uint32_t blue = add_material(d, "blue", DiffuseMaterialDesc{Rgb(0.1f, 0.1f, 0.7f)});
  add_strip(d, "left", -20, 3.5, red);
  add_strip(d, "right_a", 3.5, 5, blue);
  add_mesh_strip(d, "right_b", 5, 6.5, blue);
  return d;
}

RenderResult render_crypto(const SceneDescription& d, int threads = 0, int depth = 6) {
  RenderOptions o;
  o.aovs = std::vector<Aov>{Aov::Cryptomatte};
  o.threads = threads;
  o.cryptomatte_depth = depth;
  return render(build_scene(d), o);
}

// Each sample lands in a half-covered pixel's left half with probability 1/2;
// the count is at worst binomial (stratified samples only do better), so
// |coverage - 1/2| <= z sqrt(1/4 / N) with z = 4.42 (two-sided alpha 1e-5 per pixel).
TEST(Cryptomatte, DecodedMattesMatchAnalyticCoverage) {
  const int spp = 1024;
  const RenderResult r = render_crypto(split_scene(spp));
  const LayeredImage& img = r.image;
  const float bound = float(4.42 * std::sqrt(0.25 / spp));
  const float left[8] = {1, 1, 1, 0.5f, 0, 0, 0, 0};
  const float right_a[8] = {0, 0, 0, 0.5f, 1, 0, 0, 0};
  const float right_b[8] = {0, 0, 0, 0, 0, 1, 0.5f, 0};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const bool split = x == 3 || x == 6;
      const float tol = split ? bound : 0.f;  // whole pixels are exact
      EXPECT_NEAR(matte(img, kCryptoObject, "left", x, y), left[x], tol) << x << "," << y;
      EXPECT_NEAR(matte(img, kCryptoObject, "right_a", x, y), right_a[x], tol) << x;
      EXPECT_NEAR(matte(img, kCryptoObject, "right_b", x, y), right_b[x], tol) << x;
      // Materials: the two blue shapes add up.
      EXPECT_NEAR(matte(img, kCryptoMaterial, "red", x, y), left[x], tol) << x;
      EXPECT_NEAR(matte(img, kCryptoMaterial, "blue", x, y), right_a[x] + right_b[x], tol) << x;
      // Coverage sums to 1 where no background shows, and to the alpha (the
      // share of samples that hit a surface) everywhere.
      const float alpha = img.at(x, y, 3);
      EXPECT_NEAR(coverage_sum(img, kCryptoObject, x, y), alpha, 1e-6f) << x;
      EXPECT_NEAR(coverage_sum(img, kCryptoMaterial, x, y), alpha, 1e-6f) << x;
      if (x < 6) {
        EXPECT_EQ(alpha, 1.f) << x;
      }
    }
  // The split column is not all one side: the coverage is really fractional.
  EXPECT_GT(matte(img, kCryptoObject, "left", 3, 0), 0.25f);
  EXPECT_LT(matte(img, kCryptoObject, "left", 3, 0), 0.75f);
}

std::string attribute(const OIIO::ImageSpec& spec, const std::string& name) {
  return spec.get_string_attribute(name);
}

// Written to EXR: float channels, the required header attributes, and a
// manifest mapping every name to the id found in the pixels.
TEST(Cryptomatte, ExrHasChannelsHeaderAndManifest) {
  TempDir dir("crypto");
  const std::filesystem::path path = dir.path() / "split.exr";
  write_exr(render_crypto(split_scene(64)).image, path);
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec spec = in->spec();
  for (const char* type : {kCryptoObject, kCryptoMaterial}) {
    for (const char* layer : {"00", "01", "02"})
      for (const char* c : {".R", ".G", ".B", ".A"}) {
        const std::string name = std::string(type) + layer + c;
        const auto it = std::find(spec.channelnames.begin(), spec.channelnames.end(), name);
        ASSERT_NE(it, spec.channelnames.end()) << name;
        EXPECT_EQ(spec.channelformat(int(it - spec.channelnames.begin())), OIIO::TypeDesc::FLOAT);
      }
    const std::string key = "cryptomatte/" + crypto_metadata_key(type) + "/";
    EXPECT_EQ(attribute(spec, key + "name"), type);
    EXPECT_EQ(attribute(spec, key + "hash"), "MurmurHash3_32");
    EXPECT_EQ(attribute(spec, key + "conversion"), "uint32_to_float32");
  }
  const LayeredImage img = read_exr(path);
  const auto manifest = [&](const char* type) {
    return nlohmann::json::parse(
        attribute(spec, "cryptomatte/" + crypto_metadata_key(type) + "/manifest"));
  };
  const nlohmann::json objects = manifest(kCryptoObject), materials = manifest(kCryptoMaterial);
  EXPECT_EQ(objects.size(), 3u);
  EXPECT_EQ(materials.size(), 2u);
  // Every id in the pixels is in the manifest, and every manifest entry is in the pixels.
  std::set<uint32_t> listed, found;
  for (const auto* m : {&objects, &materials})
    for (const auto& [name, hex] : m->items()) {
      EXPECT_EQ(hex.get<std::string>(), crypto_hex(crypto_id_bits(name))) << name;
      listed.insert(uint32_t(std::stoul(hex.get<std::string>(), nullptr, 16)));
    }
  for (size_t c = 0; c < img.channel_count(); ++c) {
    const char last = img.channels[c].back();
    if (img.channels[c].rfind("Crypto", 0) != 0 || (last != 'R' && last != 'B')) continue;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        if (img.at(x, y, c + 1) > 0) found.insert(std::bit_cast<uint32_t>(img.at(x, y, c)));
  }
  EXPECT_EQ(found, listed);
}

TEST(Cryptomatte, RanksByCoverageThenId) {
  const CryptoIdCounts ranked = rank_crypto_ids({{9, 3}, {2, 1}, {1, 7}, {5, 3}, {4, 0}}, 3);
  EXPECT_EQ(ranked, (CryptoIdCounts{{1, 7}, {5, 3}, {9, 3}}));
  EXPECT_EQ(rank_crypto_ids({{3, 2}, {1, 2}}, 6), (CryptoIdCounts{{1, 2}, {3, 2}}));
  EXPECT_TRUE(rank_crypto_ids({{3, 2}}, 0).empty());
}

// Eight strips inside one pixel, widths 1..8 (of 36): with depth 6 the six
// widest are kept, in order of width. Adjacent widths differ by 1/36; with N
// samples each share's standard error is below sqrt(1/4 / N) = 0.002 at
// N = 2^16, so the gap is over 9 standard errors of the difference.
TEST(Cryptomatte, DepthKeepsTheLargestInOrder) {
  SceneDescription d = plane_scene(1, 1, 1 << 16);
  const uint32_t m = add_material(d, "m", DiffuseMaterialDesc{});
  // Strip k (width k/36) from the left, in the order 3, 8, 1, 6, 2, 7, 4, 5.
  double x = 0;
  for (int k : {3, 8, 1, 6, 2, 7, 4, 5}) {
    add_strip(d, "w" + std::to_string(k), x, x + k / 36.0, m);
    x += k / 36.0;
  }
  const LayeredImage img = render_crypto(d).image;
  const int r = img.channel_index("CryptoObject00.R");
  ASSERT_GE(r, 0);
  for (int rank = 0; rank < 6; ++rank) {
    const int k = 8 - rank;
    const size_t c = size_t(r + 2 * rank);
    EXPECT_EQ(std::bit_cast<uint32_t>(img.at(0, 0, c)), crypto_id_bits("w" + std::to_string(k)))
        << "rank " << rank;
    EXPECT_NEAR(img.at(0, 0, c + 1), k / 36.0, 4.42 * 0.002) << "rank " << rank;
  }
  EXPECT_EQ(img.channel_index("CryptoObject03.R"), -1);
  // One material: all of the pixel at rank 0, nothing after.
  const int mr = img.channel_index("CryptoMaterial00.R");
  EXPECT_EQ(img.at(0, 0, size_t(mr)), crypto_id("m"));
  EXPECT_EQ(img.at(0, 0, size_t(mr + 1)), 1.f);
  EXPECT_EQ(img.at(0, 0, size_t(mr + 2)), 0.f);
  EXPECT_EQ(img.at(0, 0, size_t(mr + 3)), 0.f);
  // Depth 2: one layer per type.
  const LayeredImage two = render_crypto(d, 0, 2).image;
  EXPECT_GE(two.channel_index("CryptoObject00.A"), 0);
  EXPECT_EQ(two.channel_index("CryptoObject01.R"), -1);
}

TEST(Cryptomatte, SameForAnyThreadCountAndAdaptiveSampling) {
  const SceneDescription d = split_scene(64);
  const LayeredImage one = render_crypto(d, 1).image, four = render_crypto(d, 4).image;
  ASSERT_EQ(one.channels, four.channels);
  EXPECT_EQ(one.pixels, four.pixels);
  // Adaptive sampling: pixels take different counts over several passes; the
  // coverage is over the samples each pixel took.
  RenderOptions o;
  o.aovs = std::vector<Aov>{Aov::Cryptomatte, Aov::Spp};
  o.noise_target = 0.05;
  o.max_spp = 256;
  const LayeredImage a = render(build_scene(small_cornell(16, 16, 8)), o).image;
  const int spp = a.channel_index("spp");
  std::set<float> counts;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      counts.insert(a.at(x, y, size_t(spp)));
      // The ceiling light is not a shape (no id): coverage <= alpha there, = elsewhere.
      const float objects = coverage_sum(a, kCryptoObject, x, y);
      EXPECT_LE(objects, a.at(x, y, 3) + 1e-6f) << x << "," << y;
      EXPECT_NEAR(coverage_sum(a, kCryptoMaterial, x, y), objects, 1e-6f) << x << "," << y;
      if (y >= 4) {  // below the light
        EXPECT_NEAR(objects, a.at(x, y, 3), 1e-6f) << x << "," << y;
      }
      // A share of the pixel's own sample count: a whole number of its samples.
      const double hits = double(objects) * a.at(x, y, size_t(spp));
      EXPECT_NEAR(hits, std::round(hits), 1e-3) << x << "," << y;
    }
  EXPECT_GT(counts.size(), 1u);  // really adaptive
}

// The first surface the camera ray hits, whatever medium lies before it: a
// thick fog in front of everything leaves the mattes bitwise unchanged.
TEST(Cryptomatte, MediaBeforeTheSurfaceAreIgnored) {
  SceneDescription clear = split_scene(64);
  add_light(clear, PointLightDesc{{0, 0, 2}, Rgb(5.f)});
  SceneDescription foggy = clear;
  HomogeneousMediumDesc fog;
  fog.sigma_s = Rgb(2.f);
  fog.sigma_a = Rgb(0.5f);
  MediumDesc& m = foggy.media.emplace_back();
  m.name = "fog";
  m.medium = fog;  // no bounds: the whole scene
  const LayeredImage a = render_crypto(clear).image, b = render_crypto(foggy).image;
  ASSERT_EQ(a.channels, b.channels);
  EXPECT_NE(a.at(0, 0, 0), b.at(0, 0, 0));  // the fog does change the beauty
  for (size_t c = 0; c < a.channel_count(); ++c) {
    if (a.channels[c].rfind("Crypto", 0) != 0) continue;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        ASSERT_EQ(std::bit_cast<uint32_t>(a.at(x, y, c)), std::bit_cast<uint32_t>(b.at(x, y, c)))
            << a.channels[c] << " " << x << "," << y;
  }
}

// Without the AOV: no Crypto channels, no cryptomatte/ attributes, and the
// other channels are bitwise those of the render with it (it takes no samples).
TEST(Cryptomatte, WithoutTheAovNothingIsWritten) {
  const SceneDescription d = small_cornell(24, 16, 8);
  RenderOptions plain;
  plain.aovs = std::vector<Aov>{Aov::Albedo, Aov::Depth};
  RenderOptions crypto = plain;
  crypto.aovs->push_back(Aov::Cryptomatte);
  const LayeredImage a = render(build_scene(d), plain).image;
  const LayeredImage b = render(build_scene(d), crypto).image;
  for (const std::string& c : a.channels) EXPECT_EQ(c.rfind("Crypto", 0), std::string::npos) << c;
  for (const auto& [k, v] : a.metadata) EXPECT_EQ(k.rfind("cryptomatte/", 0), std::string::npos);
  const size_t na = a.channel_count(), nb = b.channel_count();
  ASSERT_EQ(nb, na + 24);  // 3 RGBA layers for each of the two types
  for (size_t c = 0; c < na; ++c) ASSERT_EQ(a.channels[c], b.channels[c]);
  for (size_t p = 0; p < a.pixels.size() / na; ++p)
    for (size_t c = 0; c < na; ++c)
      ASSERT_EQ(std::bit_cast<uint32_t>(a.pixels[p * na + c]),
                std::bit_cast<uint32_t>(b.pixels[p * nb + c]));
  TempDir dir("crypto");
  write_exr(a, dir.path() / "plain.exr");
  auto in = OIIO::ImageInput::open((dir.path() / "plain.exr").string());
  ASSERT_TRUE(in);
  for (const auto& attr : in->spec().extra_attribs)
    EXPECT_EQ(attr.name().string().rfind("cryptomatte", 0), std::string::npos) << attr.name();
}

// A partial render keeps the Cryptomatte counts (partial_cryptomatte_test.cpp
// merges them); a depth outside [1, kMaxCryptoDepth] is refused before rendering.
TEST(Cryptomatte, PartialRendersKeepTheCountsAndBadDepthsAreRefused) {
  const SceneDescription d = split_scene(8);
  RenderOptions o;
  o.aovs = std::vector<Aov>{Aov::Cryptomatte};
  o.keep_sums = true;
  EXPECT_NO_THROW(check_sampling_options(d.render, o));
  const RenderResult r = render(build_scene(d), o);
  ASSERT_TRUE(r.crypto);
  EXPECT_EQ(r.crypto->types, (std::vector<std::string>{kCryptoObject, kCryptoMaterial}));
  EXPECT_EQ(r.crypto->position, r.film.channels.size());
  for (uint32_t total : r.crypto->totals) EXPECT_EQ(total, 8u);
  RenderOptions no_sums;  // an ordinary render keeps nothing
  no_sums.aovs = o.aovs;
  EXPECT_FALSE(render(build_scene(d), no_sums).crypto);
  RenderOptions zero;  // no ranks at all is a mistake
  zero.aovs = std::vector<Aov>{Aov::Cryptomatte};
  zero.cryptomatte_depth = 0;
  EXPECT_THROW(check_sampling_options(d.render, zero), std::invalid_argument);
  zero.cryptomatte_depth = kMaxCryptoDepth + 1;
  EXPECT_THROW(check_sampling_options(d.render, zero), std::invalid_argument);
}

}  // namespace
}  // namespace vesper::test
