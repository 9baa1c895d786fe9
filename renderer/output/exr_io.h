#pragma once
// Multi-layer OpenEXR in and out (through OpenImageIO).
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

#include "renderer/output/layered_image.h"

namespace vesper {

struct ImageIoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A multi-part file whose parts do not fit together (read_exr_all_parts);
// the message starts with the file's name.
struct ExrPartsError : ImageIoError {
  using ImageIoError::ImageIoError;
};

struct ExrWriteReport {
  // Half colour values beyond ±65504 or not finite, written as ±65504 (0 for
  // NaN); also the header's vesper:half_clamped and a warning in the log.
  uint64_t half_clamped = 0;
};

// Writes the channels and metadata. float32 unless the metadata's
// vesper:pixel_type is "half" (then colour channels are half, data channels
// stay float32: exr_encoding.h); compressed as vesper:compression says
// (zip by default). Numeric metadata become typed attributes
// (metadata_keys.h). The file appears atomically: it is written next to
// `path` under a temporary name and renamed, so a crash never leaves a
// half-written image behind.
ExrWriteReport write_exr(const LayeredImage& image, const std::filesystem::path& path);

// Reads every channel of the first part (subimage) as float.
LayeredImage read_exr(const std::filesystem::path& path);

// Reads every channel of every part as float, in one image: a part's
// channels that carry no layer prefix are named `<part name>.<channel>`,
// except in the first part (the default part, where the beauty lives) and
// in a part named "rgba". Throws ExrPartsError naming the file when two
// parts give the same channel or when parts differ in size. Metadata: the first
// part's.
LayeredImage read_exr_all_parts(const std::filesystem::path& path);

// Only the `vesper:*` metadata (read_exr's `metadata`), from the header.
std::map<std::string, std::string> read_exr_metadata(const std::filesystem::path& path);

}  // namespace vesper
