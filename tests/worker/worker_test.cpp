// The farm worker against a real server on 127.0.0.1 (ephemeral port), with
// real `vesper render` child processes: frames rendered through the farm are
// bitwise equal to local renders; sample-range splitting; a failing renderer
// fails its tasks (log tail kept) and gets the worker blocklisted, while the
// worker keeps running; cancel kills a running render.
#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "common/sha256.h"
#include "server/server.h"
#include "tests/common/http_blob.h"
#include "tests/common/temp_dir.h"
#include "worker/worker.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace vesper {
namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The Cornell box of scenes/cornell with its quads only (no mesh files), on a
// small film.
json tiny_scene(int size, int spp) {
  json s = json::parse(slurp(fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/scene.json"));
  json shapes = json::array();
  for (const auto& sh : s.at("shapes"))
    if (sh.at("type") != "mesh") shapes.push_back(sh);
  s["shapes"] = shapes;
  s["film"]["width"] = size;
  s["film"]["height"] = size;
  s["render"]["spp"] = spp;
  s["render"]["seed"] = 7;
  return s;
}

struct Pixels {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;
  std::vector<std::string> names;
};

// Reads an EXR with OIIO; fails the test (and returns empty) if it is not one.
Pixels read_exr(const fs::path& p) {
  Pixels px;
  auto in = OIIO::ImageInput::open(p.string());
  EXPECT_TRUE(in) << p << ": " << OIIO::geterror();
  if (!in) return px;
  EXPECT_STREQ(in->format_name(), "openexr");
  const OIIO::ImageSpec& spec = in->spec();
  px.width = spec.width;
  px.height = spec.height;
  px.channels = spec.nchannels;
  px.names = spec.channelnames;
  px.data.resize(size_t(px.width) * px.height * px.channels);
  EXPECT_TRUE(in->read_image(0, 0, 0, px.channels, OIIO::TypeDesc::FLOAT, px.data.data()));
  return px;
}

// Stops a worker running in the background when a test leaves early (a failed
// ASSERT), so that the future's destructor does not wait forever.
struct StopOnExit {
  Worker& w;
  ~StopOnExit() { w.request_stop(); }
};

class WorkerTest : public ::testing::Test {
 protected:
  void TearDown() override { server_.reset(); }

  void start(int blocklist_threshold = 3) {
    ServerConfig c;
    c.data_dir = dir_ / "data";
    c.lease_seconds = 30;
    c.blocklist_threshold = blocklist_threshold;
    c.vesper_binary = VESPER_BINARY;  // merges frames of several tasks
    server_ = std::make_unique<Server>(std::move(c));
    port_ = server_->start();
    ASSERT_GT(port_, 0);
  }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(30);
    return c;
  }
  httplib::Headers sub() const {
    return {{"Authorization", "Bearer " + server_->submitter_token()}};
  }
  httplib::Headers wrk() const { return {{"Authorization", "Bearer " + server_->worker_token()}}; }

  std::string put_blob(const std::string& bytes) {
    return test::upload_blob(client(), sub(), bytes);
  }
  std::string get_blob(const std::string& h) {
    auto r = client().Get(("/api/v1/blobs/" + h).c_str(), sub());
    EXPECT_TRUE(r && r->status == 200);
    return r ? r->body : "";
  }
  json submit(const json& body) {
    auto r = client().Post("/api/v1/jobs", sub(), body.dump(), "application/json");
    EXPECT_TRUE(r);
    if (!r) return {};
    EXPECT_EQ(r->status, 201) << r->body;
    return json::parse(r->body);
  }
  json job(const json& id) {
    const std::string sid = id.is_string() ? id.get<std::string>() : id.dump();
    auto r = client().Get(("/api/v1/jobs/" + sid).c_str(), sub());
    EXPECT_TRUE(r && r->status == 200);
    return r ? json::parse(r->body) : json{};
  }

  WorkerConfig worker_config() const {
    WorkerConfig c;
    c.server_url = server_->url();
    c.token = server_->worker_token();
    c.name = "test-worker";
    c.cache_dir = dir_ / "cache";
    c.vesper_binary = VESPER_BINARY;
    c.heartbeat_seconds = 0.2;
    c.idle_backoff_min = 0.05;
    c.idle_backoff_max = 0.2;
    c.exit_when_idle = true;
    c.render_threads = 1;
    return c;
  }

  // A local `vesper render` of the same scene file (written in `scene_dir`,
  // where its assets are), as frame `frame`.
  Pixels render_locally(const std::string& scene_text, int spp, int seed, int frame,
                        const fs::path& scene_dir = {}) {
    const fs::path scene = (scene_dir.empty() ? dir_ : scene_dir) / "local.json",
                   out = dir_ / "local.exr";
    std::ofstream(scene) << scene_text;
    const std::string cmd = std::string(VESPER_BINARY) + " render " + scene.string() + " -o " +
                            out.string() + " --spp " + std::to_string(spp) + " --seed " +
                            std::to_string(seed) + " --frame " + std::to_string(frame) +
                            " -q >/dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return read_exr(out);
  }

  Pixels result_pixels(const std::string& hash) {
    const fs::path p = dir_ / ("result-" + hash + ".exr");
    std::ofstream(p, std::ios::binary) << get_blob(hash);
    EXPECT_EQ(sha256_hex(slurp(p)), hash);
    return read_exr(p);
  }

  test::TempDir temp_{"worker"};
  fs::path dir_ = temp_.path();
  std::unique_ptr<Server> server_;
  int port_ = 0;
};

TEST_F(WorkerTest, ThreeFramesBitwiseEqualToLocalRenders) {
  start();
  const std::string scene_text = tiny_scene(16, 4).dump(2);
  const std::string scene = put_blob(scene_text);
  const json created = submit({{"name", "three"}, {"scene", scene}, {"frames", "1-3"}, {"spp", 4}});
  ASSERT_EQ(created.at("task_count"), 3);

  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);
  EXPECT_EQ(worker.tasks_completed(), 3);
  EXPECT_EQ(worker.tasks_failed(), 0);
  EXPECT_FALSE(worker.worker_id().empty());
  // The scene is cached under its hash.
  EXPECT_EQ(sha256_hex(slurp(dir_ / "cache" / (scene + ".json"))), scene);

  const json j = job(created.at("id"));
  EXPECT_EQ(j.at("counts").at("done"), 3) << j.dump();
  for (const auto& t : j.at("tasks")) {
    const Pixels local = render_locally(scene_text, 4, 7, t.at("frame").get<int>());
    ASSERT_EQ(local.width, 16);
    EXPECT_EQ(t.at("state"), "done");
    EXPECT_EQ(t.at("worker"), worker.worker_id());
    const Pixels p = result_pixels(t.at("result").get<std::string>());
    EXPECT_EQ(p.width, 16);
    EXPECT_EQ(p.height, 16);
    EXPECT_EQ(p.names, local.names);
    ASSERT_EQ(p.data.size(), local.data.size());
    EXPECT_EQ(0, std::memcmp(p.data.data(), local.data.data(), p.data.size() * sizeof(float)))
        << "frame " << t.at("frame") << " differs from the local render";
  }
}

TEST_F(WorkerTest, TwoWorkersSharingACacheNeverShareATask) {
  start();
  const std::string scene_text = tiny_scene(16, 4).dump();
  const std::string scene = put_blob(scene_text);
  const json created = submit({{"name", "six"}, {"scene", scene}, {"frames", "1-6"}, {"spp", 4}});
  ASSERT_EQ(created.at("task_count"), 6);
  WorkerConfig c = worker_config();
  Worker a(c), b(c);
  auto ra = std::async(std::launch::async, [&] { return a.run(); });
  auto rb = std::async(std::launch::async, [&] { return b.run(); });
  EXPECT_EQ(ra.get(), 0);
  EXPECT_EQ(rb.get(), 0);
  EXPECT_EQ(a.tasks_completed() + b.tasks_completed(), 6);
  EXPECT_EQ(a.tasks_failed() + b.tasks_failed() + a.tasks_dropped() + b.tasks_dropped(), 0);
  const json j = job(created.at("id"));
  EXPECT_EQ(j.at("counts").at("done"), 6) << j.dump();
  for (const auto& t : j.at("tasks")) {
    const Pixels local = render_locally(scene_text, 4, 7, t.at("frame").get<int>());
    const Pixels p = result_pixels(t.at("result").get<std::string>());
    ASSERT_EQ(p.data.size(), local.data.size());
    EXPECT_EQ(0, std::memcmp(p.data.data(), local.data.data(), p.data.size() * sizeof(float)));
  }
}

TEST_F(WorkerTest, SampleSplitRendersEveryRangeAsAPartial) {
  start();
  const std::string scene = put_blob(tiny_scene(16, 4).dump());
  const json created = submit({{"name", "split"},
                               {"scene", scene},
                               {"frames", "1-3"},
                               {"spp", 4},
                               {"samples_per_task", 2}});
  ASSERT_EQ(created.at("task_count"), 6);

  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);
  EXPECT_EQ(worker.tasks_completed(), 6);
  const json j = job(created.at("id"));
  EXPECT_EQ(j.at("counts").at("done"), 6) << j.dump();
  std::set<std::pair<int, int>> ranges;
  std::set<std::string> results;
  for (const auto& t : j.at("tasks")) {
    EXPECT_EQ(t.at("state"), "done");
    ranges.insert({t.at("sample_begin").get<int>(), t.at("sample_end").get<int>()});
    results.insert(t.at("result").get<std::string>());
    // A partial render (docs/partial-format.md), not an EXR.
    EXPECT_EQ(get_blob(t.at("result").get<std::string>()).substr(0, 15), "VESPER-PARTIAL\n");
  }
  EXPECT_EQ(ranges, (std::set<std::pair<int, int>>{{0, 2}, {2, 4}}));
  // Two sample ranges render different pixels (the same range of another frame may be equal).
  EXPECT_GE(results.size(), 2u);
}

TEST_F(WorkerTest, FailingRendererFailsTasksAndBlocklistsTheWorker) {
  start(/*blocklist_threshold=*/2);
  // Not JSON: `vesper render` exits 2 with "invalid JSON at line ...".
  const std::string scene = put_blob("{\"format\": \"vesper-scene/1\", \"camera\": \n");
  const json created = submit(
      {{"name", "broken"}, {"scene", scene}, {"frames", "1-3"}, {"spp", 4}, {"max_attempts", 1}});
  ASSERT_EQ(created.at("task_count"), 3);

  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);  // the worker survives its renders
  EXPECT_EQ(worker.tasks_failed(), 2);
  EXPECT_EQ(worker.tasks_completed(), 0);

  const json j = job(created.at("id"));
  EXPECT_EQ(j.at("counts").at("failed"), 2) << j.dump();
  EXPECT_EQ(j.at("counts").at("queued"), 1) << j.dump();  // left for other workers
  int failed_seen = 0;
  for (const auto& t : j.at("tasks")) {
    if (t.at("state") != "failed") continue;
    ++failed_seen;
    EXPECT_EQ(t.at("attempts"), 1);
    EXPECT_TRUE(t.at("has_log").get<bool>());
    const std::string id =
        t.at("id").is_string() ? t.at("id").get<std::string>() : t.at("id").dump();
    const std::string jid =
        j.at("id").is_string() ? j.at("id").get<std::string>() : j.at("id").dump();
    auto r = client().Get(("/api/v1/jobs/" + jid + "/tasks/" + id + "/log").c_str(), sub());
    ASSERT_TRUE(r && r->status == 200);
    EXPECT_NE(r->body.find("invalid JSON at line"), std::string::npos) << r->body;
    EXPECT_NE(r->body.find("exit code 2"), std::string::npos) << r->body;
  }
  EXPECT_EQ(failed_seen, 2);
  EXPECT_EQ(j.at("blocked_workers"), json::array({worker.worker_id()})) << j.dump();

  // Two failed tasks in the job: the worker is blocklisted, so the queued task
  // is not leased to it.
  auto r = client().Post("/api/v1/lease", wrk(), json{{"worker_id", worker.worker_id()}}.dump(),
                         "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 204) << r->body;
  // ... while another worker still gets it.
  auto reg = client().Post("/api/v1/workers/register", wrk(), json{{"name", "other"}}.dump(),
                           "application/json");
  ASSERT_TRUE(reg && reg->status == 200);
  r = client().Post("/api/v1/lease", wrk(),
                    json{{"worker_id", json::parse(reg->body).at("worker_id")}}.dump(),
                    "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
}

TEST_F(WorkerTest, CancelKillsTheRunningRender) {
  start();
  // ~30 s on one thread if it were not killed.
  const std::string scene = put_blob(tiny_scene(64, 8192).dump());
  const json created = submit({{"name", "slow"}, {"scene", scene}, {"frames", "1"}, {"spp", 8192}});

  Worker worker(worker_config());
  auto done = std::async(std::launch::async, [&] { return worker.run(); });
  StopOnExit stop_on_exit{worker};

  // Wait until the render runs and heartbeats (the server shows its progress).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  bool running = false;
  while (!running && std::chrono::steady_clock::now() < deadline) {
    const json j = job(created.at("id"));
    for (const auto& t : j.at("tasks"))
      if (t.at("state") == "leased" && t.value("progress", 0.0) > 0) running = true;
    if (!running) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(running);
  const std::string jid =
      created.at("id").is_string() ? created.at("id").get<std::string>() : created.at("id").dump();
  const auto canceled_at = std::chrono::steady_clock::now();
  auto r =
      client().Post(("/api/v1/jobs/" + jid + "/cancel").c_str(), sub(), "{}", "application/json");
  ASSERT_TRUE(r && r->status == 200) << (r ? r->body : "no answer");

  ASSERT_EQ(done.wait_for(std::chrono::seconds(15)), std::future_status::ready)
      << "the worker did not drop the canceled render";
  EXPECT_EQ(done.get(), 0);
  EXPECT_LT(std::chrono::steady_clock::now() - canceled_at, std::chrono::seconds(10));
  EXPECT_EQ(worker.tasks_dropped(), 1);
  EXPECT_EQ(worker.tasks_completed(), 0);
  const json j = job(created.at("id"));
  EXPECT_EQ(j.at("state"), "canceled");
  for (const auto& t : j.at("tasks")) {
    EXPECT_EQ(t.at("state"), "canceled");
    EXPECT_TRUE(t.at("result").is_null() || t.at("result") == "") << t.dump();
  }
  // No render output left behind.
  for (const auto& e : fs::directory_iterator(dir_ / "cache" / "tmp"))
    ADD_FAILURE() << "left over: " << e.path();
}

TEST_F(WorkerTest, StopDuringARenderFinishesAndCompletesTheTask) {
  start();
  // A few seconds on one thread.
  const std::string scene = put_blob(tiny_scene(16, 16000).dump());
  const json created =
      submit({{"name", "stop"}, {"scene", scene}, {"frames", "1-2"}, {"spp", 16000}});
  WorkerConfig c = worker_config();
  c.exit_when_idle = false;
  Worker worker(c);
  auto done = std::async(std::launch::async, [&] { return worker.run(); });
  StopOnExit stop_on_exit{worker};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  bool running = false;
  while (!running && std::chrono::steady_clock::now() < deadline) {
    // Leased is enough: a stop is only looked at between tasks.
    const json j = job(created.at("id"));  // (a range-for over a temporary's member would dangle)
    for (const auto& t : j.at("tasks"))
      if (t.at("state") == "leased") running = true;
    if (!running) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(running);
  worker.request_stop();  // what the CLI's SIGTERM handler does
  ASSERT_EQ(done.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  EXPECT_EQ(done.get(), 0);
  EXPECT_EQ(worker.tasks_completed(), 1);
  const json j = job(created.at("id"));
  EXPECT_EQ(j.at("counts").at("done"), 1) << j.dump();
  EXPECT_EQ(j.at("counts").at("queued"), 1) << j.dump();  // the second frame was not leased
}

TEST_F(WorkerTest, StopWhileIdleReturnsPromptly) {
  start();
  WorkerConfig c = worker_config();
  c.exit_when_idle = false;
  c.idle_backoff_min = 1;
  c.idle_backoff_max = 5;
  Worker worker(c);
  auto done = std::async(std::launch::async, [&] { return worker.run(); });
  StopOnExit stop_on_exit{worker};
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto stopped_at = std::chrono::steady_clock::now();
  worker.request_stop();
  ASSERT_EQ(done.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  EXPECT_EQ(done.get(), 0);
  EXPECT_LT(std::chrono::steady_clock::now() - stopped_at, std::chrono::milliseconds(500));
}

TEST_F(WorkerTest, CrashingRendererFailsTheTaskNotTheWorker) {
  start();
  // A stand-in renderer that writes to stderr and dies of SIGSEGV.
  const fs::path fake = dir_ / "crashing-vesper";
  std::ofstream(fake) << "#!/bin/sh\necho 'about to crash' >&2\nkill -SEGV $$\n";
  fs::permissions(fake, fs::perms::owner_all);
  const std::string scene = put_blob(tiny_scene(16, 4).dump());
  const json created = submit(
      {{"name", "crash"}, {"scene", scene}, {"frames", "1-2"}, {"spp", 4}, {"max_attempts", 1}});
  WorkerConfig c = worker_config();
  c.vesper_binary = fake;
  Worker worker(c);
  EXPECT_EQ(worker.run(), 0);
  EXPECT_EQ(worker.tasks_failed(), 2);
  const json j = job(created.at("id"));
  EXPECT_EQ(j.at("counts").at("failed"), 2) << j.dump();
  const std::string jid =
      j.at("id").is_string() ? j.at("id").get<std::string>() : j.at("id").dump();
  const json& t = j.at("tasks").at(0);
  const std::string id = t.at("id").is_string() ? t.at("id").get<std::string>() : t.at("id").dump();
  auto r = client().Get(("/api/v1/jobs/" + jid + "/tasks/" + id + "/log").c_str(), sub());
  ASSERT_TRUE(r && r->status == 200);
  EXPECT_NE(r->body.find("killed by signal 11"), std::string::npos) << r->body;
  EXPECT_NE(r->body.find("about to crash"), std::string::npos) << r->body;
}

TEST_F(WorkerTest, CorruptCacheEntryIsDownloadedAgain) {
  start();
  const std::string scene_text = tiny_scene(16, 4).dump();
  const std::string scene = put_blob(scene_text);
  fs::create_directories(dir_ / "cache");
  std::ofstream(dir_ / "cache" / (scene + ".json")) << "{\"not\": \"the scene\"}";
  const json created = submit({{"name", "c"}, {"scene", scene}, {"frames", "1"}, {"spp", 4}});
  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);
  EXPECT_EQ(worker.tasks_completed(), 1);
  EXPECT_EQ(slurp(dir_ / "cache" / (scene + ".json")), scene_text);
}

TEST_F(WorkerTest, WrongTokenIsFatal) {
  start();
  WorkerConfig c = worker_config();
  c.token = "nope";
  Worker worker(c);
  EXPECT_EQ(worker.run(), 1);
}

std::string id_str(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

TEST_F(WorkerTest, MeshAssetIsRenderedFromTheTaskDirectory) {
  start();
  // The Cornell box with its two cube meshes, the mesh travelling as a blob
  // under another name.
  json s = json::parse(slurp(fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/scene.json"));
  s["film"]["width"] = 16;
  s["film"]["height"] = 16;
  s["render"]["seed"] = 7;
  int meshes = 0;
  for (auto& sh : s.at("shapes"))
    if (sh.at("type") == "mesh") {
      sh["file"] = "assets/cube.obj";
      ++meshes;
    }
  ASSERT_EQ(meshes, 2);
  const std::string scene_text = s.dump();
  const std::string cube = put_blob(slurp(fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/cube.obj"));
  const std::string scene = put_blob(scene_text);
  const json created = submit({{"name", "mesh"},
                               {"scene", scene},
                               {"frames", "2"},
                               {"spp", 4},
                               {"assets", {{{"name", "assets/cube.obj"}, {"blob", cube}}}}});
  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);
  EXPECT_EQ(worker.tasks_completed(), 1);
  EXPECT_EQ(worker.tasks_failed(), 0);
  const json j = job(created.at("id"));
  ASSERT_EQ(j.at("counts").at("done"), 1) << j.dump();
  // The worker's cache: the blob, and a task directory with the scene and
  // the asset (hard-linked).
  EXPECT_EQ(sha256_hex(slurp(dir_ / "cache" / cube)), cube);
  int dirs = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "cache" / "jobs")) {
    ++dirs;
    EXPECT_EQ(slurp(e.path() / "scene.json"), scene_text);
    EXPECT_TRUE(fs::equivalent(e.path() / "assets" / "cube.obj", dir_ / "cache" / cube));
  }
  EXPECT_EQ(dirs, 1);
  // Bitwise equal to a local render with the mesh beside the scene.
  fs::create_directories(dir_ / "local" / "assets");
  fs::copy_file(fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/cube.obj",
                dir_ / "local" / "assets" / "cube.obj");
  const Pixels local = render_locally(scene_text, 4, 7, 2, dir_ / "local");
  const Pixels p = result_pixels(j.at("tasks").at(0).at("result").get<std::string>());
  ASSERT_EQ(p.width, 16);
  ASSERT_EQ(p.data.size(), local.data.size());
  EXPECT_EQ(0, std::memcmp(p.data.data(), local.data.data(), p.data.size() * sizeof(float)));
  // Without the meshes the image differs (the asset was really used).
  const Pixels boxless = render_locally(tiny_scene(16, 4).dump(), 4, 7, 2);
  ASSERT_EQ(boxless.data.size(), p.data.size());
  EXPECT_NE(0, std::memcmp(p.data.data(), boxless.data.data(), p.data.size() * sizeof(float)));
}

TEST_F(WorkerTest, CorruptAssetBlobFailsTheTaskWithAClearLog) {
  start();
  json s = json::parse(slurp(fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/scene.json"));
  for (auto& sh : s.at("shapes"))
    if (sh.at("type") == "mesh") sh["file"] = "cube.obj";
  const std::string cube = put_blob(slurp(fs::path(VESPER_SOURCE_DIR) / "scenes/cornell/cube.obj"));
  const std::string scene = put_blob(s.dump());
  // The server's copy goes bad after the upload.
  std::ofstream(dir_ / "data" / "blobs" / cube.substr(0, 2) / cube.substr(2)) << "garbage";
  const json created = submit({{"name", "bad"},
                               {"scene", scene},
                               {"frames", "1"},
                               {"spp", 4},
                               {"max_attempts", 1},
                               {"assets", {{{"name", "cube.obj"}, {"blob", cube}}}}});
  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);
  EXPECT_EQ(worker.tasks_failed(), 1);
  const json j = job(created.at("id"));
  ASSERT_EQ(j.at("counts").at("failed"), 1) << j.dump();
  auto r = client().Get(("/api/v1/jobs/" + id_str(j.at("id")) + "/tasks/" +
                         id_str(j.at("tasks").at(0).at("id")) + "/log")
                            .c_str(),
                        sub());
  ASSERT_TRUE(r && r->status == 200);
  EXPECT_NE(r->body.find("asset 'cube.obj'"), std::string::npos) << r->body;
  EXPECT_NE(r->body.find("does not match its hash"), std::string::npos) << r->body;
  EXPECT_FALSE(fs::exists(dir_ / "cache" / cube));  // nothing unverified is cached
}

// GET /jobs/{id}/frames/{frame} of a one-task frame: 409 until it is done,
// then the task's EXR.
TEST_F(WorkerTest, FrameEndpointServesAOneTaskFrame) {
  start();
  const std::string scene_text = tiny_scene(16, 4).dump();
  const std::string scene = put_blob(scene_text);
  const json created = submit({{"name", "one"}, {"scene", scene}, {"frames", "5"}, {"spp", 4}});
  const std::string jid = id_str(created.at("id"));
  auto r = client().Get(("/api/v1/jobs/" + jid + "/frames/5").c_str(), sub());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409) << r->body;
  EXPECT_NE(json::parse(r->body).at("error").get<std::string>().find("not finished"),
            std::string::npos);
  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);
  r = client().Get(("/api/v1/jobs/" + jid + "/frames/5").c_str(), sub());
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const fs::path got = dir_ / "frame5.exr";
  std::ofstream(got, std::ios::binary) << r->body;
  const Pixels p = read_exr(got);
  const Pixels local = render_locally(scene_text, 4, 7, 5);
  ASSERT_EQ(p.data.size(), local.data.size());
  EXPECT_EQ(0, std::memcmp(p.data.data(), local.data.data(), p.data.size() * sizeof(float)));
  r = client().Get(("/api/v1/jobs/" + jid + "/frames").c_str(), sub());
  ASSERT_TRUE(r && r->status == 200);
  const json frames = json::parse(r->body).at("frames");
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].at("state"), "ready");
  EXPECT_EQ(frames[0].at("blob"), job(created.at("id")).at("tasks").at(0).at("result"));
}

// A frame split into 4 sample ranges: the server merges the partials into
// an EXR bitwise equal to a single render of the frame.
TEST_F(WorkerTest, SplitFrameMergesBitwiseEqualToASingleRender) {
  start();
  const std::string scene_text = tiny_scene(16, 8).dump();
  const std::string scene = put_blob(scene_text);
  const json created = submit(
      {{"name", "split4"}, {"scene", scene}, {"frames", "3"}, {"spp", 8}, {"samples_per_task", 2}});
  ASSERT_EQ(created.at("task_count"), 4);
  const std::string jid = id_str(created.at("id"));
  auto r = client().Get(("/api/v1/jobs/" + jid + "/frames/3").c_str(), sub());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409) << r->body;
  Worker worker(worker_config());
  EXPECT_EQ(worker.run(), 0);
  const json j = job(created.at("id"));
  if (j.at("counts").at("failed") != 0) {
    // `vesper render --partial` not implemented by this build.
    auto log = client().Get(
        ("/api/v1/jobs/" + jid + "/tasks/" + id_str(j.at("tasks").at(0).at("id")) + "/log").c_str(),
        sub());
    if (log && log->body.find("not implemented") != std::string::npos)
      GTEST_SKIP() << "vesper render --partial is not implemented yet";
  }
  ASSERT_EQ(j.at("counts").at("done"), 4) << j.dump();
  r = client().Get(("/api/v1/jobs/" + jid + "/frames/3").c_str(), sub());
  ASSERT_TRUE(r);
  if (r->status == 500 && r->body.find("not implemented") != std::string::npos)
    GTEST_SKIP() << "vesper merge is not implemented yet: " << r->body;
  ASSERT_EQ(r->status, 200) << r->body;
  const fs::path got = dir_ / "frame3.exr";
  std::ofstream(got, std::ios::binary) << r->body;
  const Pixels p = read_exr(got);
  const Pixels local = render_locally(scene_text, 8, 7, 3);
  ASSERT_EQ(p.width, 16);
  EXPECT_EQ(p.names, local.names);
  ASSERT_EQ(p.data.size(), local.data.size());
  EXPECT_EQ(0, std::memcmp(p.data.data(), local.data.data(), p.data.size() * sizeof(float)));
  // Recorded once: the listing names the same blob, and asking again serves it.
  r = client().Get(("/api/v1/jobs/" + jid + "/frames").c_str(), sub());
  ASSERT_TRUE(r && r->status == 200);
  const json frames = json::parse(r->body).at("frames");
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].at("state"), "ready");
  EXPECT_EQ(frames[0].at("blob"), sha256_hex(slurp(got)));
}

}  // namespace
}  // namespace vesper
