#pragma once
// The one-sample defensive mixture of a vertex's own scattering (phase
// function or BSDF) and the light guide (light_guide.h) for the ray that
// leaves the vertex.
#include <optional>

#include "renderer/integrator/light_guide.h"
#include "renderer/media/henyey_greenstein.h"
#include "renderer/sampling/sampler.h"

namespace vesper {

// Share of the phase function in the mixture: bounds the path weight f / pdf
// by 1 / kPhaseShare where the guide adds nothing.
inline constexpr float kPhaseShare = 0.5f;

struct GuidedDirection {
  Vec3 wi;
  float pdf = 0;     // of the mixture, for MIS against light sampling
  float weight = 0;  // phase(wi) / pdf
};

// Uses 3 sampler dimensions, whichever strategy draws. Without lights to aim
// at it is phase sampling (weight 1). nullopt when the guide's direction is
// degenerate (a vertex at the light's aim point).
inline std::optional<GuidedDirection> sample_guided_phase(const HgPhase& phase,
                                                          const LightGuide& guide, const Vec3& wo,
                                                          Sampler& sampler) {
  const float uc = sampler.next1();
  const Vec2 u = sampler.next2();
  if (guide.empty()) {
    const Vec3 wi = phase.sample(wo, u);
    return GuidedDirection{wi, phase.pdf(wo, wi), 1.f};
  }
  Vec3 wi;
  if (uc < kPhaseShare) {
    wi = phase.sample(wo, u);
  } else {
    const std::optional<Vec3> g = guide.sample((uc - kPhaseShare) / (1.f - kPhaseShare), u);
    if (!g) return std::nullopt;
    wi = *g;
  }
  const float f = phase.eval(wo, wi);
  const float pdf = kPhaseShare * phase.pdf(wo, wi) + (1.f - kPhaseShare) * guide.pdf(wi);
  if (!(pdf > 0.f)) return std::nullopt;
  return GuidedDirection{wi, pdf, f / pdf};
}

}  // namespace vesper
