#pragma once
// The one interface every light type implements (after pbrt-v4's lights.h:
// SampleLi, PDF_Li, L/Le, Phi, Bounds). Light (light.h) only accepts types
// that satisfy it, so a new light type that misses a method, or declares one
// with another signature, does not compile.
#include <concepts>
#include <optional>

#include "renderer/lights/light_bounds.h"
#include "renderer/lights/light_sample.h"

namespace vesper {

template <typename L>
concept LightInterface = requires(const L& light, const Vec3& p, Vec2 u, const Vec3& wi,
                                  float distance, float scene_radius) {
  // A direction toward the light from the point p, with its radiance and
  // density; u is two uniform numbers (ignored by delta lights). nullopt
  // when the light cannot reach p.
  { light.sample(p, u) } -> std::same_as<std::optional<LightSample>>;
  // The solid-angle density with which sample() picks wi at a point that
  // sees the light `distance` away along wi (infinity for rays that
  // escaped the scene); 0 for delta lights, which no ray can hit.
  { light.pdf(wi, distance) } -> std::same_as<float>;
  // The radiance a ray travelling along wi receives when it reaches the
  // light; black for delta lights.
  { light.emitted(wi) } -> std::same_as<Rgb>;
  // Radiant intensity toward the unit direction wi from the light's centre:
  // point and spot lights, with or without a radius (a sphere light emits
  // it as the radiance I / (pi r^2), sphere_cone.h); black for lights with
  // an area or at infinity.
  { light.intensity_toward(wi) } -> std::same_as<Rgb>;
  // Emitted power in render units (chooses lights); scene_radius bounds
  // the area lit by lights at infinity.
  { light.power(scene_radius) } -> std::same_as<float>;
  // Where the light sits in render space; nullopt for lights at infinity.
  { light.bounds() } -> std::same_as<std::optional<LightBounds>>;
};

}  // namespace vesper
