#pragma once
// The `vesper:*` keys of an image's metadata (EXR header attributes): the one
// place their names are spelled. README.md lists them for users.
#include <array>
#include <string_view>
#include <utility>

namespace vesper::metadata_key {

// read_exr keeps the header attributes whose names start with this.
inline constexpr char kPrefix[] = "vesper:";

// One sample range of a frame, written by render() (and by merge_partials()
// for the union of the ranges); a partial carries them as its own fields.
inline constexpr char kSceneHash[] = "vesper:scene_hash";
inline constexpr char kSpp[] = "vesper:spp";  // samples in the range
inline constexpr char kSampleBegin[] = "vesper:sample_begin";
inline constexpr char kSampleEnd[] = "vesper:sample_end";
inline constexpr char kSeed[] = "vesper:seed";
inline constexpr char kRendererVersion[] = "vesper:renderer_version";
inline constexpr char kRenderSeconds[] = "vesper:render_seconds";
inline constexpr char kNonfiniteSamples[] = "vesper:nonfinite_samples";
inline constexpr std::array<const char*, 8> kRangeKeys{
    kSceneHash,       kSpp,           kSampleBegin,     kSampleEnd, kSeed,
    kRendererVersion, kRenderSeconds, kNonfiniteSamples};

// Adaptive sampling and budgets (render.noise_target, render.time_limit).
inline constexpr char kNoiseTarget[] = "vesper:noise_target";
inline constexpr char kTimeLimit[] = "vesper:time_limit";
// Figures of the samples taken, which differ between the partials of a frame:
// a partial carries them in its metadata, and merge_partials() recomputes
// (noise, spp) or combines (stop reason, passes) them for the merged frame.
// noise_reached: RMS over pixels of the estimated relative error of the mean
// (film_sums.h); spp_mean: mean samples per pixel.
inline constexpr char kNoiseReached[] = "vesper:noise_reached";
inline constexpr char kSppMean[] = "vesper:spp_mean";
inline constexpr char kStopReason[] = "vesper:stop_reason";
inline constexpr char kSamplingPasses[] = "vesper:sampling_passes";
inline constexpr std::array<const char*, 4> kPerRangeFigures{kNoiseReached, kSppMean, kStopReason,
                                                             kSamplingPasses};

// render.clamp / --clamp (biased): the indirect sample clamp, when set.
inline constexpr char kClamp[] = "vesper:clamp";
// render.photon_merging / --photon-merging (biased), when it ran: "radius R
// photons P subpaths N", what sets its bias.
inline constexpr char kPhotonMerging[] = "vesper:photon_merging";
// render.shutter (motion blur), when set: "open close" in frames relative to
// the frame; and the motion steps the camera and shapes were sampled at
// (absent when nothing moves over the shutter).
inline constexpr char kShutter[] = "vesper:shutter";
inline constexpr char kMotionSteps[] = "vesper:motion_steps";
// render_frame(): the number of render passes (beauty + variant layers).
inline constexpr char kPasses[] = "vesper:passes";
// `vesper render --frame N`.
inline constexpr char kFrame[] = "vesper:frame";
// The compositor's output: the recipe's label and the pixels' colour space.
inline constexpr char kCompRecipe[] = "vesper:comp_recipe";
inline constexpr char kCompColorspace[] = "vesper:comp_colorspace";

// The film's EXR encoding (film.pixel_type / --half, film.compression), set
// only when not the default (float, zip); write_exr() encodes the file so.
inline constexpr char kPixelType[] = "vesper:pixel_type";
inline constexpr char kCompression[] = "vesper:compression";
// Values of half colour channels beyond ±65504 (or not finite) that
// write_exr() clamped; only in a file that had any.
inline constexpr char kHalfClamped[] = "vesper:half_clamped";

// OpenEXR's standard camera attributes (M44f), for Nuke and friends: 16
// numbers, row-major, in the metadata map (renderer/output/camera_matrices.h).
inline constexpr char kWorldToCamera[] = "worldToCamera";
inline constexpr char kWorldToNdc[] = "worldToNDC";

// How write_exr() types a key's text in the EXR header, so that readers get
// numbers (oiiotool shows `int`/`double`): counts as int (a count beyond a
// 32-bit int stays text), seconds and figures as double, the camera as M44f.
// The 64-bit seed stays text: EXR has no 64-bit integer attribute. Anything
// not listed is text. read_exr() turns them back into the same text.
enum class MetadataType { Text, Int, Double, Matrix44 };

inline constexpr std::array<std::pair<std::string_view, MetadataType>, 17> kTypedKeys{{
    {kSpp, MetadataType::Int},
    {kSampleBegin, MetadataType::Int},
    {kSampleEnd, MetadataType::Int},
    {kNonfiniteSamples, MetadataType::Int},
    {kSamplingPasses, MetadataType::Int},
    {kPasses, MetadataType::Int},
    {kFrame, MetadataType::Int},
    {kHalfClamped, MetadataType::Int},
    {kMotionSteps, MetadataType::Int},
    {kRenderSeconds, MetadataType::Double},
    {kNoiseTarget, MetadataType::Double},
    {kTimeLimit, MetadataType::Double},
    {kNoiseReached, MetadataType::Double},
    {kSppMean, MetadataType::Double},
    {kClamp, MetadataType::Double},
    {kWorldToCamera, MetadataType::Matrix44},
    {kWorldToNdc, MetadataType::Matrix44},
}};

constexpr MetadataType metadata_type(std::string_view key) {
  for (const auto& [k, t] : kTypedKeys)
    if (k == key) return t;
  return MetadataType::Text;
}

}  // namespace vesper::metadata_key
