#pragma once
// The scene target's files in the sandbox (fuzz_target.h): cube.obj,
// quad.obj, pyramid.ply (copied from the repository), sky.exr (an 8x4
// environment image) and cloud.vdb (an 8^3 "density" fog volume), written
// once per process.
#include <filesystem>

namespace vesper::fuzz {

const std::filesystem::path& scene_sandbox();

}  // namespace vesper::fuzz
