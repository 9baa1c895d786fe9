#pragma once
// The camera as OpenEXR's worldToCamera / worldToNDC attributes (M44f), in
// world units, Imath's row-vector convention p' = p * M (matrices row-major,
// translation in the last row), as Nuke's camera-from-EXR tools read them:
// - camera space is right-handed: x right, y up, the camera looks down -Z;
// - NDC: (p * worldToNDC) divided by its w (the distance in front of the
//   camera) gives x from -1 (left edge) to +1 (right edge) and y from -1
//   (bottom) to +1 (top) over the image; its z is 1 / distance.
// OpenEXR's header comments describe RenderMan's spaces instead (+Z forward,
// NDC 0..1 with y down): docs/compositing.md gives the conversion.
#include <array>

#include "renderer/scene/scene_description.h"

namespace vesper {

struct CameraMatrices {
  std::array<double, 16> world_to_camera{}, world_to_ndc{};
};

CameraMatrices camera_matrices(const CameraDesc& camera, const FilmDesc& film);

// The tangents of the half field of view across x and y (fov spans the
// shorter side), as the renderer's camera uses them.
std::array<double, 2> camera_tan_half(const CameraDesc& camera, const FilmDesc& film);

}  // namespace vesper
