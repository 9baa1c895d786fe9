#include "server/result_check.h"

#include <OpenImageIO/imageio.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "common/json_parse.h"
#include "common/scene_hash.h"
#include "renderer/output/metadata_keys.h"
#include "renderer/sampling/random_hash.h"
#include "server/blob_store.h"

namespace fs = std::filesystem;

namespace vesper {
namespace {

namespace key = metadata_key;

std::string read_file(const fs::path& file, const std::string& what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + what + " (" + file.string() + ")");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Each field the result states, as text, against what the task expects;
// the first difference is the answer.
struct Comparison {
  std::string problem;
  void expect(const std::string& name, const std::string& got, const std::string& want,
              const std::string& what) {
    if (!problem.empty() || got == want) return;
    problem = got.empty() ? name + " is missing, " + what + " " + want
                          : name + " is '" + got + "', " + what + " " + want;
  }
  void check(const ExpectedResult& e, const std::string& scene_hash, const std::string& frame,
             const std::string& begin, const std::string& end, const std::string& seed) {
    expect(key::kSceneHash, scene_hash, e.scene_hash, "the task's scene hashes to");
    expect(key::kFrame, frame, std::to_string(e.frame), "the task renders frame");
    expect(key::kSampleBegin, begin, std::to_string(e.sample_begin), "the task's range begins at");
    expect(key::kSampleEnd, end, std::to_string(e.sample_end), "the task's range ends at");
    expect(key::kSeed, seed, std::to_string(e.seed), "the task's seed is");
  }
  // Without the override the scene's film.pixel_type decides (not checked).
  void check_pixel_type(const ExpectedResult& e, const std::string& pixel_type) {
    if (e.half) expect(key::kPixelType, pixel_type, "half", "the job asks for");
  }
};

std::string check_exr(const fs::path& file, const ExpectedResult& e) {
  // Blobs have no extension: ask the OpenEXR reader itself.
  auto in = OIIO::ImageInput::create("openexr");
  OIIO::ImageSpec spec;
  if (!in || !in->open(file.string(), spec)) {
    OIIO::geterror();
    return "not an OpenEXR image (a whole-frame task's result must be one)";
  }
  auto text = [&spec](const char* name) {
    const OIIO::ParamValue* p = spec.find_attribute(name);
    return p ? p->get_string() : std::string();
  };
  Comparison c;
  c.check(e, text(key::kSceneHash), text(key::kFrame), text(key::kSampleBegin),
          text(key::kSampleEnd), text(key::kSeed));
  c.check_pixel_type(e, text(key::kPixelType));
  if (!c.problem.empty()) return c.problem;
  // The last scanline too: a truncated file opens but would fail every reader
  // later. Not every pixel: decoding a noisy 256x256 16-channel frame cost
  // 122 ms against 2-3 ms for this (bench/README.md, vesper_verify_bench).
  // A tiled image (not what the renderer writes) is read whole.
  std::vector<float> pixels;
  bool read = false;
  if (spec.tile_width == 0) {
    pixels.resize(size_t(spec.width) * size_t(spec.nchannels));
    const int last = spec.y + spec.height - 1;
    read = in->read_scanlines(0, 0, last, last + 1, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                              pixels.data());
  } else {
    pixels.resize(size_t(spec.image_pixels()) * size_t(spec.nchannels));
    read = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  }
  if (!read) {
    const std::string why = in->geterror();
    return "an OpenEXR image whose pixels cannot be read: " + why;
  }
  return {};
}

std::string check_partial(const fs::path& file, const ExpectedResult& e) {
  static constexpr char kMagic[] = "VESPER-PARTIAL\n";
  std::ifstream in(file, std::ios::binary);
  char magic[sizeof kMagic - 1] = {};
  in.read(magic, sizeof magic);
  if (size_t(in.gcount()) != sizeof magic || std::memcmp(magic, kMagic, sizeof magic) != 0)
    return "not a vesper partial render (a sample-range task's result must be one)";
  std::string line;
  if (!std::getline(in, line) || in.eof()) return "a partial render whose header is truncated";
  const std::streamoff body_start = in.tellg();
  nlohmann::json h;
  try {
    h = parse_json(line, "partial header");
  } catch (const std::exception& ex) {
    return std::string("a partial render whose header is not JSON: ") + ex.what();
  }
  auto text = [](const nlohmann::json& o, const char* name) -> std::string {
    if (!o.is_object() || !o.contains(name)) return {};
    const auto& v = o.at(name);
    return v.is_string() ? v.get<std::string>() : v.dump();
  };
  if (!h.is_object() || text(h, "format") != "vesper-partial/2")
    return "a partial render of another format than vesper-partial/2";
  Comparison c;
  c.check(e, text(h, "scene_hash"), text(h.value("metadata", nlohmann::json()), key::kFrame),
          text(h, "sample_begin"), text(h, "sample_end"), text(h, "seed"));
  c.expect("frame_spp", text(h, "frame_spp"), std::to_string(e.frame_spp), "the job's spp is");
  c.check_pixel_type(e, text(h.value("metadata", nlohmann::json()), key::kPixelType));
  if (!c.problem.empty()) return c.problem;
  in.seekg(0, std::ios::end);
  const std::string body = std::to_string(in.tellg() - body_start);
  const std::string declared = text(h.value("sums", nlohmann::json()), "compressed_bytes");
  if (declared != body)
    return "a partial render of " + body + " body bytes whose header declares " +
           (declared.empty() ? "none" : declared);
  return {};
}

}  // namespace

std::string check_result(const fs::path& file, const ExpectedResult& expected) {
  return expected.partial ? check_partial(file, expected) : check_exr(file, expected);
}

ExpectedResult ResultExpectations::of(const Lease& lease) {
  ExpectedResult e;
  e.frame = lease.task.frame;
  e.sample_begin = lease.task.sample_begin;
  e.sample_end = lease.task.sample_end;
  e.frame_spp = lease.spp;
  // As the worker decides (worker/render_command.cpp: renders_partial).
  e.partial = e.sample_begin != 0 || e.sample_end != lease.spp;
  e.half = lease.overrides.half;
  const Scene scene = this->scene(lease);
  e.scene_hash = scene.hash;
  // `vesper render --frame N` mixes the frame into the seed (cli/render_command.cpp).
  e.seed = frame_seed(lease.overrides.seed.value_or(scene.seed), e.frame);
  return e;
}

ResultExpectations::Scene ResultExpectations::scene(const Lease& lease) {
  const int64_t job = lease.task.job_id;
  const int frame = lease.task.frame;
  {
    std::lock_guard lock(mutex_);
    for (const int key : {kEveryFrame, frame})
      if (const auto it = scenes_.find({job, key}); it != scenes_.end()) return it->second;
  }
  const auto scene_file = blobs_.file(lease.scene);
  if (!scene_file) throw std::runtime_error("the job's scene blob " + lease.scene + " is missing");
  const nlohmann::json raw = parse_json(read_file(*scene_file, "the scene"), "scene");
  // The renderer hashes the document of the frame it loads (--frame N).
  const nlohmann::json doc = frame_document(raw, frame, "scene");
  Scene scene;
  const auto render = doc.find("render");
  if (render != doc.end() && render->is_object() && render->contains("seed") &&
      render->at("seed").is_number_unsigned())
    scene.seed = render->at("seed").get<uint64_t>();
  SceneHash hash(doc);
  for (const std::string& ref : frame_file_references(doc, frame)) {
    // The worker renders in a directory holding the assets by name
    // (--scene-dir-only): a reference names the asset at its normal path.
    const std::string want = normal_asset_name(ref);
    const Asset* asset = nullptr;
    for (const Asset& a : lease.assets)
      if (normal_asset_name(a.name) == want) asset = &a;
    const auto file = asset ? blobs_.file(asset->blob) : std::nullopt;
    if (!file)
      throw std::runtime_error("the scene references '" + ref +
                               "', which no asset of the job holds");
    hash.add_file(read_file(*file, "asset '" + asset->name + "'"));
  }
  scene.hash = hash_with_shutter(hash.hex(), shutter_state(raw, frame, "scene"));
  std::lock_guard lock(mutex_);
  return scenes_[{job, is_animated(raw) ? frame : kEveryFrame}] = scene;
}

}  // namespace vesper
