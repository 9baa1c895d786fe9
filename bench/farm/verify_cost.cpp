// What checking a worker's result costs the server (ServerConfig::
// verify_results, server/result_check.h): the check of one 256x256
// multi-layer EXR (header and pixels), and completions per second through a
// real vesper::Server over HTTP with the check on and off, side by side in
// one run, each completion uploading a real EXR of its frame.
//
//   vesper_verify_bench [--tasks N] [--workers N] [--size PIXELS]
#include <OpenImageIO/imageio.h>
#include <httplib.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "common/scene_hash.h"
#include "common/sha256.h"
#include "renderer/sampling/random_hash.h"
#include "server/result_check.h"
#include "server/server.h"

namespace fs = std::filesystem;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

const json kScene = {{"format", "vesper-scene/1"}};

// A frame as `vesper render` writes it: beauty, albedo, normal, depth and
// two layers (16 channels), smooth pixels with noise, ZIP compressed.
std::string exr_of_frame(const fs::path& file, int size, int frame, int spp) {
  const std::vector<std::string> names = {
      "R",        "G",        "B",       "A",     "albedo.R", "albedo.G", "albedo.B", "normal.X",
      "normal.Y", "normal.Z", "depth.Z", "fog.R", "fog.G",    "fog.B",    "sky.R",    "sky.G"};
  OIIO::ImageSpec spec(size, size, int(names.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.attribute("compression", "zip");
  spec.attribute("vesper:scene_hash", vesper::SceneHash(kScene).hex());
  spec.attribute("vesper:frame", std::to_string(frame));
  spec.attribute("vesper:sample_begin", "0");
  spec.attribute("vesper:sample_end", std::to_string(spp));
  spec.attribute("vesper:seed", std::to_string(vesper::frame_seed(0, frame)));
  std::vector<float> px(size_t(size) * size * names.size());
  uint64_t state = uint64_t(frame) * 0x9e3779b97f4a7c15ull + 1;
  for (size_t i = 0; i < px.size(); ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    px[i] = 0.5f + 0.25f * std::sin(float(i % 977) * 0.01f) + float(state >> 40) * 1e-8f;
  }
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out || !out->open(file.string(), spec) ||
      !out->write_image(OIIO::TypeDesc::FLOAT, px.data()) || !out->close())
    throw std::runtime_error("cannot write " + file.string());
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// Completions per second of `tasks` one-frame tasks by `workers` keep-alive
// clients, each completion naming its frame's pre-uploaded EXR.
double completions_per_second(const fs::path& dir, bool verify,
                              const std::vector<std::string>& exrs, int workers) {
  fs::remove_all(dir);
  vesper::ServerConfig c;
  c.data_dir = dir;
  c.lease_seconds = 3600;
  c.verify_results = verify;
  vesper::Server server(c);
  const int port = server.start();
  const httplib::Headers sub = {{"Authorization", "Bearer " + server.submitter_token()}};
  const httplib::Headers wrk = {{"Authorization", "Bearer " + server.worker_token()}};
  httplib::Client admin("127.0.0.1", port);
  admin.set_read_timeout(60);
  std::vector<std::string> blobs;
  auto put = [&](const std::string& bytes) {
    const std::string h = vesper::sha256_hex(bytes);
    auto r = admin.Put(("/api/v1/blobs/" + h).c_str(), wrk, bytes, "application/octet-stream");
    if (!r || r->status >= 300) throw std::runtime_error("upload failed");
    return h;
  };
  const std::string scene = put(kScene.dump());
  for (const std::string& e : exrs) blobs.push_back(put(e));
  const json job = {{"name", "verify-bench"},
                    {"scene", scene},
                    {"frames", "1-" + std::to_string(exrs.size())},
                    {"spp", 16}};
  auto r = admin.Post("/api/v1/jobs", sub, job.dump(), "application/json");
  if (!r || r->status != 201) throw std::runtime_error("submit failed");
  std::atomic<int> refused{0};
  const auto t0 = Clock::now();
  std::vector<std::thread> threads;
  for (int w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      httplib::Client cl("127.0.0.1", port);
      cl.set_read_timeout(60);
      auto reg = cl.Post("/api/v1/workers/register", wrk,
                         json{{"name", "w" + std::to_string(w)}}.dump(), "application/json");
      const std::string id = json::parse(reg->body).at("worker_id");
      for (;;) {
        auto l = cl.Post("/api/v1/lease", wrk, json{{"worker_id", id}}.dump(), "application/json");
        if (!l || l->status != 200) break;
        const json lj = json::parse(l->body);
        const int frame = lj.at("task").at("frame");
        const json done = {{"lease_id", lj.at("lease_id")}, {"result", blobs[size_t(frame - 1)]}};
        auto d = cl.Post("/api/v1/complete", wrk, done.dump(), "application/json");
        if (!d || d->status != 200) ++refused;
      }
    });
  for (auto& t : threads) t.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  server.stop();
  fs::remove_all(dir);
  if (refused) throw std::runtime_error(std::to_string(refused.load()) + " completions refused");
  return double(exrs.size()) / seconds;
}

}  // namespace

int main(int argc, char** argv) {
  int tasks = 200, workers = 4, size = 256;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    int& out = a == "--tasks" ? tasks : a == "--workers" ? workers : size;
    out = std::max(1, std::atoi(argv[i + 1]));
  }
  spdlog::set_level(spdlog::level::err);
  const fs::path dir =
      fs::temp_directory_path() / ("vesper-verify-bench-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  try {
    std::vector<std::string> exrs;
    for (int f = 1; f <= tasks; ++f) exrs.push_back(exr_of_frame(dir / "frame.exr", size, f, 16));
    // The check alone, on one file.
    vesper::ExpectedResult e;
    e.scene_hash = vesper::SceneHash(kScene).hex();
    e.frame = 1;
    e.sample_end = e.frame_spp = 16;
    e.seed = vesper::frame_seed(0, 1);
    std::ofstream(dir / "one.exr", std::ios::binary) << exrs[0];
    std::vector<double> ms;
    for (int i = 0; i < 50; ++i) {
      const auto t0 = Clock::now();
      if (!vesper::check_result(dir / "one.exr", e).empty()) throw std::runtime_error("refused");
      ms.push_back(1e3 * std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::printf(
        "check_result of one %dx%d 16-channel ZIP EXR (%zu bytes): median %.2f ms "
        "(50 runs)\n",
        size, size, exrs[0].size(), median(ms));
    std::fflush(stdout);
    // Alternating, so that both see the same machine load.
    std::vector<double> off, on;
    for (int round = 0; round < 3; ++round) {
      off.push_back(completions_per_second(dir / "off", false, exrs, workers));
      on.push_back(completions_per_second(dir / "on", true, exrs, workers));
    }
    std::printf(
        "HTTP lease+complete, %d tasks, %d keep-alive workers, median of 3 runs:\n"
        "  verify_results off: %.0f completions/s\n  verify_results on:  %.0f "
        "completions/s (%.2f ms more per completion)\n",
        tasks, workers, median(off), median(on), 1e3 * (1 / median(on) - 1 / median(off)));
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "error: %s\n", ex.what());
    fs::remove_all(dir);
    return 1;
  }
  fs::remove_all(dir);
  return 0;
}
