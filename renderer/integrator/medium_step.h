#pragma once
// The part of a path's step that happens in participating media, between the
// path's vertex and the next surface (only compiled into trace<true>).
#include "renderer/integrator/path_context.h"

namespace vesper {

enum class MediumEvent {
  None,       // no real collision before the surface or the escape: go on there
  Scattered,  // scattered in a medium: the path holds the new ray
  PathEnded,  // absorbed, or scattered at the maximum depth
};

// Samples the media along path.ray up to tmax (the surface hit, or
// infinity): equiangular single scattering toward point lights, delta
// tracking to the next real collision with volume emission on the way, and
// at a scattering event next-event estimation and a Henyey-Greenstein sample
// for the next ray.
MediumEvent sample_medium(PathContext& ctx, float tmax, int depth, PathState& path);

}  // namespace vesper
