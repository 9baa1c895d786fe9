// The `half` render override on the farm (`vesper submit --half`, a job
// file's "half": true): fetched frames have half-float colour channels and
// are bitwise `vesper render --half --frame N`, merged split frames too, and
// a float job's results are never reused for a half one; `vesper up --half`.
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "tests/cli/farm_test_fixture.h"

namespace vesper::test {
namespace {

// Channel name -> its format in the file, as OIIO reads the header.
std::map<std::string, OIIO::TypeDesc> channel_formats(const std::filesystem::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  std::map<std::string, OIIO::TypeDesc> out;
  if (!in) {
    ADD_FAILURE() << file << ": " << OIIO::geterror();
    return out;
  }
  for (int c = 0; c < in->spec().nchannels; ++c)
    out[in->spec().channel_name(c)] = in->spec().channelformat(c);
  return out;
}

class FarmHalf : public FarmTest {
 protected:
  // `fetched` (in frames/) is bitwise the local `vesper render --half --frame N`.
  void expect_local_half(const std::filesystem::path& scene, const std::string& fetched,
                         int frame) {
    const auto local = dir_ / fmt::format("local-half.{}.exr", frame);
    const RunResult r = run(
        fmt::format("render {} -o {} --half --frame {} -q", scene.string(), local.string(), frame));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_bitwise_equal(dir_ / "frames" / fetched, local);
    EXPECT_EQ(channel_formats(dir_ / "frames" / fetched), channel_formats(local));
  }
};

TEST_F(FarmHalf, AHalfJobIsHalfBitwiseTheLocalRenderAndNotAFloatJobsReuse) {
  const auto config = write_config(10);
  const auto scene = write_scene(24, 18, 4);
  start_server(config);
  start_worker("w1", config);
  const long long plain = submit(scene.string() + " --frames 2 --name plain");
  ASSERT_EQ(wait_finished(plain, 120).at("counts").at("done"), 1);
  const long long half = submit(scene.string() + " --frames 2 --half --name half");
  const auto j = wait_finished(half, 120);
  ASSERT_EQ(j.at("counts").at("done"), 1) << j.dump();
  EXPECT_FALSE(j.at("tasks").at(0).contains("reused_from")) << j.dump();
  for (const long long id : {plain, half})
    ASSERT_EQ(farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string())).exit_code, 0);

  const auto formats = channel_formats(dir_ / "frames/half.0002.exr");
  for (const char* c : {"R", "G", "B"}) EXPECT_EQ(formats.at(c), OIIO::TypeDesc::HALF) << c;
  for (const auto& [name, format] : channel_formats(dir_ / "frames/plain.0002.exr"))
    EXPECT_EQ(format, OIIO::TypeDesc::FLOAT) << name;
  expect_local_half(scene, "half.0002.exr", 2);
  // The half frame is not the float one (quantised colour).
  EXPECT_NE(read_exr(dir_ / "frames/half.0002.exr").pixels,
            read_exr(dir_ / "frames/plain.0002.exr").pixels);
}

// A job file's "half": a frame split into sample ranges merges into a half
// EXR, bitwise the single local half render.
TEST_F(FarmHalf, AHalfJobFileSplitFrameMergesToTheLocalHalfRender) {
  const auto config = write_config(10);
  const auto scene = write_scene(24, 18, 10);
  const auto job_file = dir_ / "job.json";
  std::ofstream(job_file) << fmt::format(
      R"({{"format": "vesper-job/1", "scene": "{}", "frames": 3, "samples_per_task": 4,
          "name": "split", "half": true}})",
      scene.string());
  start_server(config);
  start_worker("w1", config);
  const long long id = submit(job_file.string());
  const auto j = wait_finished(id, 120);
  ASSERT_EQ(j.at("counts").at("done"), 3) << j.dump();  // [0,4) [4,8) [8,10)
  ASSERT_EQ(farm(fmt::format("fetch {} -o {}", id, (dir_ / "frames").string())).exit_code, 0);
  const auto formats = channel_formats(dir_ / "frames/split.0003.exr");
  for (const char* c : {"R", "G", "B"}) EXPECT_EQ(formats.at(c), OIIO::TypeDesc::HALF) << c;
  expect_local_half(scene, "split.0003.exr", 3);
}

// `vesper up --half`: the frames it fetches are half (and composite).
TEST_F(FarmHalf, UpHalfFetchesHalfFramesAndComposites) {
  const auto scene = write_scene(24, 18, 4);
  std::ofstream(scene.parent_path() / "comp.json") << R"({
    "format": "vesper-comp/1", "inputs": {"frame": "unused.exr"},
    "layers": [{"layer": "beauty"}], "outputs": {"image": "x.png"}})";
  const RunResult r =
      run(fmt::format("up --scene {} --frames 5 --workers 1 --half --data-dir {} -o {}",
                      scene.string(), (dir_ / "farm").string(), (dir_ / "frames").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto formats = channel_formats(dir_ / "frames/scene.0005.exr");
  for (const char* c : {"R", "G", "B"}) EXPECT_EQ(formats.at(c), OIIO::TypeDesc::HALF) << c;
  expect_local_half(scene, "scene.0005.exr", 5);
  // (one frame: the composite has no frame number)
  EXPECT_TRUE(std::filesystem::exists(dir_ / "frames/scene.comp.png")) << r.out;
}

}  // namespace
}  // namespace vesper::test
