// The farm renders each frame's own state: keyframes and `####` files
// evaluated per frame on the workers, bitwise `vesper render --frame N`, and
// result reuse by the frame's evaluated state.
#include <fmt/format.h>

#include "renderer/volume/vdb_io.h"
#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class FarmAnimation : public FarmTest {
 protected:
  // The small Cornell box with `edit` applied to its document.
  std::filesystem::path write_animated(const std::function<void(nlohmann::json&)>& edit) {
    const auto p = write_scene(24, 18, 2);
    nlohmann::json doc = nlohmann::json::parse(slurp(p));
    edit(doc);
    std::ofstream(p) << doc.dump(2);
    return p;
  }

  void render_local_and_compare(const std::filesystem::path& scene, const std::string& fetched,
                                int frame) {
    const auto local = dir_ / fmt::format("local.{}.exr", frame);
    const RunResult r =
        run(fmt::format("render {} -o {} --frame {} -q", scene.string(), local.string(), frame));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // (Pixels only: the farm's scene hash is of the packed scene, which names assets.)
    expect_bitwise_equal(dir_ / "frames" / fetched, local);
    EXPECT_EQ(read_exr(dir_ / "frames" / fetched).metadata.at("vesper:frame"),
              std::to_string(frame));
  }
};

TEST_F(FarmAnimation, FrameSevenOfAnAnimatedJobIsBitwiseTheLocalRender) {
  const auto config = write_config(10);
  const auto scene = write_animated([](nlohmann::json& doc) {
    doc["camera"]["from"] =
        nlohmann::json::parse(R"({"keys": [[1, [0, 1, 3.9]], [9, [0.6, 1.3, 3.4]]],
                                                      "interp": "smooth"})");
    doc["lights"][0]["radiance"] =
        nlohmann::json::parse(R"({"keys": [[1, [17, 12, 4]], [9, [4, 12, 17]]]})");
  });
  start_server(config);
  start_worker("w1", config);
  const long long id = submit(scene.string() + " --frames 6-7 --name anim");
  ASSERT_EQ(wait_finished(id, 120).at("counts").at("done"), 2);
  const RunResult f = farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string()));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  render_local_and_compare(scene, "anim.0007.exr", 7);
  render_local_and_compare(scene, "anim.0006.exr", 6);
  EXPECT_NE(read_exr(dir_ / "frames/anim.0006.exr").metadata.at("vesper:scene_hash"),
            read_exr(dir_ / "frames/anim.0007.exr").metadata.at("vesper:scene_hash"));
}

// The server checks each result's scene hash: under a shutter the renderer's
// hash covers the motion, and the server's must too, or every task fails.
TEST_F(FarmAnimation, AMotionBlurredFrameIsAcceptedAndBitwiseTheLocalRender) {
  const auto config = write_config(10);
  const auto scene = write_animated([](nlohmann::json& doc) {
    doc["render"]["shutter"] = {-0.25, 0.25};
    doc["camera"]["from"] =
        nlohmann::json::parse(R"({"keys": [[1, [0, 1, 3.9]], [9, [0.6, 1.3, 3.4]]]})");
  });
  start_server(config);
  start_worker("w1", config);
  const long long id = submit(scene.string() + " --frames 4 --name blur");
  ASSERT_EQ(wait_finished(id, 120).at("counts").at("done"), 1);
  const RunResult f = farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string()));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  render_local_and_compare(scene, "blur.0004.exr", 4);
  EXPECT_EQ(read_exr(dir_ / "frames/blur.0004.exr").metadata.at("vesper:motion_steps"), "2");
}

TEST_F(FarmAnimation, AVdbSequenceJobRendersFrameNFromFileN) {
  const auto config = write_config(10);
  // Three frames of a box of smoke, each denser than the last.
  std::filesystem::create_directories(dir_ / "scene");
  for (int f = 1; f <= 3; ++f) {
    DenseVolume v;
    v.nx = v.ny = v.nz = 4;
    v.voxel_size = 0.15;
    v.origin = {-0.3, 0.5, -0.3};
    v.values.assign(64, 2.0f * float(f));
    write_vdb_fog_volume(v, "density", dir_ / "scene" / fmt::format("smoke.{:04d}.vdb", f), 1e-6f);
  }
  const auto scene = write_animated([](nlohmann::json& doc) {
    doc["media"] = {{"smoke", {{"type", "vdb"}, {"file", "smoke.####.vdb"}}}};
  });
  start_server(config);
  start_worker("w1", config);
  const long long id = submit(scene.string() + " --frames 2-3 --name smoke");
  ASSERT_EQ(wait_finished(id, 120).at("counts").at("done"), 2);
  const RunResult f = farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string()));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  render_local_and_compare(scene, "smoke.0002.exr", 2);
  render_local_and_compare(scene, "smoke.0003.exr", 3);
  // Each task's directory holds its own frame of the sequence only.
  int task_dirs = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir_ / "cache-w1")) {
    if (e.path().filename() != "scene.json") continue;
    ++task_dirs;
    int vdbs = 0;
    for (const auto& f : std::filesystem::recursive_directory_iterator(e.path().parent_path()))
      vdbs += f.path().extension() == ".vdb";
    EXPECT_EQ(vdbs, 1) << e.path();
  }
  EXPECT_EQ(task_dirs, 2);
  // Frame 3 read smoke.0003.vdb: rendering it with frame 2's file differs.
  std::filesystem::copy_file(dir_ / "scene/smoke.0002.vdb", dir_ / "scene/smoke.0003.vdb",
                             std::filesystem::copy_options::overwrite_existing);
  const auto swapped = dir_ / "swapped.exr";
  ASSERT_EQ(
      run(fmt::format("render {} -o {} --frame 3 -q", scene.string(), swapped.string())).exit_code,
      0);
  EXPECT_NE(read_exr(swapped).pixels, read_exr(dir_ / "frames/smoke.0003.exr").pixels);
}

TEST_F(FarmAnimation, AfterAnEditOnlyTheFramesItChangesRenderAgain) {
  const auto config = write_config(10);
  // fov 37 up to frame 2, then to 45 at frame 4.
  auto keyed = [](double last) {
    return [last](nlohmann::json& doc) {
      doc["camera"]["fov"] = {{"keys", {{1, 37}, {2, 37}, {4, last}}}};
    };
  };
  const auto scene = write_animated(keyed(45));
  start_server(config);
  start_worker("w1", config);
  const long long first = submit(scene.string() + " --frames 1-4 --name first");
  ASSERT_EQ(wait_finished(first, 120).at("counts").at("done"), 4);
  write_animated(keyed(50));  // frames 3 and 4 change, 1 and 2 do not
  const long long second = submit(scene.string() + " --frames 1-4 --name second");
  const auto j = wait_finished(second, 120);
  ASSERT_EQ(j.at("counts").at("done"), 4) << j.dump();
  EXPECT_EQ(count(worker_log("w1"), "): leased"), 6) << worker_log("w1");
  const auto f = job(first);
  for (int i = 0; i < 2; ++i)
    EXPECT_EQ(j.at("tasks").at(i).at("reused_from"), f.at("tasks").at(i).at("id")) << i;
  for (int i = 2; i < 4; ++i) EXPECT_FALSE(j.at("tasks").at(i).contains("reused_from")) << i;
  // The reused frames are the edited scene's frames, bit for bit.
  ASSERT_EQ(farm(fmt::format("fetch {} -o {}", second, (dir_ / "frames").string())).exit_code, 0);
  render_local_and_compare(scene, "second.0001.exr", 1);
  render_local_and_compare(scene, "second.0004.exr", 4);
}

}  // namespace
}  // namespace vesper::test
