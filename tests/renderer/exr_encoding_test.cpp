// The EXR's encoding: half colour channels (data channels stay float32),
// values beyond half's range clamped and counted, every compression reads back.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "renderer/output/exr_encoding.h"
#include "renderer/output/exr_io.h"
#include "renderer/output/metadata_keys.h"
#include "renderer/scene/scene_loader.h"
#include "tests/common/temp_dir.h"
#include "tests/renderer/minimal_scene.h"

namespace fs = std::filesystem;

namespace vesper::test {
namespace {

const std::vector<std::string> kChannels{
    "R", "G", "B", "A", "fog.R", "fog.G", "fog.B", "depth.Z", "normal.X", "variance.R", "spp"};

// Values of both signs, log-uniform over [2^-10, 2^15]: half's normal range
// (beyond 2^-14), where rounding to nearest errs by at most 2^-11 relatively.
LayeredImage random_image(int w, int h, uint32_t seed) {
  LayeredImage img;
  img.width = w;
  img.height = h;
  img.channels = kChannels;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> exponent(-10, 15);
  std::bernoulli_distribution negative(0.3);
  img.pixels.resize(size_t(w) * size_t(h) * kChannels.size());
  for (float& v : img.pixels) v = float((negative(rng) ? -1 : 1) * std::exp2(exponent(rng)));
  return img;
}

std::vector<OIIO::TypeDesc> channel_formats(const fs::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  std::vector<OIIO::TypeDesc> out;
  for (int c = 0; c < in->spec().nchannels; ++c) out.push_back(in->spec().channelformat(c));
  return out;
}

std::string compression_of(const fs::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  return in->spec().get_string_attribute("compression");
}

LayeredImage with_encoding(LayeredImage img, const char* pixel_type, const char* compression) {
  img.metadata[metadata_key::kPixelType] = pixel_type;
  img.metadata[metadata_key::kCompression] = compression;
  return img;
}

TEST(ExrEncoding, DataChannelsKeepFloat32) {
  for (const char* c : {"R", "A", "fog.G", "albedo.B", "beauty.sub.R"})
    EXPECT_FALSE(keeps_float32(c, {})) << c;
  for (const char* c : {"depth.Z", "normal.X", "spp", "variance.R", "fog.variance.G",
                        "CryptoObject00.R", "cryptomaterial01.A", "id", "motion.U"})
    EXPECT_TRUE(keeps_float32(c, {})) << c;
  // A Cryptomatte layer named in the header, whatever its name.
  EXPECT_TRUE(keeps_float32("objs00.R", {"objs"}));
  EXPECT_FALSE(keeps_float32("objs.R", {"objs"}));
}

TEST(ExrEncoding, HalfShrinksTheFileAndReadsBackWithinHalfPrecision) {
  const TempDir dir("exr");
  const LayeredImage img = random_image(48, 32, 1);
  write_exr(with_encoding(img, "float", "zip"), dir / "float.exr");
  const ExrWriteReport report = write_exr(with_encoding(img, "half", "zip"), dir / "half.exr");
  EXPECT_EQ(report.half_clamped, 0u);
  EXPECT_LT(fs::file_size(dir / "half.exr"), fs::file_size(dir / "float.exr"));

  const std::vector<OIIO::TypeDesc> formats = channel_formats(dir / "half.exr");
  const LayeredImage back = read_exr(dir / "half.exr");
  ASSERT_EQ(back.channels.size(), img.channels.size());
  for (size_t bc = 0; bc < back.channels.size(); ++bc) {
    const std::string& name = back.channels[bc];
    const int c = img.channel_index(name);
    const bool half = !keeps_float32(name, {});
    EXPECT_EQ(formats[bc], half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT) << name;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const float want = img.at(x, y, size_t(c)), got = back.at(x, y, bc);
        if (half)  // round to nearest: half an ulp of an 11-bit significand
          ASSERT_LE(std::fabs(got - want), std::ldexp(std::fabs(want), -11)) << name;
        else
          ASSERT_EQ(got, want) << name;
      }
  }
}

TEST(ExrEncoding, ValuesBeyondHalfAreClampedAndCounted) {
  const TempDir dir("exr");
  LayeredImage img;
  img.width = 6;
  img.height = 1;
  img.channels = {"R", "depth.Z"};
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  img.pixels = {1e5f, 1e6f, -7e4f, 1e6f, inf, 1e6f, nan, 1e6f, 65504.f, 1e6f, -3.f, 1e6f};
  const ExrWriteReport report = write_exr(with_encoding(img, "half", "zip"), dir / "c.exr");
  EXPECT_EQ(report.half_clamped, 4u);  // 1e5, -7e4, inf and NaN; 65504 is half's own
  const LayeredImage back = read_exr(dir / "c.exr");
  EXPECT_EQ(back.metadata.at(metadata_key::kHalfClamped), "4");
  const int r = back.channel_index("R"), z = back.channel_index("depth.Z");
  const std::vector<float> want{65504.f, -65504.f, 65504.f, 0.f, 65504.f, -3.f};
  for (int x = 0; x < 6; ++x) {
    EXPECT_EQ(back.at(x, 0, size_t(r)), want[size_t(x)]) << x;
    EXPECT_EQ(back.at(x, 0, size_t(z)), 1e6f) << "a float32 channel is not clamped";
  }
  // No clamping, no key.
  img.pixels = {1.f, 2.f, 3.f, 4.f, 5.f, 6.f, 7.f, 8.f, 9.f, 10.f, 11.f, 12.f};
  write_exr(with_encoding(img, "half", "zip"), dir / "d.exr");
  EXPECT_EQ(read_exr(dir / "d.exr").metadata.count(metadata_key::kHalfClamped), 0u);
}

// Lossless codecs give back the float image bit for bit; dwaa quantises the
// R, G, B channels (float ones too) and leaves the others exact.
TEST(ExrEncoding, EveryCompressionReadsBack) {
  const TempDir dir("exr");
  LayeredImage img = random_image(32, 32, 2);
  for (float& v : img.pixels) v = std::fabs(v) / 32768.f;  // colour-like: [2^-25, 1]
  for (std::string_view name : kExrCompressionNames) {
    const fs::path file = dir / (std::string(name) + ".exr");
    write_exr(with_encoding(img, "float", std::string(name).c_str()), file);
    EXPECT_EQ(compression_of(file), name);
    const LayeredImage back = read_exr(file);
    double sq = 0, count = 0;
    for (size_t bc = 0; bc < back.channels.size(); ++bc) {
      const size_t c = size_t(img.channel_index(back.channels[bc]));
      const char last = back.channels[bc].back();
      const bool lossy = name == "dwaa" && (last == 'R' || last == 'G' || last == 'B');
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
          const float want = img.at(x, y, c), got = back.at(x, y, bc);
          if (!lossy) {
            ASSERT_EQ(got, want) << name << " " << back.channels[bc];
          }
          sq += (got - want) * (got - want);
          count += 1;
        }
    }
    // dwaa's default level: a loose sanity bound on the RMS error, not a precision claim.
    EXPECT_LE(std::sqrt(sq / count), name == "dwaa" ? 0.02 : 0.0) << name;
  }
}

TEST(ExrEncoding, AnUnknownEncodingIsRefusedAndNothingIsWritten) {
  const TempDir dir("exr");
  LayeredImage img = random_image(4, 4, 3);
  img.metadata[metadata_key::kCompression] = "lzma";
  try {
    write_exr(img, dir / "x.exr");
    FAIL() << "expected an ImageIoError";
  } catch (const ImageIoError& e) {
    EXPECT_NE(std::string(e.what()).find("vesper:compression"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lzma"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(ExrEncoding, TheFilmSaysPixelTypeAndCompression) {
  nlohmann::json doc = minimal_scene();
  EXPECT_EQ(parse_scene(doc, "s.json").film.pixel_type, ExrPixelType::Float);
  EXPECT_EQ(parse_scene(doc, "s.json").film.compression, ExrCompression::Zip);
  doc["film"]["pixel_type"] = "half";
  doc["film"]["compression"] = "dwaa";
  const SceneDescription d = parse_scene(doc, "s.json");
  EXPECT_EQ(d.film.pixel_type, ExrPixelType::Half);
  EXPECT_EQ(d.film.compression, ExrCompression::Dwaa);
  doc["film"]["compression"] = "b44";
  try {
    parse_scene(doc, "s.json");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/film/compression"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesper::test
