// The server checks a result before it commits it, trusts only registered
// renderer builds for reuse, and re-reads tokens.json so that a revoked
// worker token is refused without a restart (docs/farm.md, "Hardening").
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>
#include <tuple>

#include "common/scene_hash.h"
#include "renderer/sampling/random_hash.h"
#include "server/result_check.h"
#include "server/tokens.h"
#include "tests/common/temp_dir.h"
#include "tests/server/server_fixture.h"

namespace vesper {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// A scene the server can hash (it never renders): what a worker would render.
const json kScene = {{"format", "vesper-scene/1"}, {"render", {{"seed", 7}}}};

struct Header {
  std::string scene_hash = SceneHash(kScene).hex();
  int frame = 1, begin = 0, end = 8;
  uint64_t seed = frame_seed(7, 1);
  std::string pixel_type;  // vesper:pixel_type when set
};

// A small multi-layer EXR whose header says what `h` says, as render() writes it.
std::string exr_bytes(const fs::path& dir, const Header& h, int size = 8) {
  const fs::path file = dir / "result.exr";
  OIIO::ImageSpec spec(size, size, 7, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B", "A", "fog.R", "fog.G", "fog.B"};
  spec.attribute("vesper:scene_hash", h.scene_hash);
  spec.attribute("vesper:frame", std::to_string(h.frame));
  spec.attribute("vesper:sample_begin", std::to_string(h.begin));
  spec.attribute("vesper:sample_end", std::to_string(h.end));
  spec.attribute("vesper:seed", std::to_string(h.seed));
  if (!h.pixel_type.empty()) spec.attribute("vesper:pixel_type", h.pixel_type);
  std::vector<float> pixels(size_t(size * size * 7), 0.5f);
  auto out = OIIO::ImageOutput::create(file.string());
  EXPECT_TRUE(out && out->open(file.string(), spec));
  out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  out->close();
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A partial render's magic and header (docs/partial-format.md) and a body.
std::string partial_bytes(const Header& h, int frame_spp) {
  const std::string body = "0123456789";
  json metadata{{"vesper:frame", std::to_string(h.frame)}};
  if (!h.pixel_type.empty()) metadata["vesper:pixel_type"] = h.pixel_type;
  const json header{{"format", "vesper-partial/2"}, {"scene_hash", h.scene_hash},
                    {"sample_begin", h.begin},      {"sample_end", h.end},
                    {"frame_spp", frame_spp},       {"seed", h.seed},
                    {"metadata", metadata},         {"sums", {{"compressed_bytes", body.size()}}}};
  return "VESPER-PARTIAL\n" + header.dump() + "\n" + body;
}

class ResultCheckTest : public ServerTest {
 protected:
  ServerConfig checking() const {
    ServerConfig c = config();
    c.verify_results = true;  // the default, which the fixture turns off
    return c;
  }
  int64_t submit_scene(int frames, int spp, int split = 0) {
    json body{{"name", "checked"},
              {"scene", put_blob(kScene.dump())},
              {"frames", "1-" + std::to_string(frames)},
              {"spp", spp},
              {"max_attempts", 10}};
    if (split) body["samples_per_task"] = split;
    return post_ok("/jobs", body, sub(), 201).at("id").get<int64_t>();
  }
  // POST /complete of `bytes` for lease `l`; returns (status, body).
  std::pair<int, json> complete(const json& l, const std::string& bytes) {
    auto r =
        post("/complete", {{"lease_id", l.at("lease_id")}, {"result", put_blob(bytes)}}, wrk());
    EXPECT_TRUE(r);
    if (!r) return {0, {}};
    return {r->status, json::parse(r->body, nullptr, false)};
  }
};

TEST_F(ResultCheckTest, JunkIsRefusedAndTheAttemptCharged) {
  start(checking());
  const int64_t job = submit_scene(1, 8);
  const std::string w = register_worker("liar");
  const json l = lease(w);
  const auto [status, body] = complete(l, "junk bytes, not an image");
  EXPECT_EQ(status, 400) << body;
  EXPECT_NE(body.value("error", "").find("not an OpenEXR image"), std::string::npos) << body;
  EXPECT_EQ(body.value("path", ""), "/result");
  const json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("counts").at("done"), 0);
  EXPECT_EQ(j.at("tasks").at(0).at("attempts"), 1) << "the worker's fault: the attempt counts";
  EXPECT_EQ(j.at("tasks").at(0).at("state"), "queued");
  // The refused lease is over: the worker cannot complete it again.
  EXPECT_EQ(complete(l, exr_bytes(dir_, {})).first, 409);
  // A truncated EXR (header intact, pixels cut) is refused too.
  const std::string whole = exr_bytes(dir_, {}, 64);
  const auto [cut, why] = complete(lease(w), whole.substr(0, whole.size() - 100));
  EXPECT_EQ(cut, 400) << why;
}

TEST_F(ResultCheckTest, MetadataMustMatchTheTask) {
  start(checking());
  const int64_t job = submit_scene(1, 8);
  const std::string w = register_worker("w");
  Header other_scene, other_frame, other_range, other_seed;
  other_scene.scene_hash = "0123456789abcdef";
  other_frame.frame = 2;
  other_range.end = 4;
  other_seed.seed = 7;  // the scene's seed without the frame mixed in
  const std::pair<const char*, Header> cases[] = {{"vesper:scene_hash", other_scene},
                                                  {"vesper:frame", other_frame},
                                                  {"vesper:sample_end", other_range},
                                                  {"vesper:seed", other_seed}};
  for (const auto& [name, header] : cases) {
    const auto [status, body] = complete(lease(w), exr_bytes(dir_, header));
    EXPECT_EQ(status, 400) << name;
    EXPECT_NE(body.value("error", "").find(name), std::string::npos) << body;
  }
  // The render the task asked for is taken.
  const auto [status, body] = complete(lease(w), exr_bytes(dir_, {}));
  EXPECT_EQ(status, 200) << body;
  const json j = get_ok("/jobs/" + std::to_string(job));
  EXPECT_EQ(j.at("counts").at("done"), 1);
  EXPECT_EQ(j.at("tasks").at(0).at("attempts"), 5);  // four refused, the fifth taken
}

// A sample-range task's result is a partial render, checked the same way.
TEST_F(ResultCheckTest, PartialsAreChecked) {
  start(checking());
  submit_scene(1, 8, 4);  // tasks [0,4) and [4,8)
  const std::string w = register_worker("w");
  const json l = lease(w);
  ASSERT_EQ(l.at("task").at("sample_end"), 4);
  Header range;
  range.end = 4;
  // A whole-frame EXR is not what a sample-range task makes.
  EXPECT_EQ(complete(l, exr_bytes(dir_, range)).first, 400);
  Header wrong = range;
  wrong.scene_hash = "fedcba9876543210";
  auto [status, body] = complete(lease(w), partial_bytes(wrong, 8));
  EXPECT_EQ(status, 400);
  EXPECT_NE(body.value("error", "").find("vesper:scene_hash"), std::string::npos) << body;
  std::tie(status, body) = complete(lease(w), partial_bytes(range, 16));
  EXPECT_NE(body.value("error", "").find("frame_spp"), std::string::npos) << body;
  std::tie(status, body) = complete(lease(w), partial_bytes(range, 8).substr(0, 200));
  EXPECT_EQ(status, 400) << "a truncated partial";
  std::tie(status, body) = complete(lease(w), partial_bytes(range, 8));
  EXPECT_EQ(status, 200) << body;
}

// The expected scene hash covers the files the scene references (assets),
// in the renderer's order: shapes, lights, then media by name.
// A job with the `half` override: its results must say vesper:pixel_type
// "half" (a worker that ignored the lease key rendered float).
TEST(HalfResultCheck, AHalfJobsResultMustSayHalf) {
  const test::TempDir tmp("server");
  const fs::path dir = tmp.path();
  ExpectedResult e;
  e.scene_hash = Header().scene_hash;
  e.frame = 1;
  e.sample_end = e.frame_spp = 8;
  e.seed = Header().seed;
  e.half = true;
  const fs::path partial = dir / "result.vpartial";
  for (const bool is_partial : {false, true}) {
    e.partial = is_partial;
    for (const char* type : {"", "float", "half"}) {
      Header h;
      h.pixel_type = type;
      const std::string bytes = is_partial ? partial_bytes(h, 8) : exr_bytes(dir, h);
      const fs::path file = is_partial ? partial : dir / "result.exr";
      if (is_partial) std::ofstream(file, std::ios::binary) << bytes;
      const std::string problem = check_result(file, e);
      if (std::string(type) == "half")
        EXPECT_EQ(problem, "") << is_partial;
      else
        EXPECT_NE(problem.find("vesper:pixel_type is"), std::string::npos) << problem;
    }
  }
  std::ofstream(partial, std::ios::binary) << partial_bytes(Header(), 8);  // float
  e.half = false;  // no override: the scene decides
  EXPECT_EQ(check_result(partial, e), "");
}

TEST(SceneHashOrder, FollowsTheLoader) {
  const json doc = json::parse(R"({"media": {"b": {"file": "m2.vdb"}, "a": {"file": "m1.vdb"}},
    "lights": [{"type": "environment", "file": "sky.exr"}],
    "shapes": [{"type": "mesh", "file": "x.obj"}, {"type": "sphere"}]})");
  EXPECT_EQ(hashed_file_references(doc),
            (std::vector<std::string>{"x.obj", "sky.exr", "m1.vdb", "m2.vdb"}));
}

// Reuse needs a renderer build the operator registered: a worker announcing
// an unknown build renders, but what it made is not handed to later jobs.
TEST_F(ResultCheckTest, ResultsOfAnUnregisteredRendererAreNotReused) {
  start();  // trusts its own build only
  const std::string w = register_worker("w");
  const std::string claimed(64, 'b');
  submit(1);
  const json l = post_ok("/lease", {{"worker_id", w}, {"renderer", claimed}}, wrk());
  post_ok("/complete", {{"lease_id", l.at("lease_id")}, {"result", put_blob("frame")}}, wrk());
  const int64_t second = submit(1);  // identical
  auto again = post("/lease", {{"worker_id", w}, {"renderer", claimed}}, wrk());
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 200) << "rendered again, not reused";
  EXPECT_EQ(get_ok("/jobs/" + std::to_string(second)).at("counts").at("done"), 0);
}

// Per-worker tokens: tokens.json is re-read when it changes, so a revoked
// token (or the disabled shared one) is refused without a restart.
TEST_F(ResultCheckTest, RevokedTokensAreRefusedWithoutARestart) {
  start();
  const fs::path file = dir_ / "data" / "tokens.json";
  Tokens t = read_tokens(file);
  t.workers["box-1"] = {std::string(64, 'c'), true};
  write_tokens(file, t);
  const auto box = auth(std::string(64, 'c'));
  auto r = post("/workers/register", {{"name", "box-1"}}, box);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(post("/workers/register", {{"name", "box-1"}}, sub())->status, 401);

  t.workers["box-1"].enabled = false;
  write_tokens(file, t);
  EXPECT_EQ(post("/workers/register", {{"name", "box-1"}}, box)->status, 401);
  EXPECT_EQ(post("/workers/register", {{"name", "w"}}, wrk())->status, 200);

  t.shared_worker_enabled = false;
  write_tokens(file, t);
  EXPECT_EQ(post("/workers/register", {{"name", "w"}}, wrk())->status, 401);
  EXPECT_EQ(client().Get("/api/v1/jobs", sub())->status, 200) << "submitters are not affected";
  EXPECT_EQ(fs::status(file).permissions() & fs::perms::mask,
            fs::perms::owner_read | fs::perms::owner_write);
}

}  // namespace
}  // namespace vesper
