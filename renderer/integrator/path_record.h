#pragma once
// Per-path bookkeeping for layers and light-transport AOVs: every radiance
// contribution is binned by what the path did first after the camera, by
// whether it is direct (one scattering event) or indirect (more), and by the
// light group it ends at. Only allocated when layers or transport AOVs are
// requested, so plain renders pay nothing.
#include <cstdint>
#include <vector>

#include "renderer/math/rgb.h"

namespace vesper {

enum class FirstEvent : uint8_t {
  SurfaceView = 0,  // no scattering: lights, environment, background seen directly
  VolumeView = 1,   // no scattering: volume emission seen directly
  Diffuse = 2,      // first scattering event: the diffuse lobe of a surface
  Specular = 3,     // ... a specular/glossy lobe of a surface
  Volume = 4,       // ... a medium
};
inline constexpr int kFirstEventKinds = 5;

class PathRecord {
 public:
  explicit PathRecord(int groups = 1)
      : groups_(groups), bins_(size_t(kFirstEventKinds * 2 * groups)) {}

  int groups() const { return groups_; }
  static size_t bin(FirstEvent kind, bool indirect, int group, int groups) {
    return size_t((int(kind) * 2 + (indirect ? 1 : 0)) * groups + group);
  }
  const std::vector<Rgb>& bins() const { return bins_; }

  void reset() {
    std::fill(bins_.begin(), bins_.end(), Rgb{});
    first_volume_ = false;
    diffuse_fraction_ = Rgb(1.f);
  }
  // Called at the first scattering event.
  void set_first_volume() { first_volume_ = true; }
  void set_first_surface(const Rgb& diffuse_fraction) {
    first_volume_ = false;
    diffuse_fraction_ = diffuse_fraction;
  }
  // A contribution whose first event is known without the path having made
  // it (equiangular samples at the camera segment are volume events).
  void add_as(FirstEvent kind, bool indirect, int group, const Rgb& value) {
    bins_[bin(kind, indirect, group, groups_)] += value;
  }
  // The indirect sample clamp (PathContext::clamp_indirect).
  void scale_indirect(float s) {
    for (int kind = 0; kind < kFirstEventKinds; ++kind)
      for (int g = 0; g < groups_; ++g) bins_[bin(FirstEvent(kind), true, g, groups_)] *= s;
  }
  // `events`: scattering events before the light was reached (0 = seen
  // directly). `diffuse_fraction` overrides the split of the first surface
  // event (next-event estimation at that event uses its own lobe split).
  void add(const Rgb& value, int events, int group, bool volume_view = false,
           const Rgb* diffuse_fraction = nullptr) {
    if (events == 0) {
      bins_[bin(volume_view ? FirstEvent::VolumeView : FirstEvent::SurfaceView, false, group,
                groups_)] += value;
      return;
    }
    const bool indirect = events > 1;
    if (first_volume_) {
      bins_[bin(FirstEvent::Volume, indirect, group, groups_)] += value;
      return;
    }
    const Rgb& f = diffuse_fraction ? *diffuse_fraction : diffuse_fraction_;
    const Rgb diffuse = value * f;
    bins_[bin(FirstEvent::Diffuse, indirect, group, groups_)] += diffuse;
    bins_[bin(FirstEvent::Specular, indirect, group, groups_)] += value - diffuse;
  }

 private:
  int groups_;
  std::vector<Rgb> bins_;
  bool first_volume_ = false;
  Rgb diffuse_fraction_{1.f};
};

// Per-channel a / b with 0 where b is 0 (a lobe's share of a BSDF value).
inline Rgb safe_ratio(const Rgb& a, const Rgb& b) {
  return {b.r > 0.f ? a.r / b.r : 0.f, b.g > 0.f ? a.g / b.g : 0.f, b.b > 0.f ? a.b / b.b : 0.f};
}

}  // namespace vesper
