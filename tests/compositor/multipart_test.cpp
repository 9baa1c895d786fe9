// `vesper comp` reads every part of a multi-part EXR (as Nuke and Blender
// write them): a part's bare channels become `<part>.<channel>`, so recipes
// name its layer; the result equals the single-part file's.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "comp_fixtures.h"
#include "compositor/comp_run.h"
#include "compositor/recipe.h"

using namespace vesper;
using namespace vesper::comptest;
using nlohmann::json;

namespace {

const std::string kConfig = std::string(VESPER_SOURCE_DIR) + "/configs/ocio/config.ocio";

struct PartSpec {
  std::string name;
  std::vector<std::string> source;  // channels of the image
  std::vector<std::string> stored;  // their names in the part
  int width = 0, height = 0;        // 0: the image's
};

// Writes `parts` of `img` as a multi-part EXR with OIIO (one subimage each).
void write_multipart(const LayeredImage& img, const std::vector<PartSpec>& parts,
                     const fs::path& file) {
  std::vector<OIIO::ImageSpec> specs;
  std::vector<std::vector<float>> pixels;
  for (const PartSpec& p : parts) {
    const int w = p.width ? p.width : img.width, h = p.height ? p.height : img.height;
    OIIO::ImageSpec spec(w, h, int(p.stored.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = p.stored;
    spec.full_width = img.width;  // OpenEXR: one display window for all parts
    spec.full_height = img.height;
    spec.attribute("oiio:subimagename", p.name);
    specs.push_back(spec);
    std::vector<float>& px = pixels.emplace_back();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (const std::string& c : p.source)
          px.push_back(img.at(x % img.width, y % img.height, size_t(img.channel_index(c))));
  }
  auto out = OIIO::ImageOutput::create("openexr");
  ASSERT_TRUE(out->supports("multiimage"));
  ASSERT_TRUE(out->open(file.string(), int(specs.size()), specs.data())) << out->geterror();
  for (size_t i = 0; i < specs.size(); ++i) {
    if (i > 0) {
      ASSERT_TRUE(out->open(file.string(), specs[i], OIIO::ImageOutput::AppendSubimage))
          << out->geterror();
    }
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels[i].data())) << out->geterror();
  }
  ASSERT_TRUE(out->close());
}

const std::vector<std::string> kRgba{"R", "G", "B", "A"};

// Nuke's layout: the beauty in the first part ("rgba"), a layer per part,
// fog with bare channel names, lightrays with full ones.
std::vector<PartSpec> nuke_like_parts() {
  return {{"rgba", kRgba, kRgba},
          {"fog", {"fog.R", "fog.G", "fog.B", "fog.A"}, kRgba},
          {"lightrays",
           {"lightrays.R", "lightrays.G", "lightrays.B"},
           {"lightrays.R", "lightrays.G", "lightrays.B"}},
          {"surfaces", {"surfaces.R", "surfaces.G", "surfaces.B"}, {"R", "G", "B"}}};
}

json recipe_for(const std::string& input, const std::string& out) {
  return json{{"inputs", {{"frame", input}}},
              {"layers", json::array({{{"layer", "surfaces"}},
                                      {{"layer", "fog"}, {"mode", "over"}},
                                      {{"layer", "lightrays"}, {"gain", 0.5}},
                                      {{"layer", "beauty"}, {"gain", 0.25}}})},
              {"display", {{"config", kConfig}, {"display", "sRGB"}, {"view", "Standard"}}},
              {"outputs", {{"exr", out}}}};
}

std::string comp_error(const CompRecipe& r) {
  try {
    run_comp(r);
  } catch (const CompError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(CompMultipart, EveryPartIsReadAndTheResultEqualsTheSinglePartFile) {
  ScratchDir dir;
  const LayeredImage img = night_like();
  write_exr(img, dir / "single.exr");
  write_multipart(img, nuke_like_parts(), dir / "multi.exr");

  const LayeredImage parts = read_exr_all_parts(dir / "multi.exr");
  EXPECT_EQ(parts.channels,
            (std::vector<std::string>{"R", "G", "B", "A", "fog.R", "fog.G", "fog.B", "fog.A",
                                      "lightrays.R", "lightrays.G", "lightrays.B", "surfaces.R",
                                      "surfaces.G", "surfaces.B"}));
  write_json(dir / "single.json", recipe_for("single.exr", "single-comp.exr"));
  write_json(dir / "multi.json", recipe_for("multi.exr", "multi-comp.exr"));
  run_comp(load_recipe(dir / "single.json"));
  run_comp(load_recipe(dir / "multi.json"));
  const LayeredImage a = read_exr(dir / "single-comp.exr"), b = read_exr(dir / "multi-comp.exr");
  EXPECT_EQ(a.channels, b.channels);
  EXPECT_EQ(a.pixels, b.pixels);
  // read_exr still reads the first part only.
  EXPECT_EQ(read_exr(dir / "multi.exr").channels, kRgba);
}

TEST(CompMultipart, TwoPartsGivingOneChannelIsAnErrorNamingTheFile) {
  ScratchDir dir;
  std::vector<PartSpec> parts = nuke_like_parts();
  parts.push_back({"more", {"fog.R"}, {"fog.R"}});
  write_multipart(night_like(), parts, dir / "dup.exr");
  write_json(dir / "r.json", recipe_for("dup.exr", "out.exr"));
  const std::string err = comp_error(load_recipe(dir / "r.json"));
  EXPECT_NE(err.find((dir / "dup.exr").string() + ": parts 1 and 4 both give the channel 'fog.R'"),
            std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST(CompMultipart, PartsOfDifferentSizesAreAnError) {
  ScratchDir dir;
  std::vector<PartSpec> parts = nuke_like_parts();
  parts[2].width = 8;
  write_multipart(night_like(), parts, dir / "sizes.exr");
  write_json(dir / "r.json", recipe_for("sizes.exr", "out.exr"));
  const std::string err = comp_error(load_recipe(dir / "r.json"));
  EXPECT_NE(err.find((dir / "sizes.exr").string() + ": part 2 is 8x12"), std::string::npos) << err;
}

}  // namespace
