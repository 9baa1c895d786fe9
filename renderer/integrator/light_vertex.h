#pragma once
// Light-vertex connections: the strategy for multiple scattering from point
// and spot lights (issue 11). Each camera sample traces one vertex from a
// light (its first scattering in a medium, or its first diffuse surface), and
// every scattering vertex of the camera path connects to it: the two-segment
// strategy of bidirectional path tracing (Veach 1997; Lafortune & Willems
// 1996 for media), restricted to light subpaths of one vertex.
//
// It finds what the path tracer finds only by chance: fog lit by the bright
// pool a spot light makes on the floor, and fog beside a shaft lit by the
// fog inside it. The path x -> y -> light is also made by the path tracer
// (a ray from x that scatters at y, then next-event estimation; or the
// equiangular estimate on that ray), so the strategies share it by MIS:
// u = P_light^2 / (P_light^2 + P_path^2) goes to the connection and (1 - u)
// scales the path tracer's estimates (whose own equiangular/distance MIS
// weights sum to 1). P_path is the density of y for the path tracer's
// distance sampling and light choice (and its equiangular sampling: see
// light_vertex_weight), P_light that of the light vertex; both
// are deterministic functions of (x, y, light), evaluated by the same code
// on both sides, so the weights are a partition of unity and the sum is
// unbiased. Point and spot lights take part, with or without a radius: a
// sphere light's ray takes a direction in its cone as a point light's does,
// then leaves a point of the hemisphere facing that direction (uniform in
// projected area), and the weights compare densities of the pair (light
// point, y), where next-event estimation picks the light point by solid
// angle (sphere_cone.h).
#include <optional>

#include "renderer/core/ray.h"
#include "renderer/math/rgb.h"
#include "renderer/sampling/sampler.h"
#include "renderer/scene/scene.h"

namespace vesper {

struct LightVertex {
  Vec3 p;
  Vec3 n{};  // geometric normal of a surface vertex; zero in a medium
  size_t light = 0;
  Vec3 light_point;  // where the light ray left: the light's position, or a point on its sphere
  Rgb alpha;         // emitted * flight weight / (pmf * emission pdfs): the flux it carries
  uint32_t material = 0;  // surface vertices
  float g = 0;            // phase asymmetry of medium vertices
  bool on_surface() const { return n.x != 0.f || n.y != 0.f || n.z != 0.f; }
};

// The default (RenderOptions::light_vertices unset): where the connections
// paid for themselves in vesper_volume_bench. Off without media or without
// a point or spot light. On where every medium is
// homogeneous (fog-shafts, point-fog, the night room) or a light that takes
// part sits inside a scattering medium (a lantern in a cloud VDB: 5.9x at
// equal error); off otherwise (the smoke VDB, its light outside the voxels:
// 1.65x slower at equal error, the shadow rays and majorant walks costing
// more than the noise they remove).
bool light_vertices_pay_off(const Scene& scene);

// Where a light subpath starts: a point or spot light (with or without a
// radius) chosen by power, a point on it and a direction, as light vertices
// and the light tracer (light_tracer.h) sample them.
struct LightRayStart {
  size_t light = 0;
  Vec3 origin, dir;
  float weight = 0;  // per unit intensity: 1 / (light pmf * emission pdfs)
};
std::optional<LightRayStart> sample_light_ray(const Scene& scene, Sampler& sampler);
// The intensity the start's light sends toward its subpath's first vertex p
// (a spot's depends on p's direction from its centre); black for a p at the
// light, which leaves no direction.
Rgb light_ray_intensity(const Scene& scene, const LightRayStart& start, const Vec3& p);
// Whether light subpaths start at this light (point and spot lights with power).
bool light_is_traced(const Scene& scene, size_t light);

// Traces one light vertex at shutter time `time`; nullopt when the light ray
// left the scene, was absorbed, or hit an emitter or a specular surface.
std::optional<LightVertex> trace_light_vertex(const Scene& scene, float time, Sampler& sampler,
                                              uint32_t& rays);

// Which of the path tracer's strategies for x -> y -> light run: equiangular
// sampling on the ray from x (PathTracerOptions::equiangular and
// equiangular_in_cone) counts in P_path when it does.
struct PathStrategies {
  bool equiangular = true;
  bool equiangular_in_cone = true;
};

// The weight u above for the path x -> y -> light_point on `light`, where x
// made the ray toward y with direction pdf `pdf_x` (solid angle) and y has
// the geometric normal n_y (zero in a medium). `n_y_shading` is the normal
// the path tracer's light choice at y uses (ShadingPoint::n). 0 when the
// light does not take part.
//
// In a medium P_path^2 is the sum of the squares of two densities of y:
// distance sampling then next-event estimation, and equiangular sampling on
// the ray from x. Near a point light both x and y can be close to it, and
// then neither distance sampling (y's 1/r^2 to the light) nor the connection
// (1/|x - y|^2) is bounded, but equiangular sampling toward the light is:
// counting it here hands those paths to it (point-fog's fireflies). Its
// density is evaluated over the media along the whole ray from x, not up to
// the surface the ray hits: any deterministic stand-in keeps the weights a
// partition of unity, and this one needs no extra ray.
float light_vertex_weight(const Scene& scene, const Vec3& x, float pdf_x, const Vec3& y,
                          const Vec3& n_y, const Vec3& n_y_shading, size_t light,
                          const Vec3& light_point, float time, const PathStrategies& strategies);

}  // namespace vesper
