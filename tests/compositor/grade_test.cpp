// Grader (OCIO grading and display) against oiiotool's own OCIO display
// conversion, the ASC CDL formula by hand, error messages, the look LUT and
// ociocheck on the bundled config.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <sys/wait.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "compositor/grade.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;
using namespace vesper;

namespace {

const std::string kConfig = bundled_ocio_config();
const std::string kNightLut = std::string(VESPER_SOURCE_DIR) + "/configs/looks/night.cube";

struct TempDir {
  vesper::test::TempDir temp{"grade"};
  const fs::path path = temp.path();
};

struct RunResult {
  int status = -1;
  std::string output;
};

// Runs a shell command, capturing stdout and stderr.
RunResult run(const std::string& cmd) {
  RunResult r;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool have_tool(const std::string& name) {
  return run("command -v " + name + " >/dev/null").status == 0;
}

// A ramp over -0.5..4 along x in the first rows, then random colours in
// [-0.25, 4] (about 5% of the channels negative); alpha = 1.
RgbaImage test_image(int w = 64, int h = 32) {
  RgbaImage img(w, h);
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u(-0.25f, 4.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c)
        img.at(x, y, c) = y < 4 ? -0.5f + 4.5f * float(x) / float(w - 1) : u(rng);
      img.at(x, y, 3) = 1.f;
    }
  return img;
}

void write_exr(const RgbaImage& img, const fs::path& path) {
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out) << OIIO::geterror();
  OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, img.pixels.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

RgbaImage read_image(const fs::path& path) {
  RgbaImage img;
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return img;
  const auto& spec = in->spec();
  EXPECT_EQ(spec.nchannels, 4);
  img = RgbaImage(spec.width, spec.height);
  EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, img.pixels.data()));
  return img;
}

// Display conversion by Grader vs `oiiotool --ociodisplay` on the same EXR.
void compare_with_oiiotool(const std::string& display, const std::string& view) {
  if (!have_tool("oiiotool")) GTEST_SKIP() << "oiiotool not installed (openimageio-tools)";
  TempDir tmp;
  const RgbaImage src = test_image();
  const fs::path in = tmp.path / "in.exr", out = tmp.path / "out.exr";
  write_exr(src, in);
  const std::string cmd = "oiiotool " + quote(in.string()) + " --colorconfig " + quote(kConfig) +
                          " --iscolorspace " + quote("Linear Rec.709 (sRGB)") +
                          " --ociodisplay:unpremult=0 " + quote(display) + " " + quote(view) +
                          " -d float -o " + quote(out.string());
  const RunResult r = run(cmd);
  ASSERT_EQ(r.status, 0) << cmd << "\n" << r.output;
  const RgbaImage ref = read_image(out);
  ASSERT_EQ(ref.width, src.width);
  ASSERT_EQ(ref.height, src.height);

  Grader grader(GradeDesc{}, DisplayDesc{kConfig, display, view});
  RgbaImage mine = src;
  grader.apply_grade(mine);
  EXPECT_EQ(mine.pixels, src.pixels) << "an empty grade must not change the image";
  grader.apply_display(mine);

  double max_diff = 0;
  bool changed = false;
  for (size_t i = 0; i < mine.pixels.size(); ++i) {
    ASSERT_TRUE(std::isfinite(mine.pixels[i])) << i;
    max_diff = std::max(max_diff, double(std::fabs(mine.pixels[i] - ref.pixels[i])));
    if (i % 4 != 3 && std::fabs(mine.pixels[i] - src.pixels[i]) > 1e-3f) changed = true;
    if (i % 4 == 3) {
      EXPECT_EQ(mine.pixels[i], src.pixels[i]) << "alpha must be untouched";
    }
  }
  EXPECT_TRUE(changed) << "the display transform did nothing";
  EXPECT_LE(max_diff, 1.0 / 255.0) << display << " / " << view;
  testing::Test::RecordProperty("max_abs_difference", std::to_string(max_diff));
}

// --- the ASC CDL by hand -------------------------------------------------
struct V3 {
  double r, g, b;
};

// out = (in * 2^e * slope + offset)^power (v < 0 passes the power unchanged,
// as OCIO's CDL_NO_CLAMP does), then saturation around Rec.709 luma.
V3 cdl_by_hand(V3 in, double exposure, const Cdl& c) {
  const double k = std::exp2(exposure);
  auto channel = [&](double v, double s, double o, double p) {
    const double x = v * k * s + o;
    return x < 0 ? x : std::pow(x, p);
  };
  V3 t{channel(in.r, c.slope.r, c.offset.r, c.power.r),
       channel(in.g, c.slope.g, c.offset.g, c.power.g),
       channel(in.b, c.slope.b, c.offset.b, c.power.b)};
  const double luma = 0.2126 * t.r + 0.7152 * t.g + 0.0722 * t.b;
  const double s = c.saturation;
  return {luma + s * (t.r - luma), luma + s * (t.g - luma), luma + s * (t.b - luma)};
}

void expect_rel_near(double got, double want, const std::string& what) {
  EXPECT_NEAR(got, want, 1e-5 * std::max(1.0, std::fabs(want))) << what;
}

}  // namespace

TEST(Grade, BundledConfigPathAndListing) {
  EXPECT_TRUE(fs::is_regular_file(kConfig)) << kConfig;
  Grader g(GradeDesc{}, DisplayDesc{kConfig, "sRGB", "Standard"});
  EXPECT_EQ(g.config_path(), kConfig);
  EXPECT_EQ(g.displays(), (std::vector<std::string>{"sRGB", "Rec.1886 Rec.709"}));
  EXPECT_EQ(g.views("sRGB"), (std::vector<std::string>{"Standard", "ACES 1.0 SDR", "Raw"}));
  EXPECT_EQ(g.views("Rec.1886 Rec.709"),
            (std::vector<std::string>{"Standard", "ACES 1.0 SDR", "Raw"}));
}

TEST(Grade, ConfigFallsBackToOcioEnvThenBundled) {
  const char* old = std::getenv("OCIO");
  const std::string saved = old ? old : "";
  TempDir tmp;
  const fs::path copy = tmp.path / "env_config.ocio";
  fs::copy_file(kConfig, copy);
  ::setenv("OCIO", copy.c_str(), 1);
  EXPECT_EQ(Grader(GradeDesc{}, DisplayDesc{}).config_path(), copy.string());
  ::setenv("OCIO", (tmp.path / "nope.ocio").c_str(), 1);
  EXPECT_THROW(Grader(GradeDesc{}, DisplayDesc{}), CompError);
  ::unsetenv("OCIO");
  EXPECT_EQ(Grader(GradeDesc{}, DisplayDesc{}).config_path(), kConfig);
  if (old) ::setenv("OCIO", saved.c_str(), 1);
}

TEST(Grade, IdentityStandardMatchesOiiotoolSrgb) { compare_with_oiiotool("sRGB", "Standard"); }
TEST(Grade, IdentityAcesSdrMatchesOiiotoolSrgb) { compare_with_oiiotool("sRGB", "ACES 1.0 SDR"); }
TEST(Grade, IdentityStandardMatchesOiiotoolRec1886) {
  compare_with_oiiotool("Rec.1886 Rec.709", "Standard");
}
TEST(Grade, IdentityAcesSdrMatchesOiiotoolRec1886) {
  compare_with_oiiotool("Rec.1886 Rec.709", "ACES 1.0 SDR");
}

// Negative control for the oiiotool comparisons: the two views differ by far
// more than the 1/255 tolerance, so a wrong view would be caught.
TEST(Grade, StandardAndAcesViewsDiffer) {
  RgbaImage a = test_image(), b = a;
  Grader(GradeDesc{}, DisplayDesc{kConfig, "sRGB", "Standard"}).apply_display(a);
  Grader(GradeDesc{}, DisplayDesc{kConfig, "sRGB", "ACES 1.0 SDR"}).apply_display(b);
  double max_diff = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    max_diff = std::max(max_diff, double(std::fabs(a.pixels[i] - b.pixels[i])));
  EXPECT_GT(max_diff, 0.05);
}

// The "Standard" views are the plain display encodings, checked by formula.
TEST(Grade, StandardViewsAreThePlainEncodings) {
  auto srgb = [](double v) {
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  };
  auto bt1886 = [](double v) { return std::pow(std::max(v, 0.0), 1 / 2.4); };
  const float values[] = {0.f, 0.001f, 0.0031308f, 0.01f, 0.18f, 0.5f, 1.f};
  for (const auto& [display, f] :
       {std::pair<std::string, double (*)(double)>{"sRGB", +srgb},
        std::pair<std::string, double (*)(double)>{"Rec.1886 Rec.709", +bt1886}}) {
    Grader g(GradeDesc{}, DisplayDesc{kConfig, display, "Standard"});
    RgbaImage img(7, 1);
    for (int i = 0; i < 7; ++i)
      for (int c = 0; c < 4; ++c) img.at(i, 0, c) = values[i];
    g.apply_display(img);
    for (int i = 0; i < 7; ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(img.at(i, 0, c), f(values[i]), 2e-4) << display << " at " << values[i];
  }
}

// ACES 1.0 SDR: 18% grey lands near the published ~0.36 sRGB code value, and
// the tone scale compresses highlights below 1.
TEST(Grade, AcesSdrToneScale) {
  Grader g(GradeDesc{}, DisplayDesc{kConfig, "sRGB", "ACES 1.0 SDR"});
  RgbaImage img(3, 1);
  const float v[] = {0.18f, 1.f, 16.f};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) img.at(i, 0, c) = v[i];
  g.apply_display(img);
  EXPECT_NEAR(img.at(0, 0, 1), 0.356, 0.01);
  EXPECT_LT(img.at(1, 0, 1), 0.9f);
  EXPECT_GT(img.at(2, 0, 1), img.at(1, 0, 1));
  EXPECT_LE(img.at(2, 0, 1), 1.0001f);
}

TEST(Grade, CdlAndExposureMatchTheAscFormula) {
  const std::vector<V3> inputs = {{0.18, 0.18, 0.18}, {0.5, 0.25, 0.125}, {1.0, 2.0, 4.0},
                                  {0.0, 0.0, 0.0},    {0.02, 0.7, 0.3},   {3.0, 0.01, 1.5},
                                  {0.05, -0.2, -0.3}, {-1.0, -1.0, -1.0}};
  struct Case {
    float exposure;
    Cdl cdl;
  };
  const std::vector<Case> cases = {
      {0.f, Cdl{Rgb(1.f), Rgb(0.f), Rgb(1.f), 1.f}},
      {1.f, Cdl{Rgb(1.f), Rgb(0.f), Rgb(1.f), 1.f}},
      {-0.7f, Cdl{Rgb(1.2f, 1.f, 0.8f), Rgb(-0.1f, 0.f, 0.05f), Rgb(2.f, 0.5f, 1.5f), 1.f}},
      {0.3f, Cdl{Rgb(1.1f, 0.95f, 1.05f), Rgb(0.01f, -0.02f, 0.03f), Rgb(1.2f, 0.9f, 1.1f), 0.6f}},
      {0.f, Cdl{Rgb(1.f), Rgb(0.f), Rgb(1.f), 1.7f}},
      {2.f, Cdl{Rgb(0.5f, 0.6f, 0.7f), Rgb(0.f), Rgb(0.8f), 0.f}},
  };
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& k = cases[ci];
    GradeDesc gd;
    gd.exposure = k.exposure;
    gd.cdl = k.cdl;
    Grader g(gd, DisplayDesc{kConfig, "sRGB", "Standard"});
    RgbaImage img(int(inputs.size()), 1);
    for (size_t i = 0; i < inputs.size(); ++i) {
      img.at(int(i), 0, 0) = float(inputs[i].r);
      img.at(int(i), 0, 1) = float(inputs[i].g);
      img.at(int(i), 0, 2) = float(inputs[i].b);
      img.at(int(i), 0, 3) = 0.25f;
    }
    g.apply_grade(img);
    for (size_t i = 0; i < inputs.size(); ++i) {
      // The float inputs, as the image holds them.
      const V3 in{double(float(inputs[i].r)), double(float(inputs[i].g)),
                  double(float(inputs[i].b))};
      const V3 want = cdl_by_hand(in, k.exposure, k.cdl);
      const std::string what = "case " + std::to_string(ci) + " input " + std::to_string(i);
      expect_rel_near(img.at(int(i), 0, 0), want.r, what + " R");
      expect_rel_near(img.at(int(i), 0, 1), want.g, what + " G");
      expect_rel_near(img.at(int(i), 0, 2), want.b, what + " B");
      EXPECT_EQ(img.at(int(i), 0, 3), 0.25f) << what << " alpha";
    }
  }
}

// Documents OCIO's CDL_NO_CLAMP on negatives: the power passes them through
// (no clamp to 0, no NaN), saturation still applies.
TEST(Grade, CdlNoClampPassesNegativesThroughThePower) {
  GradeDesc gd;
  gd.cdl = Cdl{Rgb(1.f), Rgb(-0.5f), Rgb(2.2f), 1.f};
  Grader g(gd, DisplayDesc{kConfig, "sRGB", "Standard"});
  RgbaImage img(1, 1);
  img.at(0, 0, 0) = 0.25f;  // 0.25 - 0.5 = -0.25
  img.at(0, 0, 1) = 1.5f;   // 1.0^2.2 = 1
  img.at(0, 0, 2) = -1.f;   // -1.5
  g.apply_grade(img);
  EXPECT_NEAR(img.at(0, 0, 0), -0.25f, 1e-6);
  EXPECT_NEAR(img.at(0, 0, 1), 1.f, 1e-6);
  EXPECT_NEAR(img.at(0, 0, 2), -1.5f, 1e-6);
}

TEST(Grade, ErrorMissingConfig) {
  const std::string path = "/nonexistent/dir/config.ocio";
  try {
    Grader g(GradeDesc{}, DisplayDesc{path, "sRGB", "Standard"});
    FAIL() << "no error";
  } catch (const CompError& e) {
    EXPECT_NE(std::string(e.what()).find("OCIO config not found: " + path), std::string::npos)
        << e.what();
  }
}

TEST(Grade, ErrorInvalidConfig) {
  TempDir tmp;
  const fs::path bad = tmp.path / "bad.ocio";
  std::ofstream(bad)
      << "ocio_profile_version: 2.1\nroles: {scene_linear: nothing}\ncolorspaces: [\n";
  try {
    Grader g(GradeDesc{}, DisplayDesc{bad.string(), "sRGB", "Standard"});
    FAIL() << "no error";
  } catch (const CompError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

TEST(Grade, ErrorUnknownViewListsViews) {
  try {
    Grader g(GradeDesc{}, DisplayDesc{kConfig, "sRGB", "ACES 2.0 SDR"});
    FAIL() << "no error";
  } catch (const CompError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'ACES 2.0 SDR'"), std::string::npos) << m;
    EXPECT_NE(m.find("'Standard'"), std::string::npos) << m;
    EXPECT_NE(m.find("'ACES 1.0 SDR'"), std::string::npos) << m;
  }
}

TEST(Grade, ErrorUnknownDisplayListsDisplays) {
  try {
    Grader g(GradeDesc{}, DisplayDesc{kConfig, "P3-D65", "Standard"});
    FAIL() << "no error";
  } catch (const CompError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'P3-D65'"), std::string::npos) << m;
    EXPECT_NE(m.find("'sRGB'"), std::string::npos) << m;
    EXPECT_NE(m.find("'Rec.1886 Rec.709'"), std::string::npos) << m;
  }
}

TEST(Grade, ErrorMissingLut) {
  GradeDesc gd;
  gd.look_lut = "/nonexistent/looks/missing.cube";
  try {
    Grader g(gd, DisplayDesc{kConfig, "sRGB", "Standard"});
    FAIL() << "no error";
  } catch (const CompError& e) {
    EXPECT_NE(std::string(e.what()).find(gd.look_lut), std::string::npos) << e.what();
  }
}

TEST(Grade, ErrorCorruptLut) {
  TempDir tmp;
  const fs::path bad = tmp.path / "broken.cube";
  std::ofstream(bad) << "LUT_3D_SIZE 9\n0 0 0\nnot numbers\n";
  GradeDesc gd;
  gd.look_lut = bad.string();
  try {
    Grader g(gd, DisplayDesc{kConfig, "sRGB", "Standard"});
    FAIL() << "no error";
  } catch (const CompError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

// The night look changes the image (cooler, less saturated); without a LUT
// the grade is the identity; the LUT samples match the generator's formula.
TEST(Grade, NightLookLut) {
  const RgbaImage src = test_image(32, 8);
  {
    Grader none(GradeDesc{}, DisplayDesc{kConfig, "sRGB", "Standard"});
    RgbaImage img = src;
    none.apply_grade(img);
    EXPECT_EQ(img.pixels, src.pixels);
  }
  GradeDesc gd;
  gd.look_lut = kNightLut;
  Grader g(gd, DisplayDesc{kConfig, "sRGB", "Standard"});
  RgbaImage img = src;
  g.apply_grade(img);
  double diff = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    ASSERT_TRUE(std::isfinite(img.pixels[i]));
    diff = std::max(diff, double(std::fabs(img.pixels[i] - src.pixels[i])));
  }
  EXPECT_GT(diff, 0.05);

  // Mid grey becomes bluish; grid points (multiples of 1.0) are exact samples.
  RgbaImage p(3, 1);
  const float pts[3][3] = {{0.18f, 0.18f, 0.18f}, {2.f, 1.f, 0.f}, {0.f, 0.f, 0.f}};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) p.at(i, 0, c) = pts[i][c];
  g.apply_grade(p);
  EXPECT_GT(p.at(0, 0, 2), p.at(0, 0, 1));
  EXPECT_GT(p.at(0, 0, 1), p.at(0, 0, 0));
  const double y = 0.2126 * 2 + 0.7152 * 1;
  EXPECT_NEAR(p.at(1, 0, 0), (y + 0.8 * (2 - y)) * 0.94, 1e-5);
  EXPECT_NEAR(p.at(1, 0, 1), (y + 0.8 * (1 - y)) * 0.98, 1e-5);
  EXPECT_NEAR(p.at(1, 0, 2), (y + 0.8 * (0 - y)) * 1.06, 1e-5);
  EXPECT_NEAR(p.at(2, 0, 0), 0.0, 1e-6);
  EXPECT_NEAR(p.at(2, 0, 1), 0.0015, 1e-6);
  EXPECT_NEAR(p.at(2, 0, 2), 0.006, 1e-6);
}

// The grade order is exposure -> CDL -> LUT: a LUT after a CDL differs from
// the CDL alone and equals LUT(CDL(x)) evaluated in two Graders.
TEST(Grade, LutComesAfterCdl) {
  GradeDesc cdl_only;
  cdl_only.exposure = 0.5f;
  cdl_only.cdl = Cdl{Rgb(1.1f, 1.f, 0.9f), Rgb(0.01f), Rgb(1.1f), 0.8f};
  GradeDesc lut_only;
  lut_only.look_lut = kNightLut;
  GradeDesc both = cdl_only;
  both.look_lut = kNightLut;
  const DisplayDesc d{kConfig, "sRGB", "Standard"};
  RgbaImage a = test_image(16, 8), b = a;
  for (float& v : a.pixels) v = std::max(v, 0.f);
  b = a;
  Grader(cdl_only, d).apply_grade(a);
  Grader(lut_only, d).apply_grade(a);
  Grader(both, d).apply_grade(b);
  for (size_t i = 0; i < a.pixels.size(); ++i) EXPECT_NEAR(a.pixels[i], b.pixels[i], 1e-4) << i;
}

TEST(Grade, OciocheckBundledConfig) {
  if (!have_tool("ociocheck")) GTEST_SKIP() << "ociocheck not installed (opencolorio-tools)";
  const RunResult r = run("ociocheck --iconfig " + quote(kConfig));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("ERROR"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("passed"), std::string::npos) << r.output;
}
