// Compositor: layer extraction and listing, add/over maths on known numbers, a
// partition of layers reproducing the beauty composite through grade + display,
// recipe validation (with JSON paths), frame sequences, and failures that leave
// no output behind (library and `vesper comp`).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <string>

#include "comp_fixtures.h"
#include "compositor/comp_run.h"
#include "compositor/grade.h"
#include "compositor/histogram.h"
#include "compositor/layer_mix.h"
#include "compositor/recipe.h"
#include "tests/common/cli_runner.h"

using namespace vesper;
using namespace vesper::comptest;
using nlohmann::json;

namespace {

const std::string kConfig = std::string(VESPER_SOURCE_DIR) + "/configs/ocio/config.ocio";

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const CompError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("(not a CompError) ") + e.what();
  }
  return "(no error)";
}

// A minimal valid recipe for `frame.exr` in `dir`.
json base_recipe() {
  return json{{"inputs", {{"frame", "frame.exr"}}},
              {"layers", json::array({{{"layer", "beauty"}}})},
              {"display", {{"config", kConfig}, {"display", "sRGB"}, {"view", "Standard"}}},
              {"outputs", {{"image", "out/comp.png"}, {"exr", "out/comp.exr"}}}};
}

struct Fixture {
  ScratchDir dir;
  Fixture() {
    write_exr(night_like(), dir / "frame.exr");
    fs::create_directories(dir / "out");
  }
  fs::path recipe(const json& j, const std::string& name = "comp.json") {
    write_json(dir / name, j);
    return dir / name;
  }
};

}  // namespace

// ---------------------------------------------------------------- layers

TEST(LayerMix, ListsBeautyThenSortedLayers) {
  const LayeredImage img = make_layered(
      2, 2,
      {"R", "G", "B", "A", "fog.R", "fog.G", "fog.B", "fog.A", "albedo.R", "albedo.G", "albedo.B",
       "normal.X", "normal.Y", "normal.Z", "depth.Z", "partial.R", "partial.G"},
      [](int, int, size_t) { return 0.f; });
  EXPECT_EQ(list_layers(img),
            (std::vector<std::string>{"beauty", "albedo", "depth", "fog", "normal"}));
}

TEST(LayerMix, ExtractsRgbAndAlphaWithDefaults) {
  const LayeredImage img = night_like(4, 3);
  const RgbaImage fog = extract_layer(img, "fog", "x.exr");
  const RgbaImage rays = extract_layer(img, "lightrays", "x.exr");
  const RgbaImage beauty = extract_layer(img, "beauty", "x.exr");
  const RgbaImage depth = extract_layer(img, "depth", "x.exr");
  ASSERT_EQ(fog.width, 4);
  ASSERT_EQ(fog.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(fog.at(x, y, c), img.at(x, y, size_t(7 + c)));
        EXPECT_EQ(rays.at(x, y, c), img.at(x, y, size_t(11 + c)));
        EXPECT_EQ(beauty.at(x, y, c), img.at(x, y, size_t(c)));
        EXPECT_EQ(depth.at(x, y, c), img.at(x, y, 17));
      }
      EXPECT_EQ(fog.at(x, y, 3), img.at(x, y, 10));  // fog.A
      EXPECT_EQ(rays.at(x, y, 3), 0.f);              // named layer without alpha: 0
      EXPECT_EQ(beauty.at(x, y, 3), 1.f);
    }
}

TEST(LayerMix, MissingLayerListsTheLayersOfTheFile) {
  const LayeredImage img = night_like(2, 2);
  const std::string err = error_of([&] { extract_layer(img, "lightray", "out/night.exr"); });
  EXPECT_NE(err.find("no layer 'lightray' in out/night.exr"), std::string::npos) << err;
  EXPECT_NE(err.find("(layers: beauty, candles, depth, fog, lightrays, surfaces)"),
            std::string::npos)
      << err;
  const std::string err2 = error_of([&] { mix_layers(img, {LayerOp{"nope"}}, "a.exr"); });
  EXPECT_NE(err2.find("no layer 'nope' in a.exr"), std::string::npos) << err2;
}

TEST(LayerMix, AddWithGainTintExposure) {
  // One pixel, two layers with known values.
  const LayeredImage img =
      make_layered(1, 1, {"a.R", "a.G", "a.B", "a.A", "b.R", "b.G", "b.B"}, [](int, int, size_t c) {
        const float v[] = {0.5f, 0.25f, 1.0f, 0.3f, 2.0f, 4.0f, 8.0f};
        return v[c];
      });
  LayerOp a{"a"};
  a.gain = 2.f;
  LayerOp b{"b"};
  b.gain = 0.5f;
  b.tint = Rgb(1.f, 0.5f, 0.25f);
  b.exposure = -1.f;  // x 0.5
  const RgbaImage out = mix_layers(img, {a, b}, "t.exr");
  // a: (1, 0.5, 2); b: (2, 4, 8) * 0.5 * (1, .5, .25) * 0.5 = (0.5, 0.5, 0.5)
  EXPECT_FLOAT_EQ(out.at(0, 0, 0), 1.5f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 1), 1.0f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 2), 2.5f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 3), 0.3f);  // max of the alphas (b has none: 0)
}

TEST(LayerMix, OverUsesTheLayersAlpha) {
  const LayeredImage img = make_layered(
      2, 1, {"R", "G", "B", "A", "fg.R", "fg.G", "fg.B", "fg.A"}, [](int x, int, size_t c) {
        const float bg[] = {1.0f, 0.5f, 0.25f, 1.0f};
        const float fg0[] = {0.2f, 0.4f, 0.6f, 0.75f};  // premultiplied, alpha 0.75
        const float fg1[] = {0.0f, 0.0f, 0.0f, 0.0f};   // transparent
        if (c < 4) return bg[c];
        return x == 0 ? fg0[c - 4] : fg1[c - 4];
      });
  LayerOp fg{"fg"};
  fg.mode = BlendMode::Over;
  fg.gain = 2.f;
  const RgbaImage out = mix_layers(img, {LayerOp{"beauty"}, fg}, "t.exr");
  // x=0: fg*2 + (1-0.75)*bg
  EXPECT_FLOAT_EQ(out.at(0, 0, 0), 0.4f + 0.25f * 1.0f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 1), 0.8f + 0.25f * 0.5f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 2), 1.2f + 0.25f * 0.25f);
  EXPECT_FLOAT_EQ(out.at(0, 0, 3), 0.75f + 0.25f * 1.0f);
  // x=1: a transparent layer leaves the canvas untouched
  EXPECT_FLOAT_EQ(out.at(1, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(out.at(1, 0, 1), 0.5f);
  EXPECT_FLOAT_EQ(out.at(1, 0, 2), 0.25f);
  EXPECT_FLOAT_EQ(out.at(1, 0, 3), 1.0f);
  // over onto an empty canvas: the layer itself (times k)
  const RgbaImage alone = mix_layers(img, {fg}, "t.exr");
  EXPECT_FLOAT_EQ(alone.at(0, 0, 0), 0.4f);
  EXPECT_FLOAT_EQ(alone.at(0, 0, 3), 0.75f);
}

// The sum of a partition of the beauty is the beauty, also after grade and display.
TEST(LayerMix, PartitionReproducesTheBeautyCompositeAfterGradeAndDisplay) {
  const LayeredImage img = night_like(24, 16);
  GradeDesc grade;
  grade.exposure = 0.3f;
  Cdl cdl;
  cdl.slope = Rgb(1.05f, 1.0f, 0.95f);
  cdl.offset = Rgb(0.001f, 0.f, -0.001f);
  cdl.power = Rgb(1.02f, 1.0f, 0.98f);
  cdl.saturation = 0.9f;
  grade.cdl = cdl;
  const Grader grader(grade, DisplayDesc{kConfig, "sRGB", "ACES 1.0 SDR"});
  auto composite = [&](const std::vector<LayerOp>& ops) {
    RgbaImage im = mix_layers(img, ops, "night.exr");
    grader.apply_grade(im);
    grader.apply_display(im);
    return im;
  };
  const RgbaImage beauty = composite({LayerOp{"beauty"}});
  const RgbaImage parts = composite({LayerOp{"surfaces"}, LayerOp{"fog"}});
  const RgbaImage finer =
      composite({LayerOp{"surfaces"}, LayerOp{"lightrays"}, LayerOp{"candles"}});
  double max_diff = 0, max_diff_finer = 0, max_value = 0;
  for (size_t i = 0; i < beauty.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const size_t k = i * 4 + size_t(c);
      max_diff = std::max(max_diff, double(std::fabs(beauty.pixels[k] - parts.pixels[k])));
      max_diff_finer =
          std::max(max_diff_finer, double(std::fabs(beauty.pixels[k] - finer.pixels[k])));
      max_value = std::max(max_value, double(beauty.pixels[k]));
    }
  EXPECT_GT(max_value, 0.2);  // the test image is not black after the display transform
  EXPECT_LE(max_diff, 1e-6);
  EXPECT_LE(max_diff_finer, 1e-6);
  // ... and dropping a part is noticed.
  const RgbaImage missing = composite({LayerOp{"surfaces"}, LayerOp{"lightrays"}});
  double miss = 0;
  for (size_t k = 0; k < beauty.pixels.size(); ++k)
    miss = std::max(miss, double(std::fabs(beauty.pixels[k] - missing.pixels[k])));
  EXPECT_GT(miss, 1e-2);
}

// ---------------------------------------------------------------- recipes

TEST(Recipe, ParsesTheIssueExampleWithRelativePaths) {
  Fixture f;
  json j = base_recipe();
  j["layers"] = json::array({{{"layer", "beauty"}},
                             {{"layer", "lightrays"}, {"gain", 0.8}, {"tint", {1.0, 0.95, 0.85}}},
                             {{"layer", "candles"}, {"exposure", 0.5}, {"mode", "over"}}});
  j["grade"] = {{"exposure", 0.3},
                {"cdl",
                 {{"slope", {1.1, 1.0, 0.9}},
                  {"offset", {0.0, 0.0, 0.01}},
                  {"power", {1.0, 1.0, 1.1}},
                  {"saturation", 0.9}}}};
  j["outputs"]["histogram_plot"] = "out/comp.hist.png";
  j["outputs"]["bit_depth"] = 16;
  const CompRecipe r = load_recipe(f.recipe(j));
  ASSERT_EQ(r.inputs.size(), 1u);
  EXPECT_EQ(r.inputs[0].path, (f.dir.path / "frame.exr").lexically_normal());
  ASSERT_EQ(r.layers.size(), 3u);
  EXPECT_FLOAT_EQ(r.layers[1].op.gain, 0.8f);
  EXPECT_FLOAT_EQ(r.layers[1].op.tint.b, 0.85f);
  EXPECT_FLOAT_EQ(r.layers[2].op.exposure, 0.5f);
  EXPECT_EQ(r.layers[2].op.mode, BlendMode::Over);
  EXPECT_EQ(r.layers[1].json_path, "/layers/1/layer");
  EXPECT_FLOAT_EQ(r.grade.exposure, 0.3f);
  ASSERT_TRUE(r.grade.cdl);
  EXPECT_FLOAT_EQ(r.grade.cdl->saturation, 0.9f);
  EXPECT_EQ(r.outputs.bit_depth, 16);
  EXPECT_EQ(r.outputs.image, f.dir.path / "out/comp.png");
  EXPECT_TRUE(r.frames.empty());
  EXPECT_EQ(default_histogram_path(r.outputs), f.dir.path / "out/comp.hist.json");
}

TEST(Recipe, ValidationErrorsNameTheJsonPath) {
  Fixture f;
  struct Case {
    std::function<void(json&)> edit;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {[](json& j) { j["colour"] = 1; }, "comp.json: /colour: "},
      {[](json& j) { j["layers"][0]["gian"] = 2; }, "comp.json: /layers/0/gian: "},
      {[](json& j) { j["layers"][0]["mode"] = "multiply"; }, "comp.json: /layers/0/mode: "},
      {[](json& j) { j["layers"][0]["gain"] = "loud"; }, "comp.json: /layers/0/gain: "},
      {[](json& j) { j["layers"][0]["input"] = "plate"; }, "comp.json: /layers/0/input: "},
      {[](json& j) { j["layers"][0].erase("layer"); },
       "comp.json: /layers/0: missing key \"layer\""},
      {[](json& j) { j["inputs"]["frame"] = "nothere.exr"; },
       "comp.json: /inputs/frame: no such file"},
      {[](json& j) {
         j["grade"] = {{"cdl", {{"power", {1, 0, 1}}}}};
       },
       "comp.json: /grade/cdl/power/1: expected a number in (0, 100]"},
      {[](json& j) {
         j["grade"] = {{"look_lut", "missing.cube"}};
       },
       "comp.json: /grade/look_lut: no such LUT"},
      {[](json& j) { j["display"]["config"] = "no/config.ocio"; },
       "comp.json: /display/config: no such OCIO config"},
      {[](json& j) { j["outputs"]["image"] = "out/comp.bmp"; },
       "comp.json: /outputs/image: expected a .png"},
      {[](json& j) { j["outputs"]["bit_depth"] = 12; },
       "comp.json: /outputs/bit_depth: expected 8 or 16"},
      {[](json& j) {
         j["outputs"]["image"] = "out/comp.jpg";
         j["outputs"]["bit_depth"] = 16;
       },
       "comp.json: /outputs/bit_depth: JPEG is 8-bit only"},
      {[](json& j) { j["outputs"] = json::object(); },
       "comp.json: /outputs: expected an \"image\" or an \"exr\""},
      {[](json& j) { j["outputs"]["image"] = "nowhere/comp.png"; },
       "comp.json: /outputs/image: the output folder"},
      {[](json& j) { j["outputs"]["image"] = "out/comp.####.png"; },
       "comp.json: /outputs/image: expected no frame pattern"},
      {[](json& j) { j["outputs"]["exr"] = "frame.exr"; },
       "comp.json: /outputs/exr: would overwrite the input"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    json j = base_recipe();
    cases[i].edit(j);
    const fs::path p = f.recipe(j);
    const std::string err = error_of([&] { load_recipe(p); });
    EXPECT_NE(err.find(cases[i].expected), std::string::npos)
        << "case " << i << ": expected '" << cases[i].expected << "' in: " << err;
    EXPECT_EQ(err.find(f.dir.path.string() + "/comp.json"), 0u) << err;  // names the file
  }
  EXPECT_NE(error_of([&] { load_recipe(f.dir / "nope.json"); }).find("nope.json"),
            std::string::npos);
  write_text(f.dir / "bad.json", "{\"inputs\": ");
  // The common JSON parser's wording (as for scenes), with the position.
  EXPECT_NE(error_of([&] { load_recipe(f.dir / "bad.json"); }).find("invalid JSON at line 1"),
            std::string::npos);
}

TEST(Recipe, MissingLayerIsReportedAtItsJsonPathWithTheLayersOfTheFile) {
  Fixture f;
  json j = base_recipe();
  j["layers"].push_back({{"layer", "lightray"}});
  const CompRecipe r = load_recipe(f.recipe(j));
  const std::string err = error_of([&] { run_comp(r); });
  EXPECT_NE(err.find("comp.json: /layers/1/layer: no layer 'lightray' in "), std::string::npos)
      << err;
  EXPECT_NE(err.find("(layers: beauty, candles, depth, fog, lightrays, surfaces)"),
            std::string::npos)
      << err;
  EXPECT_TRUE(files_in(f.dir / "out").empty());
}

TEST(Recipe, LayersDefaultToTheFirstInputAndMayNameAnother) {
  Fixture f;
  LayeredImage plate = night_like();
  for (float& v : plate.pixels) v *= 0.5f;
  write_exr(plate, f.dir / "plate.exr");
  // Written as text so that the key order (first input) is the document's.
  write_text(f.dir / "two.json", R"({
    "inputs": {"main": "frame.exr", "plate": "plate.exr"},
    "layers": [{"layer": "beauty"}, {"layer": "beauty", "input": "plate", "gain": -2}],
    "display": {"config": ")" + kConfig +
                                     R"(", "view": "Standard"},
    "outputs": {"exr": "out/sum.exr"}})");
  const CompRecipe r = load_recipe(f.dir / "two.json");
  EXPECT_EQ(r.layers[0].input, 0u);
  EXPECT_EQ(r.layers[1].input, 1u);
  run_comp(r);
  // frame + (-2) * 0.5 * frame = 0
  const LayeredImage out = read_exr(f.dir / "out/sum.exr");
  ASSERT_EQ(out.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    if (i % 4 != 3) {
      EXPECT_NEAR(out.pixels[i], 0.f, 1e-6f);
    }
  }
}

// ---------------------------------------------------------------- running

TEST(CompRun, WritesImageExrAndHistogramAtomically) {
  Fixture f;
  json j = base_recipe();
  j["layers"].push_back({{"layer", "lightrays"}, {"gain", 0.8}, {"tint", {1.0, 0.95, 0.85}}});
  j["grade"] = {{"exposure", 0.5}};
  j["outputs"]["histogram_plot"] = "out/comp.plot.png";
  const CompRecipe r = load_recipe(f.recipe(j));
  size_t calls = 0;
  const CompReport rep = run_comp(r, [&](size_t d, size_t t) {
    ++calls;
    EXPECT_EQ(d, 1u);
    EXPECT_EQ(t, 1u);
  });
  EXPECT_EQ(calls, 1u);
  ASSERT_EQ(rep.frames.size(), 1u);
  EXPECT_EQ(files_in(f.dir / "out"),
            (std::vector<std::string>{"comp.exr", "comp.hist.json", "comp.plot.png", "comp.png"}));
  // The EXR is the graded scene-linear mix: beauty + 0.8 * tint * lightrays, times 2^0.5.
  const LayeredImage src = night_like();
  const LayeredImage exr = read_exr(f.dir / "out/comp.exr");
  ASSERT_EQ(exr.width, src.width);
  const float tint[3] = {1.0f, 0.95f, 0.85f};
  for (int c = 0; c < 3; ++c) {
    const float expect =
        (src.at(5, 7, size_t(c)) + 0.8f * tint[c] * src.at(5, 7, size_t(11 + c))) * std::exp2(0.5f);
    EXPECT_NEAR(exr.at(5, 7, size_t(c)), expect, 1e-5f * expect);
  }
  // The image is 8-bit RGB, and the histogram JSON counts every pixel.
  auto in = OIIO::ImageInput::open((f.dir / "out/comp.png").string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
  EXPECT_EQ(in->spec().nchannels, 3);
  in->close();
  const json h = json::parse(read_text(f.dir / "out/comp.hist.json"));
  EXPECT_EQ(h["count"].get<uint64_t>(), uint64_t(src.width * src.height));
  EXPECT_EQ(h["format"], "vesper-histogram/1");
  EXPECT_NEAR(h["median"].get<double>(), rep.frames[0].display_histogram.median, 1e-12);
}

TEST(CompRun, SixteenBitPngAndTiffRoundTripTheDisplayValues) {
  Fixture f;
  for (const std::string name : {"out/c16.png", "out/c16.tif"}) {
    json j = base_recipe();
    j["outputs"] = {{"image", name}, {"bit_depth", 16}, {"histogram", "out/h.json"}};
    run_comp(load_recipe(f.recipe(j)));
    // The display values, computed directly.
    const Grader g(GradeDesc{}, DisplayDesc{kConfig, "sRGB", "Standard"});
    RgbaImage disp = mix_layers(night_like(), {LayerOp{"beauty"}}, "x");
    g.apply_grade(disp);
    g.apply_display(disp);
    auto in = OIIO::ImageInput::open((f.dir / name).string());
    ASSERT_TRUE(in) << name;
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT16) << name;
    std::vector<uint16_t> px(size_t(disp.width * disp.height * 3));
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT16, px.data()));
    in->close();
    for (size_t i = 0; i < disp.pixel_count(); ++i)
      for (int c = 0; c < 3; ++c) {
        const float v = std::clamp(disp.pixels[i * 4 + size_t(c)], 0.f, 1.f);
        EXPECT_EQ(px[i * 3 + size_t(c)], uint16_t(std::lround(v * 65535.f)));
      }
    fs::remove_all(f.dir / "out");
    fs::create_directories(f.dir / "out");
  }
}

TEST(CompRun, QuantizeRoundsAndClamps) {
  RgbaImage im(4, 1);
  const float v[4] = {-0.5f, 0.5f / 255.f + 1e-6f, 1.5f, std::nanf("")};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) im.at(x, 0, c) = v[x];
  const auto q = quantize_rgb(im, 8);
  EXPECT_EQ(q[0], 0);
  EXPECT_EQ(q[3], 1);
  EXPECT_EQ(q[6], 255);
  EXPECT_EQ(q[9], 0);
  EXPECT_EQ(quantize_rgb(im, 16)[6], 65535);
}

TEST(CompRun, SequenceOfThreeFramesCompositesToThreeOutputs) {
  ScratchDir dir;
  fs::create_directories(dir / "render");
  fs::create_directories(dir / "out");
  for (int f : {1, 2, 10}) {
    char name[64];
    std::snprintf(name, sizeof name, "render/shot.%04d.exr", f);
    write_exr(night_like(8, 6, 0.5f * float(f)), dir / name);
  }
  write_text(dir / "render/shot.12.exr", "not this one (wrong padding)");
  write_text(dir / "render/shot.0003.exr.tmp-1", "not this one");
  json j = {{"inputs", {{"frame", "render/shot.####.exr"}}},
            {"layers", json::array({{{"layer", "surfaces"}}, {{"layer", "fog"}}})},
            {"display", {{"config", kConfig}, {"view", "ACES 1.0 SDR"}}},
            {"outputs", {{"image", "out/comp.####.png"}, {"exr", "out/comp.####.exr"}}}};
  write_json(dir / "seq.json", j);
  const CompRecipe r = load_recipe(dir / "seq.json");
  EXPECT_EQ(r.frames, (std::vector<long>{1, 2, 10}));
  std::vector<size_t> done;
  const CompReport rep = run_comp(r, [&](size_t d, size_t t) {
    done.push_back(d);
    EXPECT_EQ(t, 3u);
  });
  EXPECT_EQ(done, (std::vector<size_t>{1, 2, 3}));
  ASSERT_EQ(rep.frames.size(), 3u);
  EXPECT_EQ(*rep.frames[2].frame, 10);
  EXPECT_EQ(files_in(dir / "out"),
            (std::vector<std::string>{"comp.0001.exr", "comp.0001.hist.json", "comp.0001.png",
                                      "comp.0002.exr", "comp.0002.hist.json", "comp.0002.png",
                                      "comp.0010.exr", "comp.0010.hist.json", "comp.0010.png"}));
  // Frame by frame: frame 10 is brighter than frame 1.
  EXPECT_GT(rep.frames[2].display_histogram.median, rep.frames[0].display_histogram.median);
  const LayeredImage e2 = read_exr(dir / "out/comp.0002.exr");
  const LayeredImage s2 = night_like(8, 6, 1.0f);
  EXPECT_NEAR(e2.at(3, 3, 0), s2.at(3, 3, 0), 1e-6f);

  // Outputs must carry the same pattern.
  j["outputs"]["image"] = "out/comp.png";
  write_json(dir / "seq.json", j);
  std::string err = error_of([&] { load_recipe(dir / "seq.json"); });
  EXPECT_NE(err.find("seq.json: /outputs/image: the inputs are a frame sequence (####)"),
            std::string::npos)
      << err;
  j["outputs"]["image"] = "out/comp.##.png";
  write_json(dir / "seq.json", j);
  err = error_of([&] { load_recipe(dir / "seq.json"); });
  EXPECT_NE(err.find("/outputs/image: the inputs are a frame sequence"), std::string::npos) << err;
  j["inputs"]["frame"] = "render/none.####.exr";
  write_json(dir / "seq.json", j);
  err = error_of([&] { load_recipe(dir / "seq.json"); });
  EXPECT_NE(err.find("/inputs/frame: no files match the frame pattern"), std::string::npos) << err;
}

TEST(CompRun, FailingFrameLeavesNothingAndEarlierFramesStay) {
  ScratchDir dir;
  fs::create_directories(dir / "out");
  write_exr(night_like(8, 6), dir / "s.0001.exr");
  write_truncated_exr(dir / "s.0002.exr", night_like(8, 6));
  write_json(dir / "r.json", {{"inputs", {{"f", "s.####.exr"}}},
                              {"display", {{"config", kConfig}}},
                              {"outputs",
                               {{"image", "out/c.####.png"},
                                {"exr", "out/c.####.exr"},
                                {"histogram_plot", "out/p.####.png"}}}});
  const std::string err = error_of([&] { run_comp(load_recipe(dir / "r.json")); });
  EXPECT_NE(err.find("s.0002.exr"), std::string::npos) << err;
  EXPECT_EQ(files_in(dir / "out"), (std::vector<std::string>{"c.0001.exr", "c.0001.hist.json",
                                                             "c.0001.png", "p.0001.png"}));
}

TEST(CompRun, BrokenInputsAndColourSettingsFailBeforeWritingAnything) {
  Fixture f;
  write_garbage_exr(f.dir / "garbage.exr");
  write_truncated_exr(f.dir / "half.exr", night_like(64, 64));
  struct Case {
    std::function<void(json&)> edit;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {[](json& j) { j["inputs"]["frame"] = "garbage.exr"; }, "garbage.exr"},
      {[](json& j) { j["inputs"]["frame"] = "half.exr"; }, "half.exr"},
      {[](json& j) { j["display"]["view"] = "Filmic"; }, "Filmic"},
      {[](json& j) { j["display"]["display"] = "P3"; }, "P3"},
  };
  for (const Case& c : cases) {
    json j = base_recipe();
    j["outputs"]["histogram_plot"] = "out/plot.png";
    c.edit(j);
    const std::string err = error_of([&] { run_comp(load_recipe(f.recipe(j))); });
    EXPECT_NE(err.find(c.expected), std::string::npos) << err;
    EXPECT_EQ(err.find("(no error)"), std::string::npos);
    EXPECT_EQ(err.find("(not a CompError)"), std::string::npos) << err;
    EXPECT_TRUE(files_in(f.dir / "out").empty()) << c.expected;
  }
  // A config that exists but is not an OCIO config.
  write_text(f.dir / "broken.ocio", "this: is not [an OCIO config");
  json j = base_recipe();
  j["display"]["config"] = "broken.ocio";
  const std::string err = error_of([&] { run_comp(load_recipe(f.recipe(j))); });
  EXPECT_NE(err.find("broken.ocio"), std::string::npos) << err;
  EXPECT_TRUE(files_in(f.dir / "out").empty());
}

// ---------------------------------------------------------------- vesper comp

class CompCli : public vesper::test::CliTest {
 protected:
  CompCli() : CliTest("comp") {}
  void SetUp() override {
    CliTest::SetUp();
    write_exr(night_like(), dir_ / "in.exr");
    fs::create_directories(dir_ / "out");
  }
  std::string q(const fs::path& p) { return "'" + p.string() + "'"; }
};

TEST_F(CompCli, QuickFlagsWriteImageExrAndHistogram) {
  const auto r =
      run(q(dir_ / "in.exr") + " --layer lightrays:0.8 --layer candles:0.5:over" +
          " --exposure 0.3 --cdl-slope 1.05,1,0.95 --saturation 0.9 --config " + q(kConfig) +
          " --view 'ACES 1.0 SDR' -o " + q(dir_ / "out/c.png") + " --exr " + q(dir_ / "out/c.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find((dir_ / "out/c.png").string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find((dir_ / "out/c.exr").string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find((dir_ / "out/c.hist.json").string()), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("median"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("clipped"), std::string::npos) << r.err;
  EXPECT_EQ(files_in(dir_ / "out"), (std::vector<std::string>{"c.exr", "c.hist.json", "c.png"}));
}

TEST_F(CompCli, RecipeFileRuns) {
  write_json(dir_ / "comp.json",
             {{"inputs", {{"frame", "in.exr"}}},
              {"layers", json::array({{{"layer", "beauty"}}, {{"layer", "fog"}, {"gain", 0.5}}})},
              {"display", {{"config", kConfig}, {"view", "Standard"}}},
              {"outputs", {{"image", "out/c.jpg"}, {"histogram", "out/h.json"}}}});
  const auto r = run(q(dir_ / "comp.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files_in(dir_ / "out"), (std::vector<std::string>{"c.jpg", "h.json"}));
  // Flags do not mix with a recipe.
  const auto mixed = run(q(dir_ / "comp.json") + " --exposure 1");
  EXPECT_EQ(mixed.exit_code, 2);
}

TEST_F(CompCli, ErrorsExitTwoAndLeaveNothingBehind) {
  write_garbage_exr(dir_ / "garbage.exr");
  write_truncated_exr(dir_ / "half.exr", night_like(64, 64));
  const std::string out = " -o " + q(dir_ / "out/c.png") + " --exr " + q(dir_ / "out/c.exr") +
                          " --hist-plot " + q(dir_ / "out/p.png");
  const std::string cfg = " --config " + q(kConfig);
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {q(dir_ / "garbage.exr") + cfg + out, "garbage.exr"},
      {q(dir_ / "half.exr") + cfg + out, "half.exr"},
      {q(dir_ / "missing.exr") + cfg + out, "missing.exr"},
      {q(dir_ / "in.exr") + " --config " + q(dir_ / "no.ocio") + out, "no.ocio"},
      {q(dir_ / "in.exr") + cfg + " --view Filmic" + out, "Filmic"},
      {q(dir_ / "in.exr") + cfg + " --layer lightray:0.8" + out,
       "--layer lightray:0.8: no layer 'lightray'"},
      {q(dir_ / "in.exr") + cfg + " --layer fog:0.8:multiply" + out, "--layer fog:0.8:multiply"},
      {q(dir_ / "in.exr") + cfg + " -o " + q(dir_ / "out/c.bmp"), "-o: expected a .png"},
  };
  for (const Case& c : cases) {
    const auto r = run(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_TRUE(files_in(dir_ / "out").empty()) << c.args;
  }
  // Without --config: $OCIO, else the bundled config.
  const auto r = run(q(dir_ / "in.exr") + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Hostile recipes and grades: a recipe nested 100 000 deep (it overflowed the
// stack) is refused by depth; absurd CDL parameters are refused naming the
// flag; bounded ones that still overflow a bright image to infinity stop the
// frame instead of writing NaN/Inf with exit 0.
TEST_F(CompCli, DeepRecipesAndOverflowingGradesAreRefused) {
  const std::string out = " -o " + q(dir_ / "out/c.png") + " --exr " + q(dir_ / "out/c.exr");
  std::ofstream(dir_ / "deep.json") << std::string(100000, '[') << std::string(100000, ']');
  std::ofstream(dir_ / "deep-object.json")
      << "{\"inputs\": " << std::string(100000, '[') << std::string(100000, ']') << "}";
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {q(dir_ / "deep.json"), "nested deeper than 100 levels"},
      {q(dir_ / "deep-object.json"), "nested deeper than 100 levels"},
      {q(dir_ / "in.exr") + " --cdl-power 3.4e38" + out, "--cdl-power"},
      {q(dir_ / "in.exr") + " --saturation 3.4e38" + out, "--saturation"},
      {q(dir_ / "in.exr") + " --cdl-slope 1e300" + out, "--cdl-slope"},
      {q(dir_ / "in.exr") + " --layer fog:1e300" + out, "--layer fog:1e300"},
      {q(dir_ / "in.exr") + " --layer fog:1000000 --cdl-slope 1000 --cdl-power 100" + out,
       "not finite (NaN or infinity)"},
  };
  for (const Case& c : cases) {
    const auto r = run(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_TRUE(files_in(dir_ / "out").empty()) << c.args;
  }
}

// The shipped night-room recipe is valid and runs (on a synthetic frame with
// the same layers, written to a scratch folder instead of out/).
TEST(Recipe, NightRoomRecipeRuns) {
  ScratchDir dir;
  const fs::path recipe_dir = fs::path(VESPER_SOURCE_DIR) / "scenes/night-room";
  json doc = json::parse(read_text(recipe_dir / "comp.json"));
  write_exr(night_like(), dir / "night-room.exr");
  doc["inputs"]["frame"] = (dir / "night-room.exr").string();
  for (auto& [key, value] : doc["outputs"].items())
    value = (dir / fs::path(value.get<std::string>()).filename()).string();
  const CompRecipe r = parse_recipe(doc, recipe_dir, (recipe_dir / "comp.json").string());
  EXPECT_EQ(r.layers.size(), 3u);
  EXPECT_EQ(r.display.view, "ACES 1.0 SDR");
  run_comp(r);
  EXPECT_EQ(files_in(dir.path),
            (std::vector<std::string>{"night-room.comp.exr", "night-room.comp.hist.json",
                                      "night-room.comp.hist.png", "night-room.comp.png",
                                      "night-room.exr"}));
}

// Identity recipe (beauty only, no grade, view Standard) written as an 8-bit
// PNG equals oiiotool's own OCIO display conversion of the same EXR to 8 bits,
// within one code value (1/255).
TEST(CompRun, IdentityRecipeMatchesOiiotoolOciodisplay) {
  if (std::system("command -v oiiotool >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "oiiotool not installed (openimageio-tools)";
  Fixture f;
  // Brighter than night_like alone, so some values clip at the top.
  LayeredImage img = night_like(32, 24, 3.f);
  write_exr(img, f.dir / "frame.exr");
  for (const std::string view : {"Standard", "ACES 1.0 SDR"}) {
    json j = base_recipe();
    j["display"]["view"] = view;
    j["outputs"] = {{"image", "out/comp.png"}};
    run_comp(load_recipe(f.recipe(j)));
    const fs::path ref = f.dir / "ref.png";
    const std::string cmd = "oiiotool '" + (f.dir / "frame.exr").string() +
                            "' --ch R,G,B --colorconfig '" + kConfig +
                            "' --iscolorspace 'Linear Rec.709 (sRGB)' --ociodisplay sRGB '" + view +
                            "' -d uint8 -o '" + ref.string() + "' >/dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    auto read8 = [](const fs::path& p) {
      auto in = OIIO::ImageInput::open(p.string());
      EXPECT_TRUE(in) << p;
      std::vector<uint8_t> px(size_t(in->spec().width * in->spec().height * 3));
      EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
      in->close();
      return px;
    };
    const auto mine = read8(f.dir / "out/comp.png"), theirs = read8(ref);
    ASSERT_EQ(mine.size(), theirs.size());
    int max_diff = 0, nonzero = 0;
    for (size_t i = 0; i < mine.size(); ++i) {
      max_diff = std::max(max_diff, std::abs(int(mine[i]) - int(theirs[i])));
      nonzero += mine[i] > 0;
    }
    EXPECT_LE(max_diff, 1) << view;
    EXPECT_GT(nonzero, int(mine.size() / 2)) << view;
    fs::remove_all(f.dir / "out");
    fs::create_directories(f.dir / "out");
  }
}
