#include "renderer/render/photon_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <vector>

#include "renderer/integrator/light_tracer.h"

namespace vesper {
namespace {

constexpr uint64_t kSubpathsPerTask = 1024;

}  // namespace

uint64_t photon_subpaths(const Scene& scene, int frame_spp) {
  const uint64_t pixels = uint64_t(scene.film.width) * uint64_t(scene.film.height);
  return std::min(pixels * uint64_t(std::max(frame_spp, 1)), kMaxPhotonSubpaths);
}

PhotonPassResult trace_photons(const Scene& scene, const PathTracerOptions& pt, uint64_t seed,
                               int frame_spp, float radius, int threads,
                               const std::function<void(uint64_t)>& progress) {
  const uint64_t pixels = uint64_t(scene.film.width) * uint64_t(scene.film.height);
  const uint64_t total = photon_subpaths(scene, frame_spp);
  const uint64_t tasks = (total + kSubpathsPerTask - 1) / kSubpathsPerTask;
  // Each task's photons in their own vector, joined in task order: the map
  // is the same for any thread count.
  std::vector<std::vector<Photon>> per_task(tasks);
  std::atomic<uint64_t> rays{0}, nonfinite{0};
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, tasks, 1), [&](const auto& r) {
      for (uint64_t task = r.begin(); task != r.end(); ++task) {
        uint32_t task_rays = 0;
        uint64_t task_nonfinite = 0;
        std::vector<Photon>& out = per_task[task];
        const uint64_t end = std::min(total, (task + 1) * kSubpathsPerTask);
        for (uint64_t i = task * kSubpathsPerTask; i < end; ++i) {
          // Subpath k of sample index s: the light tracer's sampler stream.
          Sampler sampler(seed, pixels + i % pixels, i / pixels);
          const size_t before = out.size();
          trace_photon_path(scene, pt, sampler, task_rays, out);
          const auto bad = std::remove_if(out.begin() + std::ptrdiff_t(before), out.end(),
                                          [](const Photon& p) { return !p.weight.is_finite(); });
          task_nonfinite += uint64_t(out.end() - bad);
          out.erase(bad, out.end());
        }
        rays += task_rays;
        nonfinite += task_nonfinite;
        progress(end - task * kSubpathsPerTask);
      }
    });
  });
  // Joined in task order; media and surfaces apart. The radius follows
  // the media's photons (their box's volume), or the surfaces' where there
  // are none.
  std::vector<Photon> photons, surface;
  for (auto& v : per_task) {
    for (const Photon& p : v) (p.n == Vec3(0.f) ? photons : surface).push_back(p);
    std::vector<Photon>().swap(v);
  }
  const std::vector<Photon>& sizing = photons.empty() ? surface : photons;
  Vec3 lo(0.f), hi(0.f);
  for (size_t i = 0; i < sizing.size(); ++i) {
    lo = i == 0 ? sizing[i].p : min(lo, sizing[i].p);
    hi = i == 0 ? sizing[i].p : max(hi, sizing[i].p);
  }
  const Vec3 extent = hi - lo;
  const double volume = double(extent.x) * double(extent.y) * double(extent.z);
  if (!(radius > 0.f)) radius = photon_radius(double(sizing.size()), volume);
  if (!(radius > 0.f)) radius = 1e-3f;  // no photons, or all in a plane: nothing to find
  PhotonPassResult result;
  result.photons.map = PhotonMap(std::move(photons), radius);
  result.photons.surface_map = PhotonMap(std::move(surface), radius);
  result.photons.subpaths = total;
  result.rays = rays;
  result.nonfinite = nonfinite;
  return result;
}

}  // namespace vesper
