#pragma once
// Lat-long (equirectangular) environment images and their direction mapping.
//
// Convention (also in docs/scene-format.md). For image coordinates
// (u, v) in [0,1]^2, u to the right and v downward (row 0 is the top row):
//   theta = v * pi           (polar angle from +Y: the top row looks straight up)
//   phi   = 2 * pi * u       (azimuth)
//   dir   = (sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi))
// so u = 0 (and 1) looks toward -Z, u = 0.25 toward +X, u = 0.5 toward +Z and
// u = 0.75 toward -X; inversely phi = atan2(x, -z) wrapped to [0, 2*pi).
// Pixel (i, j) covers u in [i, i+1) / width, v in [j, j+1) / height.
//
// The light's `rotation` (degrees) then turns the map about +Y,
// counter-clockwise seen from above (the right-hand rule about +Y):
//   world = R_y(rotation) * dir,  R_y(a)(x, y, z) = (x cos a + z sin a, y, -x sin a + z cos a).
#include <cmath>
#include <filesystem>
#include <string>

#include "renderer/math/constants.h"
#include "renderer/math/vec.h"
#include "renderer/scene/scene_description.h"

namespace vesper {

// Unrotated map direction for image coordinates (u, v).
inline Vec3 env_latlong_direction(float u, float v) {
  const float theta = v * kPi, phi = 2.f * kPi * u;
  const float st = std::sin(theta);
  return {st * std::sin(phi), std::cos(theta), -st * std::cos(phi)};
}

// Inverse of env_latlong_direction for a unit direction: (u, v) in [0,1]^2.
inline Vec2 env_latlong_uv(const Vec3& d) {
  float phi = std::atan2(d.x, -d.z);
  if (phi < 0.f) phi += 2.f * kPi;
  const float theta = std::acos(clamp(d.y, -1.f, 1.f));
  return {phi * kInv2Pi, theta * kInvPi};
}

// Reads an image with OpenImageIO into linear RGB floats. Uses the first three
// channels; one- and two-channel (grey, grey+alpha) images are replicated to
// grey RGB. Integer-encoded images tagged (or, untagged, assumed) sRGB are
// linearized; float images are taken as linear. Rejects NaN, Inf and negative
// pixels with a SceneError naming `scene_file`, `json_path`, `path` and the
// pixel position.
EnvironmentImage load_environment_image(const std::filesystem::path& path,
                                        const std::string& scene_file,
                                        const std::string& json_path);

}  // namespace vesper
