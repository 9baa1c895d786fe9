// The browser monitor against a real server on 127.0.0.1: the page and its
// assets, the cookie login (a wrong token refused; the cookie works for reads
// and actions; an action without the X-Vesper-Monitor header refused; never
// for submitting or uploading), read-only viewing, and the thumbnail and
// histogram of a finished frame (a real EXR, completed through the worker
// protocol).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "renderer/output/exr_io.h"
#include "server/frame_views.h"
#include "server/tokens.h"
#include "tests/common/cli_runner.h"
#include "tests/server/server_fixture.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

class MonitorTest : public ServerTest {
 protected:
  // POST /api/v1/login with `token`; the answer.
  httplib::Result login(const std::string& token) {
    return client().Post("/api/v1/login", json{{"token", token}}.dump(), "application/json");
  }
  // The session cookie ("vesper_session=...") a good login sets.
  std::string session() {
    auto r = login(server_->submitter_token());
    EXPECT_TRUE(r);
    if (!r) return {};
    EXPECT_EQ(r->status, 200) << r->body;
    const std::string set = r->get_header_value("Set-Cookie");
    return set.substr(0, set.find(';'));
  }
  static httplib::Headers cookie(const std::string& c, bool monitor_header) {
    httplib::Headers h{{"Cookie", c}};
    if (monitor_header) h.emplace("X-Vesper-Monitor", "1");
    return h;
  }
  int status_of(httplib::Result r) { return r ? r->status : -1; }
};

TEST_F(MonitorTest, ThePageAndItsAssetsAreServedFromTheBinary) {
  start();
  auto page = client().Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  // Without a cookie the API refuses, and the page has the login form it then shows.
  EXPECT_NE(page->body.find("id=\"login-form\""), std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("default-src 'self'"),
            std::string::npos);
  EXPECT_EQ(page->body.find("http://"), std::string::npos) << "the page loads nothing from the web";
  EXPECT_EQ(page->body.find("https://"), std::string::npos)
      << "the page loads nothing from the web";
  for (const auto& [asset, type] : {std::pair{"monitor.js", "text/javascript; charset=utf-8"},
                                    std::pair{"monitor.css", "text/css; charset=utf-8"}}) {
    auto r = client().Get((std::string("/monitor/") + asset).c_str());
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << asset;
    EXPECT_EQ(r->get_header_value("Content-Type"), type) << asset;
    EXPECT_GT(r->body.size(), 1000u) << asset;
    EXPECT_EQ(r->body.find("https://"), std::string::npos) << asset;
  }
  EXPECT_EQ(status_of(client().Get("/monitor/nothing.js")), 404);
  EXPECT_EQ(status_of(client().Get("/api/v1/jobs")), 401);
}

TEST_F(MonitorTest, LoginWithAWrongTokenIsRefused) {
  start();
  auto r = login("not-the-token");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 401);
  EXPECT_FALSE(r->has_header("Set-Cookie"));
  EXPECT_NE(json::parse(r->body).at("error").get<std::string>().find("wrong token"),
            std::string::npos)
      << r->body;
  // The worker token is not the submitter token either.
  EXPECT_EQ(status_of(login(server_->worker_token())), 401);
  auto bad = client().Post("/api/v1/login", "token=x", "application/x-www-form-urlencoded");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(bad->body.find("\\\"token\\\""), std::string::npos) << bad->body;
  // A made-up cookie is no session.
  EXPECT_EQ(status_of(client().Get("/api/v1/jobs", cookie("vesper_session=abc", true))), 401);
}

TEST_F(MonitorTest, TheSessionCookieWorksForReadsAndJobActions) {
  start();
  const int64_t job = submit(2);
  auto r = login(server_->submitter_token());
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const std::string set = r->get_header_value("Set-Cookie");
  EXPECT_NE(set.find("HttpOnly"), std::string::npos) << set;
  EXPECT_NE(set.find("SameSite=Strict"), std::string::npos) << set;
  EXPECT_NE(set.find("Path=/"), std::string::npos) << set;
  EXPECT_EQ(set.find("Domain"), std::string::npos) << "scoped to this server: " << set;
  EXPECT_EQ(set.find(server_->submitter_token()), std::string::npos) << "not the token itself";
  const std::string c = set.substr(0, set.find(';'));

  const std::string jp = "/api/v1/jobs/" + std::to_string(job);
  for (const std::string& path :
       std::vector<std::string>{"/api/v1/jobs", jp, "/api/v1/workers", jp + "/frames"})
    EXPECT_EQ(status_of(client().Get(path.c_str(), cookie(c, false))), 200) << path;
  const std::string pause = "/api/v1/jobs/" + std::to_string(job) + "/pause";
  // A state change on the cookie alone (what a cross-site form could send) is refused...
  auto refused = client().Post(pause.c_str(), cookie(c, false), "{}", "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 403);
  EXPECT_NE(refused->body.find("X-Vesper-Monitor"), std::string::npos) << refused->body;
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(job)).at("state"), "active");
  // ... and works with the page's header.
  auto paused = client().Post(pause.c_str(), cookie(c, true), "{}", "application/json");
  ASSERT_TRUE(paused);
  EXPECT_EQ(paused->status, 200) << paused->body;
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(job)).at("state"), "paused");

  // Never for submitting work or storing bytes.
  const json body{{"name", "x"}, {"scene", sha256_hex("s")}, {"frames", "1"}};
  EXPECT_EQ(
      status_of(client().Post("/api/v1/jobs", cookie(c, true), body.dump(), "application/json")),
      401);
  EXPECT_EQ(status_of(client().Put(("/api/v1/blobs/" + sha256_hex("b")).c_str(), cookie(c, true),
                                   "b", "application/octet-stream")),
            401);
  // Logging out expires the cookie in the browser.
  auto out = client().Post("/api/v1/logout", "{}", "application/json");
  ASSERT_TRUE(out);
  EXPECT_NE(out->get_header_value("Set-Cookie").find("Max-Age=0"), std::string::npos);
}

TEST_F(MonitorTest, ReplacingTheSubmitterTokenEndsEverySession) {
  start();
  const std::string c = session();
  EXPECT_EQ(status_of(client().Get("/api/v1/jobs", cookie(c, false))), 200);
  const fs::path file = dir_ / "data" / "tokens.json";
  Tokens tokens = read_tokens(file);
  tokens.submitter = std::string(64, 'a');
  write_tokens(file, tokens);
  EXPECT_EQ(status_of(client().Get("/api/v1/jobs", cookie(c, false))), 401);
  EXPECT_EQ(status_of(client().Get("/api/v1/jobs", auth(std::string(64, 'a')))), 200);
}

TEST_F(MonitorTest, ReadOnlyViewingNeedsNoTokenButActionsDo) {
  ServerConfig c = config();
  c.monitor_read_only = true;
  start(c);
  const int64_t job = submit(1);
  const std::string j = "/api/v1/jobs/" + std::to_string(job);
  for (const std::string& path : std::vector<std::string>{"/api/v1/jobs", j, "/api/v1/workers"})
    EXPECT_EQ(status_of(client().Get(path.c_str())), 200) << path;
  EXPECT_EQ(status_of(client().Post((j + "/cancel").c_str(), "{}", "application/json")), 401);
  EXPECT_EQ(status_of(client().Get((j + "/frames/1").c_str())), 401) << "EXRs need a token";
  EXPECT_EQ(status_of(client().Get(("/api/v1/blobs/" + sha256_hex("x")).c_str())), 401);
  // A wrong token is still refused, not taken as no token.
  EXPECT_EQ(status_of(client().Get("/api/v1/jobs", auth("wrong"))), 401);
}

// A 300x150 EXR: the left half black, the right half at 4.0 (over white).
std::string two_tone_exr(const fs::path& dir) {
  LayeredImage img;
  img.width = 300;
  img.height = 150;
  img.channels = {"R", "G", "B", "A"};
  img.pixels.resize(size_t(img.width) * img.height * 4);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (size_t ch = 0; ch < 4; ++ch) img.at(x, y, ch) = ch == 3 ? 1.f : x < 150 ? 0.f : 4.f;
  write_exr(img, dir / "frame.exr");
  return test::slurp(dir / "frame.exr");
}

TEST_F(MonitorTest, AFinishedFrameHasAThumbnailAndAHistogram) {
  start();
  const int64_t job = submit(1);
  const std::string frame = "/api/v1/jobs/" + std::to_string(job) + "/frames/1";
  // Not finished yet: the frame's own answer (409).
  EXPECT_EQ(status_of(client().Get((frame + "/thumbnail").c_str(), sub())), 409);
  const std::string worker = register_worker("w");
  const json l = lease(worker);
  const std::string result = put_blob(two_tone_exr(dir_));
  post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", result}}, wrk());

  auto thumb = client().Get((frame + "/thumbnail").c_str(), sub());
  ASSERT_TRUE(thumb);
  ASSERT_EQ(thumb->status, 200) << thumb->body;
  EXPECT_EQ(thumb->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(thumb->get_header_value("X-Vesper-Blob"), result);
  const fs::path png = dir_ / "thumb.png";
  std::ofstream(png, std::ios::binary) << thumb->body;
  auto in = OIIO::ImageInput::open(png.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->format_name(), std::string("png"));
  ASSERT_EQ(in->spec().width, 256);
  ASSERT_EQ(in->spec().height, 128);
  ASSERT_EQ(in->spec().nchannels, 3);
  std::vector<uint8_t> px(256 * 128 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  EXPECT_EQ(px[(64 * 256 + 10) * 3], 0);     // black stays black
  EXPECT_EQ(px[(64 * 256 + 250) * 3], 255);  // over white clips to white

  auto hist = client().Get((frame + "/histogram").c_str(), sub());
  ASSERT_TRUE(hist);
  ASSERT_EQ(hist->status, 200) << hist->body;
  const json h = json::parse(hist->body);
  EXPECT_EQ(h.at("format"), "vesper-histogram/1");
  EXPECT_EQ(h.at("width"), 300);
  EXPECT_EQ(h.at("height"), 150);
  uint64_t sum = 0;
  for (const json& b : h.at("bins")) sum += b.get<uint64_t>();
  EXPECT_EQ(sum, 300u * 150u);
  EXPECT_EQ(h.at("count").get<uint64_t>(), 300u * 150u);
  EXPECT_EQ(h.at("bins").at(0).get<uint64_t>(), 150u * 150u);
  EXPECT_EQ(h.at("bins").at(255).get<uint64_t>(), 150u * 150u);
  // Made once per output blob, kept by its name.
  EXPECT_TRUE(fs::is_regular_file(dir_ / "data" / "monitor-cache" / (result + ".png")));
  auto again = client().Get((frame + "/thumbnail").c_str(), sub());
  ASSERT_TRUE(again);
  EXPECT_EQ(again->body, thumb->body);
  EXPECT_EQ(status_of(client().Get(
                ("/api/v1/jobs/" + std::to_string(job) + "/frames/7/histogram").c_str(), sub())),
            404);
}

TEST_F(MonitorTest, DeletingAJobTakesItsFramesViewsWithItsBlobs) {
  ServerConfig c = config();
  c.blob_grace_seconds = 0;  // collect at once what no job references
  start(c);
  const int64_t job = submit(1);
  const std::string worker = register_worker("w");
  const json l = lease(worker);
  const std::string result = put_blob(two_tone_exr(dir_));
  post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", result}}, wrk());
  const std::string frame = "/api/v1/jobs/" + std::to_string(job) + "/frames/1";
  ASSERT_EQ(status_of(client().Get((frame + "/thumbnail").c_str(), sub())), 200);
  ASSERT_EQ(status_of(client().Get((frame + "/histogram").c_str(), sub())), 200);
  const fs::path cache = dir_ / "data" / "monitor-cache";
  ASSERT_TRUE(fs::is_regular_file(cache / (result + ".png")));
  ASSERT_TRUE(fs::is_regular_file(cache / (result + ".histogram.json")));

  ASSERT_EQ(status_of(client().Delete(("/api/v1/jobs/" + std::to_string(job)).c_str(), sub())),
            200);
  EXPECT_FALSE(fs::exists(cache / (result + ".png")));
  EXPECT_FALSE(fs::exists(cache / (result + ".histogram.json")));
}

TEST(FrameViews, ScalingKeepsTheAspectAndAveragesInLinearLight) {
  RgbaImage img(1000, 10);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 1000; ++x)
      for (int c = 0; c < 4; ++c) img.at(x, y, c) = x % 2 ? 1.f : 0.f;
  const RgbaImage small = scaled_to_width(img, 256);
  EXPECT_EQ(small.width, 256);
  EXPECT_EQ(small.height, 3);  // 10 * 256 / 1000, rounded
  EXPECT_EQ(scaled_to_width(img, 2000).width, 1000);
  const RgbaImage encoded = srgb_encoded(small);
  // Half the pixels white: 0.5 linear, 0.735 encoded (not 0.5).
  EXPECT_NEAR(encoded.at(100, 0, 0), 0.7354, 0.01);
}

}  // namespace
}  // namespace vesper
