#include "renderer/render/sampling_plan.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesper {
namespace {

constexpr int64_t kStreams = kSampleStreams;
constexpr int kDefaultMinSpp = 16;

int64_t round_up_to_streams(int64_t n) { return (n + kStreams - 1) / kStreams * kStreams; }

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument("render: " + what); }

void check_positive(std::optional<double> v, const char* field, const char* flag) {
  if (v && !(std::isfinite(*v) && *v > 0))
    bad(std::string(field) + " (" + flag + ") must be a positive number, got " +
        std::to_string(*v));
}

}  // namespace

SamplingPlan plan_sampling(const RenderDesc& r, const RenderOptions& options) {
  SamplingPlan plan;
  plan.noise_target = options.noise_target ? options.noise_target : r.noise_target;
  plan.time_limit = options.time_limit ? options.time_limit : r.time_limit;
  check_positive(plan.noise_target, "render.noise_target", "--noise-target");
  check_positive(plan.time_limit, "render.time_limit", "--time-limit");
  // Not a sampling setting, but checked with the others before a render starts.
  check_positive(options.clamp ? options.clamp : r.clamp, "render.clamp", "--clamp");
  check_positive(options.photon_radius ? options.photon_radius : r.photon_radius,
                 "render.photon_radius", "--photon-radius");
  const std::optional<int> max_spp = options.max_spp ? options.max_spp : r.max_spp;
  const std::optional<int> min_spp = options.min_spp ? options.min_spp : r.min_spp;
  if (max_spp && *max_spp < 1) bad("render.max_spp (--max-spp) must be at least 1");
  if (min_spp && *min_spp < 1) bad("render.min_spp (--min-spp) must be at least 1");
  if (min_spp && max_spp && *min_spp > *max_spp)
    bad("render.min_spp (--min-spp) " + std::to_string(*min_spp) +
        " is greater than render.max_spp (--max-spp) " + std::to_string(*max_spp));
  const std::vector<Aov>& aovs = options.aovs ? *options.aovs : r.aovs;
  const bool crypto = std::find(aovs.begin(), aovs.end(), Aov::Cryptomatte) != aovs.end();
  if (crypto && (options.cryptomatte_depth < 1 || options.cryptomatte_depth > kMaxCryptoDepth))
    bad("cryptomatte_depth must be in [1, " + std::to_string(kMaxCryptoDepth) + "], got " +
        std::to_string(options.cryptomatte_depth));
  plan.begin = options.sample_begin;
  plan.end = options.sample_end.value_or(frame_spp(r, options));
  plan.cap = std::max(0, plan.end - plan.begin);
  plan.seed = options.seed.value_or(r.seed);
  if (plan.cap > kMaxExactSamples)
    bad(std::to_string(plan.cap) + " samples per pixel in one range; at most " +
        std::to_string(kMaxExactSamples) + " fit the exact sample sums (split the range)");
  if (!plan.multipass()) {
    plan.first_pass = plan.cap;
  } else if (plan.noise_target) {
    plan.first_pass = int(std::min<int64_t>(
        plan.cap, round_up_to_streams(min_spp.value_or(std::min(kDefaultMinSpp, plan.cap)))));
  } else {  // a time limit alone: uniform passes
    plan.first_pass = int(std::min<int64_t>(plan.cap, next_sample_count(0, plan.cap)));
  }
  return plan;
}

int frame_spp(const RenderDesc& r, const RenderOptions& options) {
  const int spp = options.spp.value_or(r.spp);
  const bool adaptive = options.noise_target || r.noise_target;
  return adaptive ? (options.max_spp ? *options.max_spp : r.max_spp.value_or(spp)) : spp;
}

void check_sampling_options(const RenderDesc& render, const RenderOptions& options) {
  (void)plan_sampling(render, options);
}

int64_t next_sample_count(int64_t n, int64_t cap) {
  return std::min(cap, n + std::max(kStreams, round_up_to_streams(n / 2)));
}

std::vector<PixelState> pixel_states(const FilmSums& film, std::optional<double> target,
                                     int64_t cap) {
  const int w = film.width, h = film.height;
  std::vector<double> err_sq(film.pixel_count(), 0);
  if (target)
    for (size_t p = 0; p < err_sq.size(); ++p) {
      const double e = pixel_relative_error(film.pixel(p));
      err_sq[p] = std::isfinite(e) ? e * e : INFINITY;
    }
  std::vector<PixelState> state(film.pixel_count(), PixelState::Converged);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      const bool capped = sample_count(film.pixel(p).counts) >= cap;
      if (!target) {
        if (!capped) state[p] = PixelState::Active;
        continue;
      }
      double pooled = 0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          pooled += err_sq[size_t(yy) * size_t(w) + size_t(xx)];
          ++n;
        }
      const double limit = *target * *target;
      if (err_sq[p] > limit || pooled / n > limit)
        state[p] = capped ? PixelState::Capped : PixelState::Active;
    }
  return state;
}

}  // namespace vesper
