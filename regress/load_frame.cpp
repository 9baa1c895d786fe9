#include "regress/load_frame.h"

#include <system_error>

#include "regress/compare.h"
#include "renderer/output/exr_io.h"

namespace vesper::regress {

std::optional<LayeredImage> load_frame(const std::filesystem::path& path, const std::string& role,
                                       SceneResult& result) {
  auto fail = [&](const std::string& reason) -> std::optional<LayeredImage> {
    result.verdict = Verdict::Error;
    result.reasons.push_back(reason);
    return std::nullopt;
  };
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    const std::string hint = role == "golden" ? " (run with --update-goldens to create it)" : "";
    return fail("no " + role + " image " + path.string() + hint);
  }
  try {
    LayeredImage image = read_exr(path);
    if (image.width <= 0 || image.height <= 0 || image.channels.empty())
      return fail(role + " image " + path.string() + " has no pixels");
    return image;
  } catch (const std::exception& e) {
    return fail(role + " image unreadable: " + e.what());  // what() names the file
  }
}

SceneResult compare_files(const std::string& scene, const std::filesystem::path& golden,
                          const std::filesystem::path& fresh,
                          const std::vector<std::string>* layers, const Thresholds& thresholds) {
  SceneResult result;
  const auto g = load_frame(golden, "golden", result);
  const auto f = load_frame(fresh, "new render", result);
  if (g && f) result = compare_frames(*g, *f, layers, thresholds);
  result.name = scene;
  result.golden_image = golden.string();
  result.new_image = fresh.string();
  return result;
}

}  // namespace vesper::regress
