#pragma once
// The images a comparison needs, read so that a missing or corrupt file is
// an `error` result with a clear reason, never an exception or a crash.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "regress/regress_result.h"
#include "regress/suite.h"
#include "renderer/output/layered_image.h"

namespace vesper::regress {

// Reads the EXR at `path`; on failure returns nullopt and turns `result` into
// an Error whose reason names the role ("golden", "new render") and the file:
// "no golden image goldens/cornell.exr (run with --update-goldens to create it)",
// "golden image unreadable: cannot read goldens/cornell.exr: <why>".
std::optional<LayeredImage> load_frame(const std::filesystem::path& path, const std::string& role,
                                       SceneResult& result);

// Loads both images and compares them (compare_frames); the result carries
// the scene's name and both paths, and is an Error if either cannot be read.
SceneResult compare_files(const std::string& scene, const std::filesystem::path& golden,
                          const std::filesystem::path& fresh,
                          const std::vector<std::string>* layers, const Thresholds& thresholds);

}  // namespace vesper::regress
