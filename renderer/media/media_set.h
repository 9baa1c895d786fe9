#pragma once
// All media of a scene, queried along rays: a piecewise-constant grey
// majorant (sum over the media a ray crosses) and the coefficients at a point.
#include <vector>

#include "renderer/media/medium.h"

namespace vesper {

struct MajorantSpan {
  float t0 = 0, t1 = 0;
  float sigma_maj = 0;    // >= max over channels of sigma_t anywhere in the span
  bool analytic = false;  // only homogeneous media: sigma_t is constant in the span
};

// Whether a ray's spans cross a grid medium (some span is not analytic).
inline bool crosses_grid(const std::vector<MajorantSpan>& spans) {
  for (const MajorantSpan& s : spans)
    if (!s.analytic) return true;
  return false;
}

struct MediumCoefficients {
  Rgb sigma_a, sigma_s;
};

class MediaSet {
 public:
  MediaSet() = default;
  explicit MediaSet(std::vector<Medium> media);

  bool empty() const { return media_.empty(); }
  bool has_emission() const { return has_emission_; }
  const std::vector<Medium>& media() const { return media_; }

  // Spans over [0, tmax] of the ray (tmax may be infinite), front to back;
  // gaps without any medium are left out. `out` is cleared first. Moving
  // media are where they are at ray.time (motion blur).
  void majorant_spans(const Ray& ray, float tmax, std::vector<MajorantSpan>& out) const;
  // At p, at shutter time `time` (motion blur; a still medium ignores it).
  MediumCoefficients coefficients(const Vec3& p, float time = 0.f) const;
  // Henyey-Greenstein g of the medium that scattered at p, picked with
  // probability proportional to each medium's average sigma_s there.
  float pick_phase_g(const Vec3& p, float u, float time = 0.f) const;

 private:
  std::vector<Medium> media_;
  bool has_emission_ = false;
};

}  // namespace vesper
