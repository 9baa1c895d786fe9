#pragma once
// Photon merging (opt-in, biased and consistent; render.photon_merging):
// volumetric photon mapping (Jensen & Christensen 1998) for the multiple
// scattering of fog lit by small lights. Light subpaths (the light
// tracer's, light_tracer.h) leave a photon at every scattering vertex in a
// medium and on a diffuse surface from light_traced_from events on. A
// camera path's first scattering vertex x in a medium estimates the light
// those paths bring it from the photons y within a radius r of x,
//   L(x, wo) ~ sum_y phase(wo, -dir_y) weight_y / (sigma_s(y) N 4/3 pi r^3),
// N the light subpaths traced; one on a diffuse surface from the photons on
// its plane (normals within 26 degrees; the BSDF drops those from behind),
//   L(x, wo) ~ sum_y f(wo, -dir_y) weight_y / (N pi r^2).
// That is light tracing's part of path space (PathContext::light_traced),
// which the camera paths leave out in the same way. The kernel blurs the
// light over r (bias), and lights the fog within r of a medium's boundary
// less (part of its ball lies outside); both vanish as r -> 0, which the
// radius rule does as the photon count grows (photon_radius). Unlike light
// tracing it needs no pinhole and works in adaptive renders: every camera
// sample reads the same photons.
#include <cstdint>

#include "renderer/bsdf/bsdf.h"
#include "renderer/integrator/photon_map.h"
#include "renderer/math/frame.h"

namespace vesper {

struct PhotonMerging {
  PhotonMap map;          // photons in media
  PhotonMap surface_map;  // photons on diffuse surfaces, the same radius
  uint64_t subpaths = 0;  // N: light subpaths traced (with or without photons)
  // 1 / (N * 4/3 pi r^3) and 1 / (N * pi r^2): the kernels' normalisations.
  float scale() const;
  float surface_scale() const;
};

struct PathContext;
struct PathState;
struct HgPhase;

// Adds the photons' estimate at the camera path's first medium vertex p
// (wo toward the camera), by light group.
void merge_medium_photons(PathContext& ctx, const Vec3& p, const HgPhase& phase, const Vec3& wo,
                          const PathState& path);
// ... at its first surface vertex, on a diffuse BSDF (first_event_light_traced).
void merge_surface_photons(PathContext& ctx, const Vec3& p, const Vec3& n, const Bsdf& bsdf,
                           const Frame& frame, const Vec3& wo, const PathState& path);

// The default radius for `photons` photons spread over a box of `volume`:
// the radius whose ball holds k of them at that mean density, with k
// growing as photons^0.4 (k = 32 at a million), so that r shrinks as
// photons^-0.2: bias and variance both vanish as the count grows.
float photon_radius(double photons, double volume);

}  // namespace vesper
