#pragma once
// Whether equiangular sampling toward a light is worth its shadow ray on a
// ray through grid media. There the distance-sampling density is known only
// by a proxy and the transmittance to the sampled distance only by ratio
// tracking, so equiangular samples cost more and weigh worse than in
// homogeneous media. Measured at equal error (time x relMSE, as
// vesper_volume_bench does), toward every light they cost 1.2x on the smoke
// scene and 1.75x in a thick generated cloud around a sphere light, while a
// thin cloud with a point light inside gained; with this reach (2 mean free
// paths) the thick cloud was 0.96x and the thin one kept its gain.
#include <cmath>
#include <vector>

#include "renderer/integrator/equiangular.h"
#include "renderer/media/media_set.h"

namespace vesper {

// Optical distance (mean free paths) beyond which a light is out of reach.
inline constexpr double kEquiangularReach = 2.0;
// The least angle (radians) a grid segment must subtend at the light. Below
// it 1 / r^2 barely changes along the segment, and distance sampling with
// next-event estimation does as well for less: on the smoke scene (its
// point light outside the voxels) equiangular cost 1.12x at equal error
// with no angle rule, 1.03x at 0.5 and 1.01x at 1.0, while the lantern
// (a point light inside a thin cloud) kept its 1.8x gain at either
// (vesper_volume_bench smoke lantern). Homogeneous rays keep every angle:
// there the same rule cost fog-shafts 2.4x.
inline constexpr float kEquiangularMinGridAngle = 1.0f;

// True unless the ray crosses a grid medium and the segment subtends less
// than kEquiangularMinGridAngle at the light, or the light is out of reach:
// its optical distance from the segment's start, along the ray to the point
// nearest the light and then straight to the light, at the majorants (an
// upper bound, and no density lookups), is kEquiangularReach or more. A
// deterministic function of (ray, light), as the MIS weights need
// (equiangular_sampling.h). Rays through homogeneous media only always pass:
// their MIS weights are exact, and their images stay as they were.
inline bool light_within_reach(const EquiangularSegment& seg,
                               const std::vector<MajorantSpan>& spans) {
  if (!crosses_grid(spans)) return true;
  if (seg.angle < kEquiangularMinGridAngle) return false;
  const float t_near = std::fmin(std::fmax(seg.delta, seg.ta), seg.tb);
  double optical = 0;
  float sigma_near = 0;  // the majorant where the ray is nearest the light
  for (const MajorantSpan& s : spans) {
    sigma_near = s.sigma_maj;
    if (s.t1 >= t_near) {
      optical += double(s.sigma_maj) * std::fmax(0.f, t_near - s.t0);
      break;
    }
    optical += double(s.sigma_maj) * (s.t1 - s.t0);
  }
  const double along = double(seg.delta) - t_near;
  const double dist = std::sqrt(double(seg.dist) * seg.dist + along * along);
  return optical + sigma_near * dist < kEquiangularReach;
}

// Optical depth (mean free paths, by the majorants) from the start of the
// ray's media beyond which equiangular sampling places no distance.
inline constexpr double kEquiangularDepth = 4.0;

// The spans of a ray through grid media up to where their majorant optical
// depth reaches kEquiangularDepth (the last one cut there), into `out`:
// beyond, the transmittance is below e^-4 by any estimate and ratio
// tracking's estimate of it mostly noise, so delta tracking alone takes
// those distances (equiangular_pdf is 0 there). Rays through homogeneous
// media only keep all their spans.
inline void spans_within_depth(const std::vector<MajorantSpan>& spans,
                               std::vector<MajorantSpan>& out) {
  out.clear();
  const bool grid = crosses_grid(spans);
  double optical = 0;
  for (MajorantSpan s : spans) {
    const double span_depth = double(s.sigma_maj) * (s.t1 - s.t0);
    if (grid && optical + span_depth > kEquiangularDepth) {
      s.t1 = s.t0 + float((kEquiangularDepth - optical) / s.sigma_maj);
      out.push_back(s);
      return;
    }
    optical += span_depth;
    out.push_back(s);
  }
}

}  // namespace vesper
