#include "renderer/media/media_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesper {

bool Box3::clip(const Vec3& o, const Vec3& d, float tmax, float* t0, float* t1) const {
  float a = 0.f, b = tmax;
  for (int i = 0; i < 3; ++i) {
    const float inv = 1.f / d[i];  // +-inf for axis-parallel rays: handled by the comparisons
    float tn = (lo[i] - o[i]) * inv, tf = (hi[i] - o[i]) * inv;
    if (std::isnan(tn) || std::isnan(tf)) {  // o on the slab plane with d[i] == 0
      if (o[i] < lo[i] || o[i] > hi[i]) return false;
      continue;
    }
    if (tn > tf) std::swap(tn, tf);
    a = std::max(a, tn);
    b = std::min(b, tf);
    if (a > b) return false;
  }
  *t0 = a;
  *t1 = b;
  return b > a;
}

MediaSet::MediaSet(std::vector<Medium> media) : media_(std::move(media)) {
  for (const auto& m : media_)
    if (const auto* g = std::get_if<GridMedium>(&m); g && g->emission) has_emission_ = true;
}

namespace {
float max_sigma_t(const Rgb& sa, const Rgb& ss) { return (sa + ss).max_component(); }

void spans_of(const Medium& medium, const Ray& ray, float tmax, std::vector<MajorantSpan>& out) {
  if (const auto* h = std::get_if<HomogeneousMedium>(&medium)) {
    const float sigma = max_sigma_t(h->sigma_a, h->sigma_s);
    if (sigma <= 0.f) return;
    float t0 = 0.f, t1 = tmax;
    if (h->bounded && !h->box_at(ray.time).clip(ray.origin, ray.dir, tmax, &t0, &t1)) return;
    out.push_back({t0, t1, sigma, true});
    return;
  }
  const auto& g = std::get<GridMedium>(medium);
  const float scale = g.density_scale * max_sigma_t(g.sigma_a, g.sigma_s);
  if (scale <= 0.f) return;
  const Vec3 o = g.index_point(ray.origin, ray.time), d = g.index_vector(ray.dir, ray.time);
  g.majorants->walk(o, d, 0.f, tmax, [&](const MajorantSegment& s) {
    if (s.max_density > 0.f) out.push_back({s.t0, s.t1, s.max_density * scale, false});
    return true;
  });
}
}  // namespace

void MediaSet::majorant_spans(const Ray& ray, float tmax, std::vector<MajorantSpan>& out) const {
  out.clear();
  if (media_.size() == 1) {
    spans_of(media_[0], ray, tmax, out);
    return;
  }
  // Several media: sweep over the span boundaries, summing the majorants.
  thread_local std::vector<MajorantSpan> all;
  all.clear();
  for (const auto& m : media_) spans_of(m, ray, tmax, all);
  if (all.empty()) return;
  struct Event {
    float t;
    float sigma;
    int non_analytic;
  };
  thread_local std::vector<Event> events;
  events.clear();
  for (const auto& s : all) {
    events.push_back({s.t0, s.sigma_maj, s.analytic ? 0 : 1});
    events.push_back({s.t1, -s.sigma_maj, s.analytic ? 0 : -1});
  }
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  double sigma = 0;
  int non_analytic = 0, active = 0;
  for (size_t i = 0; i + 1 < events.size(); ++i) {
    sigma += events[i].sigma;
    non_analytic += events[i].non_analytic;
    active += events[i].sigma > 0 ? 1 : -1;
    const float a = events[i].t, b = events[i + 1].t;
    if (active <= 0 || !(b > a)) continue;
    const float s = float(std::max(sigma, 0.0));
    if (s <= 0.f) continue;
    // Grow the previous span when nothing changed (common with aligned cells).
    if (!out.empty() && out.back().t1 == a && out.back().sigma_maj == s &&
        out.back().analytic == (non_analytic == 0))
      out.back().t1 = b;
    else
      out.push_back({a, b, s, non_analytic == 0});
  }
}

MediumCoefficients MediaSet::coefficients(const Vec3& p, float time) const {
  MediumCoefficients c;
  for (const auto& m : media_) {
    if (const auto* h = std::get_if<HomogeneousMedium>(&m)) {
      if (!h->contains(p, time)) continue;
      c.sigma_a += h->sigma_a;
      c.sigma_s += h->sigma_s;
    } else {
      const auto& g = std::get<GridMedium>(m);
      const float d = g.density->sample(g.index_point(p, time)) * g.density_scale;
      if (d > 0.f) {
        c.sigma_a += g.sigma_a * d;
        c.sigma_s += g.sigma_s * d;
      }
    }
  }
  return c;
}

float MediaSet::pick_phase_g(const Vec3& p, float u, float time) const {
  if (media_.size() == 1) {
    return std::visit([](const auto& m) { return m.g; }, media_[0]);
  }
  float weights[16];
  float total = 0.f;
  const size_t n = std::min<size_t>(media_.size(), 16);
  for (size_t i = 0; i < n; ++i) {
    float w = 0.f;
    if (const auto* h = std::get_if<HomogeneousMedium>(&media_[i])) {
      if (h->contains(p, time)) w = h->sigma_s.average();
    } else {
      const auto& g = std::get<GridMedium>(media_[i]);
      w = g.density->sample(g.index_point(p, time)) * g.density_scale * g.sigma_s.average();
    }
    weights[i] = std::max(w, 0.f);
    total += weights[i];
  }
  float x = u * total;
  for (size_t i = 0; i < n; ++i) {
    if (x < weights[i]) return std::visit([](const auto& m) { return m.g; }, media_[i]);
    x -= weights[i];
  }
  return std::visit([](const auto& m) { return m.g; }, media_[n - 1]);
}

}  // namespace vesper
