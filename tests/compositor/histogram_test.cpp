// Luminosity histograms: flat on a ramp, χ² against uniform, counts, the
// Wasserstein-1 distance, exposure matching, weights, JSON, the PNG plot and
// `vesper hist` as a user runs it.
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "compositor/histogram.h"
#include "renderer/output/exr_io.h"
#include "tests/common/temp_dir.h"

namespace fs = std::filesystem;
using namespace vesper;

namespace {

RgbaImage grey_image(int w, int h, const std::function<float(int)>& value) {
  RgbaImage img(w, h);
  for (int i = 0; i < w * h; ++i) {
    const float v = value(i);
    for (int c = 0; c < 3; ++c) img.pixels[size_t(i) * 4 + size_t(c)] = v;
    img.pixels[size_t(i) * 4 + 3] = 1.f;
  }
  return img;
}

// A log-normal-ish scene-linear image (median luminance 2^-2.5, σ = 1.5
// stops) with a mild per-pixel tint, so that it is not just grey.
RgbaImage lognormal_image(int w, int h, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> stops(-2.5, 1.5);
  std::uniform_real_distribution<double> tint(0.9, 1.1);
  RgbaImage img(w, h);
  for (size_t i = 0; i < img.pixel_count(); ++i) {
    const double y = std::exp2(stops(rng));
    img.pixels[i * 4 + 0] = float(y * tint(rng));
    img.pixels[i * 4 + 1] = float(y);
    img.pixels[i * 4 + 2] = float(y * tint(rng));
    img.pixels[i * 4 + 3] = 1.f;
  }
  return img;
}

RgbaImage exposed(const RgbaImage& img, double stops) {
  RgbaImage out = img;
  const float k = float(std::exp2(stops));
  for (size_t i = 0; i < out.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) out.pixels[i * 4 + size_t(c)] *= k;
  return out;
}

RgbaImage srgb_encoded(const RgbaImage& linear) {
  RgbaImage out = linear;
  for (size_t i = 0; i < out.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c)
      out.pixels[i * 4 + size_t(c)] = float(srgb_encode(out.pixels[i * 4 + size_t(c)]));
  return out;
}

uint64_t sum(const std::vector<uint64_t>& bins) {
  uint64_t s = 0;
  for (uint64_t b : bins) s += b;
  return s;
}

// Upper α quantile of χ² with k degrees of freedom (Wilson–Hilferty).
double chi2_critical(double k, double z_alpha) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z_alpha * std::sqrt(a), 3.0);
}

}  // namespace

// (a) flat ramp, χ² against uniform ------------------------------------------

TEST(Histogram, LinearRampIsExactlyFlat) {
  constexpr int n = 256 * 64;
  // Evenly spaced over [0, 1), bin edges included: every bin gets 64 values.
  for (const auto& ramp :
       {grey_image(256, 64, [](int i) { return float(i) / float(n); }),
        grey_image(256, 64, [](int i) { return (float(i) + 0.5f) / float(n); })}) {
    for (const LumaWeights w : {LumaWeights::Rec709, LumaWeights::Luminosity}) {
      const Histogram h = display_histogram(ramp, w);
      ASSERT_EQ(h.bins.size(), 256u);
      for (size_t b = 0; b < 256; ++b) ASSERT_EQ(h.bins[b], 64u) << "bin " << b;
      EXPECT_NEAR(h.median, 0.5, 1e-4);
      EXPECT_NEAR(h.mean, 0.5, 1e-4);
    }
  }
  // An 8-bit ramp: every code value in its own bin.
  const Histogram h8 = display_histogram(grey_image(16, 16, [](int i) { return float(i) / 255.f; }),
                                         LumaWeights::Rec709);
  for (size_t b = 0; b < 256; ++b) ASSERT_EQ(h8.bins[b], 1u) << "bin " << b;
}

TEST(Histogram, UniformRandomImagePassesChiSquareAgainstUniform) {
  constexpr int w = 256, h = 400;  // 400 expected per bin
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const RgbaImage img = grey_image(w, h, [&](int) { return u(rng); });
  const Histogram hist = display_histogram(img, LumaWeights::Rec709);
  const double expected = double(w) * h / 256.0;
  double chi2 = 0;
  for (uint64_t b : hist.bins) chi2 += (double(b) - expected) * (double(b) - expected) / expected;
  const double critical = chi2_critical(255, 2.3263);  // α = 0.01
  EXPECT_LT(chi2, critical);
  // The same test rejects a skewed image (it can fail).
  const RgbaImage skewed = grey_image(w, h, [&](int) { return std::pow(u(rng), 1.1f); });
  const Histogram hs = display_histogram(skewed, LumaWeights::Rec709);
  double chi2s = 0;
  for (uint64_t b : hs.bins) chi2s += (double(b) - expected) * (double(b) - expected) / expected;
  EXPECT_GT(chi2s, critical);
  // Percentiles of U(0,1) are p/100.
  for (const auto& [p, v] : hist.percentiles) EXPECT_NEAR(v, p / 100.0, 0.01) << p;
}

// (b) counts -------------------------------------------------------------------

TEST(Histogram, CountsSumToThePixelCountAndClippingIsCounted) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.5f, 1.5f);
  RgbaImage img(37, 23);
  for (float& v : img.pixels) v = u(rng);
  img.pixels[0] = img.pixels[1] = img.pixels[2] = std::nanf("");
  const Histogram d = display_histogram(img, LumaWeights::Rec709);
  EXPECT_EQ(d.count, img.pixel_count());
  EXPECT_EQ(sum(d.bins), img.pixel_count());
  size_t low = 0, high = 0;
  for (size_t i = 0; i < img.pixel_count(); ++i) {
    double y = luminance(img.pixels[i * 4], img.pixels[i * 4 + 1], img.pixels[i * 4 + 2],
                         LumaWeights::Rec709);
    if (std::isnan(y)) y = 0;
    low += y <= 0;
    high += y >= 1;
  }
  EXPECT_DOUBLE_EQ(d.clipped_low, double(low) / double(img.pixel_count()));
  EXPECT_DOUBLE_EQ(d.clipped_high, double(high) / double(img.pixel_count()));
  EXPECT_GT(d.clipped_low, 0);
  EXPECT_GT(d.clipped_high, 0);

  const Histogram l = log2_histogram(img, LumaWeights::Rec709);
  EXPECT_EQ(l.count, img.pixel_count());
  EXPECT_EQ(sum(l.bins), img.pixel_count());
  EXPECT_DOUBLE_EQ(l.clipped_low,
                   double(low) / double(img.pixel_count()));  // all within [-12, 8] otherwise
  EXPECT_EQ(l.lo, -12);
  EXPECT_EQ(l.hi, 8);
  EXPECT_EQ(l.domain, HistogramDomain::Log2);
}

// (c) distance ------------------------------------------------------------------

TEST(Histogram, DistanceIsZeroToItselfAndGrowsWithExposureShift) {
  const RgbaImage base = lognormal_image(256, 256);
  const double shifts[] = {0, 0.25, 0.5, 1, 2};
  for (const HistogramDomain domain : {HistogramDomain::Log2, HistogramDomain::Display}) {
    auto hist = [&](const RgbaImage& linear) {
      return domain == HistogramDomain::Log2
                 ? log2_histogram(linear, LumaWeights::Rec709)
                 : display_histogram(srgb_encoded(linear), LumaWeights::Rec709);
    };
    const Histogram ref = hist(base);
    EXPECT_EQ(wasserstein1(ref, ref), 0.0);
    double prev = -1;
    for (const double s : shifts) {
      const double d = wasserstein1(hist(exposed(base, s)), ref);
      SCOPED_TRACE(fmt::format("{} shift {}", histogram_domain_name(domain), s));
      if (s == 0) {
        EXPECT_EQ(d, 0.0);
      } else {
        EXPECT_GT(d, prev);
      }
      // In stops, a shift translates the distribution: W1 is the shift (up to a bin).
      if (domain == HistogramDomain::Log2) {
        EXPECT_NEAR(d, s, 20.0 / 256);
      }
      prev = d;
      // Symmetric.
      EXPECT_DOUBLE_EQ(d, wasserstein1(ref, hist(exposed(base, s))));
    }
  }
}

TEST(Histogram, DistanceRefusesDifferentDomainsOrRanges) {
  const RgbaImage img = lognormal_image(16, 16);
  const Histogram a = log2_histogram(img, LumaWeights::Rec709);
  EXPECT_THROW(wasserstein1(a, display_histogram(img, LumaWeights::Rec709)), CompError);
  EXPECT_THROW(wasserstein1(a, log2_histogram(img, LumaWeights::Rec709, -10, 10)), CompError);
  EXPECT_THROW(matching_exposure_shift(a, display_histogram(img, LumaWeights::Rec709)), CompError);
  Histogram empty;
  empty.domain = HistogramDomain::Log2;
  empty.lo = -12;
  empty.hi = 8;
  empty.bins.assign(256, 0);
  EXPECT_THROW(wasserstein1(a, empty), CompError);
}

// (d) matching exposure -------------------------------------------------------------

TEST(Histogram, MatchingExposureRecoversAKnownShift) {
  const RgbaImage base = lognormal_image(200, 200, 11);
  for (const double s : {-1.3, -0.4, 0.0, 0.7, 1.5}) {
    SCOPED_TRACE(s);
    const RgbaImage reference = exposed(base, s);
    // Log2: medians in stops.
    const double l = matching_exposure_shift(log2_histogram(base, LumaWeights::Rec709),
                                             log2_histogram(reference, LumaWeights::Rec709));
    EXPECT_NEAR(l, s, 0.05);
    // Display: sRGB-encoded images, medians decoded back to linear.
    const double d =
        matching_exposure_shift(display_histogram(srgb_encoded(base), LumaWeights::Rec709),
                                display_histogram(srgb_encoded(reference), LumaWeights::Rec709));
    EXPECT_NEAR(d, s, 0.05);
    // And the other way round.
    EXPECT_NEAR(matching_exposure_shift(log2_histogram(reference, LumaWeights::Luminosity),
                                        log2_histogram(base, LumaWeights::Luminosity)),
                -s, 0.05);
  }
  // A black median has no matching shift.
  const RgbaImage black(8, 8);
  EXPECT_THROW(matching_exposure_shift(display_histogram(black, LumaWeights::Rec709),
                                       display_histogram(srgb_encoded(base), LumaWeights::Rec709)),
               CompError);
}

// (e) weights -------------------------------------------------------------------------

TEST(Histogram, WeightsGiveTheExpectedLuminanceOfPrimaries) {
  struct Case {
    LumaWeights w;
    double r, g, b;
  };
  for (const Case c : {Case{LumaWeights::Rec709, 0.2126, 0.7152, 0.0722},
                       Case{LumaWeights::Luminosity, 0.30, 0.59, 0.11}}) {
    for (int primary = 0; primary < 3; ++primary) {
      RgbaImage img(4, 4);
      for (size_t i = 0; i < img.pixel_count(); ++i) img.pixels[i * 4 + size_t(primary)] = 1.f;
      const Histogram h = display_histogram(img, c.w);
      const double expected = primary == 0 ? c.r : primary == 1 ? c.g : c.b;
      EXPECT_NEAR(h.mean, expected, 1e-9);
      EXPECT_NEAR(h.median, expected, 1e-9);
      EXPECT_EQ(h.bins[size_t(std::floor(expected * 256))], 16u);
      EXPECT_EQ(h.weights, c.w);
    }
  }
  EXPECT_EQ(parse_luma_weights("luminosity"), LumaWeights::Luminosity);
  EXPECT_EQ(parse_luma_weights("rec709"), LumaWeights::Rec709);
  EXPECT_FALSE(parse_luma_weights("rec2020").has_value());
}

// (f) JSON ------------------------------------------------------------------------------

TEST(Histogram, JsonHasTheDocumentedKeys) {
  const RgbaImage img = srgb_encoded(lognormal_image(64, 32));
  const Histogram h = display_histogram(img, LumaWeights::Luminosity);
  const Histogram r = display_histogram(srgb_encoded(exposed(lognormal_image(64, 32), 0.5)),
                                        LumaWeights::Luminosity);
  const nlohmann::json j = nlohmann::json::parse(histogram_json(h, &r));
  for (const nlohmann::json* x : {&j, &j.at("reference")}) {
    for (const char* k : {"domain", "weights", "range", "bins", "count", "mean", "median",
                          "percentiles", "clipped"})
      EXPECT_TRUE(x->contains(k)) << k;
    EXPECT_EQ(x->at("domain"), "display");
    EXPECT_EQ(x->at("weights").at("name"), "luminosity");
    EXPECT_DOUBLE_EQ(x->at("weights").at("r").get<double>(), 0.30);
    EXPECT_DOUBLE_EQ(x->at("weights").at("g").get<double>(), 0.59);
    EXPECT_DOUBLE_EQ(x->at("weights").at("b").get<double>(), 0.11);
    EXPECT_EQ(x->at("range"), nlohmann::json::array({0.0, 1.0}));
    ASSERT_EQ(x->at("bins").size(), 256u);
    uint64_t s = 0;
    for (const auto& b : x->at("bins")) s += b.get<uint64_t>();
    EXPECT_EQ(s, x->at("count").get<uint64_t>());
    EXPECT_EQ(x->at("count").get<uint64_t>(), 64u * 32u);
    for (const char* p : {"1", "5", "25", "50", "75", "95", "99"})
      EXPECT_TRUE(x->at("percentiles").contains(p)) << p;
    EXPECT_DOUBLE_EQ(x->at("percentiles").at("50").get<double>(), x->at("median").get<double>());
    EXPECT_TRUE(x->at("clipped").contains("low"));
    EXPECT_TRUE(x->at("clipped").contains("high"));
  }
  EXPECT_DOUBLE_EQ(j.at("distance").at("wasserstein1").get<double>(), wasserstein1(h, r));
  EXPECT_NEAR(j.at("matching_exposure_stops").get<double>(), 0.5, 0.05);
  // Without a reference: no comparison keys.
  const nlohmann::json solo = nlohmann::json::parse(histogram_json(h));
  EXPECT_FALSE(solo.contains("reference"));
  EXPECT_FALSE(solo.contains("distance"));
  EXPECT_EQ(
      nlohmann::json::parse(histogram_json(log2_histogram(img, LumaWeights::Rec709))).at("domain"),
      "log2");
}

// (g) PNG plot ----------------------------------------------------------------------------

TEST(Histogram, PlotIsWrittenAtomicallyAndReadable) {
  const vesper::test::TempDir temp("hist-plot");
  const fs::path dir = temp.path();
  const RgbaImage base = lognormal_image(128, 128);
  const Histogram h = log2_histogram(base, LumaWeights::Rec709);
  const Histogram r = log2_histogram(exposed(base, 1), LumaWeights::Rec709);
  const Histogram d = display_histogram(srgb_encoded(base), LumaWeights::Rec709);
  for (const auto& [name, hist, ref] :
       {std::tuple{"log2.png", &h, &r}, std::tuple{"display.png", &d, (const Histogram*)nullptr}}) {
    const fs::path p = dir / name;
    write_histogram_png(*hist, p, ref);
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->format_name(), std::string("png"));
    EXPECT_EQ(in->spec().width, 800);
    EXPECT_EQ(in->spec().height, 400);
    EXPECT_EQ(in->spec().nchannels, 3);
    std::vector<uint8_t> px(800 * 400 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
    // Not a blank picture: some bright (histogram) pixels and a dark background.
    size_t bright = 0, dark = 0;
    for (size_t i = 0; i < px.size(); i += 3) {
      bright += px[i] > 150 && px[i + 1] > 150 && px[i + 2] > 150;
      dark += px[i] < 40 && px[i + 1] < 40 && px[i + 2] < 40;
    }
    EXPECT_GT(bright, 5000u);
    EXPECT_GT(dark, 100000u);
  }
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos);
  EXPECT_THROW(write_histogram_png(h, dir / "no" / "such" / "dir.png"), CompError);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos);
}

TEST(Histogram, TerminalRenderingHasHeightRowsOfWidthColumnsAndASummary) {
  const Histogram h = display_histogram(srgb_encoded(lognormal_image(64, 64)), LumaWeights::Rec709);
  const std::string t = terminal_histogram(h, 32, 6);
  std::vector<std::string> lines;
  std::stringstream ss(t);
  for (std::string l; std::getline(ss, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 7u) << t;
  for (int r = 0; r < 6; ++r) {
    // Each column is one 3-byte block character or a space (trailing spaces trimmed).
    size_t cols = 0;
    for (size_t i = 0; i < lines[size_t(r)].size();) {
      i += (lines[size_t(r)][i] & 0x80) ? 3 : 1;
      ++cols;
    }
    EXPECT_LE(cols, 32u);
  }
  EXPECT_NE(lines[5].find("█"), std::string::npos) << t;  // the tallest column fills the bottom row
  EXPECT_NE(lines[6].find("median"), std::string::npos);
  EXPECT_NE(lines[6].find("mean"), std::string::npos);
  EXPECT_NE(lines[6].find("clipped"), std::string::npos);
}

// (h) `vesper hist` --------------------------------------------------------------------------

namespace {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class HistCli : public ::testing::Test {
 protected:
  RunResult run(const std::string& args) {
    const fs::path out = dir_ / ".stdout", err = dir_ / ".stderr";
    const std::string cmd = std::string(VESPER_BINARY) + " hist " + args + " >" + out.string() +
                            " 2>" + err.string() + " </dev/null";
    const int status = std::system(cmd.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(out);
    r.err = read_text(err);
    fs::remove(out);
    fs::remove(err);
    return r;
  }

  // An 8-bit grey PNG: 4096 pixels, code values 0..255 sixteen times, plus a bright square.
  fs::path write_png(const std::string& name) {
    const fs::path p = dir_ / name;
    std::vector<uint8_t> px(64 * 64 * 3);
    for (int i = 0; i < 64 * 64; ++i) {
      const uint8_t v = (i % 64 < 8 && i / 64 < 8) ? 230 : uint8_t((i * 7) % 256);
      px[size_t(i) * 3] = px[size_t(i) * 3 + 1] = px[size_t(i) * 3 + 2] = v;
    }
    auto o = OIIO::ImageOutput::create("png");
    EXPECT_TRUE(o->open(p.string(), OIIO::ImageSpec(64, 64, 3, OIIO::TypeDesc::UINT8)));
    EXPECT_TRUE(o->write_image(OIIO::TypeDesc::UINT8, px.data()));
    EXPECT_TRUE(o->close());
    return p;
  }

  bool no_temporaries() const {
    for (const auto& e : fs::directory_iterator(dir_))
      if (e.path().string().find(".tmp-") != std::string::npos) return false;
    return true;
  }

  vesper::test::TempDir temp_{"hist"};
  fs::path dir_ = temp_.path();
};

}  // namespace

TEST_F(HistCli, PrintsTheHistogramAndMedianOfAPng) {
  const fs::path png = write_png("a.png");
  const Histogram expected =
      display_histogram(read_histogram_source(png).image, LumaWeights::Rec709);
  const fs::path json = dir_ / "a.hist.json", plot = dir_ / "a.hist.png";
  const RunResult r = run(png.string() + " --json " + json.string() + " --plot " + plot.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(fmt::format("median {:.4g}", expected.median)), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("█"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j.at("count").get<uint64_t>(), 64u * 64u);
  EXPECT_DOUBLE_EQ(j.at("median").get<double>(), expected.median);
  EXPECT_EQ(j.at("weights").at("name"), "rec709");
  EXPECT_TRUE(fs::exists(plot));
  EXPECT_TRUE(no_temporaries());
  // Luminosity weights are named in the output.
  const RunResult l = run(png.string() + " --weights luminosity");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_NE(l.out.find("luminosity"), std::string::npos);
}

TEST_F(HistCli, ReferenceToItselfHasDistanceZero) {
  const fs::path png = write_png("a.png");
  const RunResult r = run(png.string() + " --ref " + png.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("distance (Wasserstein-1, display): 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("matching exposure (display): +0.000 stops"), std::string::npos) << r.out;
}

TEST_F(HistCli, ExrGetsADisplayAndALog2HistogramAndMatchesAnExposure) {
  const RgbaImage base = lognormal_image(64, 64);
  auto write = [&](const RgbaImage& img, const fs::path& p) {
    LayeredImage li;
    li.width = img.width;
    li.height = img.height;
    li.channels = {"R", "G", "B", "A"};
    li.pixels = img.pixels;
    write_exr(li, p);
  };
  const fs::path a = dir_ / "a.exr", b = dir_ / "b.exr", json = dir_ / "h.json";
  write(base, a);
  write(exposed(base, 0.75), b);
  const RunResult r = run(a.string() + " --ref " + b.string() + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("log2 luminance"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("matching exposure (log2): +0.750 stops"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j.at("domain"), "display");
  EXPECT_EQ(j.at("log2").at("domain"), "log2");
  EXPECT_NEAR(j.at("log2").at("matching_exposure_stops").get<double>(), 0.75, 1e-3);
  // --log2 makes the stops histogram the primary one.
  const fs::path plot = dir_ / "h.png";
  const RunResult l =
      run(a.string() + " --log2 --plot " + plot.string() + " --json " + json.string());
  ASSERT_EQ(l.exit_code, 0) << l.err;
  EXPECT_EQ(nlohmann::json::parse(read_text(json)).at("domain"), "log2");
  EXPECT_TRUE(fs::exists(plot));
}

TEST_F(HistCli, MissingFileIsAClearErrorNamingIt) {
  const fs::path missing = dir_ / "nowhere.png", json = dir_ / "out.json";
  const RunResult r = run(missing.string() + " --json " + json.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(json));
  // A missing reference too.
  const fs::path png = write_png("a.png");
  const RunResult m = run(png.string() + " --ref " + missing.string() + " --json " + json.string());
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.err.find(missing.string()), std::string::npos) << m.err;
  EXPECT_FALSE(fs::exists(json));
}

TEST_F(HistCli, CorruptOrTruncatedFileFailsAndLeavesNoOutput) {
  const fs::path png = write_png("a.png");
  const std::string bytes = read_text(png);
  const fs::path cut = dir_ / "cut.png", junk = dir_ / "junk.exr", json = dir_ / "out.json",
                 plot = dir_ / "out.png";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::ofstream(junk, std::ios::binary) << "v/1\x01 this is not an OpenEXR file";
  for (const fs::path& bad : {cut, junk}) {
    const RunResult r = run(bad.string() + " --json " + json.string() + " --plot " + plot.string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(json));
    EXPECT_FALSE(fs::exists(plot));
    EXPECT_TRUE(no_temporaries());
  }
}

TEST_F(HistCli, UnknownWeightsAreRefused) {
  const fs::path png = write_png("a.png");
  const RunResult r = run(png.string() + " --weights rec2020");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("rec2020"), std::string::npos) << r.err;
}
