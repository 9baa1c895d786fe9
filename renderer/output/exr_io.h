#pragma once
// Multi-layer OpenEXR in and out (through OpenImageIO).
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

#include "renderer/output/layered_image.h"

namespace vesper {

struct ImageIoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes float32 channels and metadata. The file appears atomically: it is
// written next to `path` under a temporary name and renamed, so a crash never
// leaves a half-written image behind.
void write_exr(const LayeredImage& image, const std::filesystem::path& path);

// Reads every channel of the first subimage as float.
LayeredImage read_exr(const std::filesystem::path& path);

// Only the `vesper:*` metadata (read_exr's `metadata`), from the header.
std::map<std::string, std::string> read_exr_metadata(const std::filesystem::path& path);

}  // namespace vesper
