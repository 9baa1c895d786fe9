#pragma once
// Photon merging (opt-in, biased and consistent; render.photon_merging):
// volumetric photon mapping (Jensen & Christensen 1998) for the multiple
// scattering of fog lit by small lights. Light subpaths (the light
// tracer's, light_tracer.h) leave a photon at every scattering vertex in a
// medium from light_traced_from events on; a camera path's first scattering
// vertex x in a medium estimates the light those paths bring it from the
// photons within a radius r of x,
//   L(x, wo) sigma_s(x) ~ sum_p phase(wo, -dir_p) weight_p / (N * 4/3 pi r^3),
// N the light subpaths traced. That takes the same part of path space as
// light tracing (PathContext::light_traced), so the camera paths leave it
// out in the same way. The kernel blurs the light over r (bias), and lights
// the fog within r of a medium's boundary less (part of its sphere lies
// outside); both vanish as r -> 0, which the radius rule does as the photon
// count grows (photon_radius). Unlike light tracing it needs no pinhole and
// works in adaptive renders: every camera sample reads the same photons.
#include <cstdint>

#include "renderer/integrator/photon_map.h"

namespace vesper {

struct PhotonMerging {
  PhotonMap map;
  uint64_t subpaths = 0;  // N: light subpaths traced (with or without photons)
  // 1 / (N * 4/3 pi r^3): the kernel's normalisation.
  float scale() const;
};

// The default radius for `photons` photons spread over a box of `volume`:
// the radius whose ball holds k of them at that mean density, with k
// growing as photons^0.4 (k = 32 at a million), so that r shrinks as
// photons^-0.2: bias and variance both vanish as the count grows.
float photon_radius(double photons, double volume);

}  // namespace vesper
