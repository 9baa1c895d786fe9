#include "renderer/integrator/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/integrator/direct_lighting.h"
#include "renderer/integrator/equiangular.h"
#include "renderer/integrator/volume_tracking.h"
#include "renderer/math/frame.h"
#include "renderer/media/henyey_greenstein.h"

namespace vesper {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool is_transmissive(const Bsdf& bsdf) { return std::holds_alternative<DielectricBsdf>(bsdf); }

// Adds a contribution to the pixel and, for layers/AOVs, to the path record.
struct Contributions {
  PathResult& result;
  PathRecord* record;
  void add(const Rgb& value, int events, int group, bool volume_view = false,
           const Rgb* diffuse_fraction = nullptr) {
    result.radiance += value;
    if (record) record->add(value, events, group, volume_view, diffuse_fraction);
  }
};

// Emitted radiance from infinite lights for an escaped ray, MIS-weighted
// against the BSDF or phase sample that produced it.
void add_escaped_radiance(const Scene& scene, const Vec3& dir, bool count_fully, float scatter_pdf,
                          const Rgb& throughput, int events, Contributions& out) {
  for (uint32_t li : scene.infinite_lights) {
    const Light& light = scene.lights[li];
    Rgb le;
    float light_pdf = 0.f;
    if (const auto* env = std::get_if<EnvironmentLight>(&light)) {
      le = env->emitted(dir);
      if (!count_fully) light_pdf = env->pdf(dir);
    } else if (const auto* sun = std::get_if<SunLight>(&light)) {
      le = sun->emitted(dir);
      if (!count_fully) light_pdf = sun->pdf(dir);
    }
    if (le.is_black()) continue;
    const float w =
        count_fully ? 1.f : power_heuristic(scatter_pdf, scene.light_sampler.pmf(li) * light_pdf);
    out.add(throughput * le * w, events, scene.light_group[li]);
  }
}

// Continues the path (Russian roulette); false = terminated.
bool russian_roulette(int depth, const PathTracerOptions& options, Sampler& sampler,
                      Rgb& throughput) {
  if (depth + 1 >= options.rr_start_depth) {
    const float q = std::max(0.05f, 1.f - throughput.max_component());
    if (sampler.next1() < q) return false;
    throughput *= 1.f / (1.f - q);
  }
  return throughput.is_finite();
}

template <bool kMedia>
PathResult trace(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                 const PathTracerOptions& options) {
  PathResult result;
  if (options.record) options.record->reset();
  Contributions out{result, options.record};
  Rgb throughput(1.f);
  Ray ray = camera_ray;
  bool count_emission_fully = true;  // camera ray or delta bounce: no MIS partner
  float prev_scatter_pdf = 0.f;
  const bool have_lights = !scene.light_sampler.empty();

  for (int depth = 0;; ++depth) {
    const std::optional<SurfaceHit> hit = scene.accel->intersect(ray);
    ++result.rays;
    if (depth == 0 && hit) {
      result.alpha = 1.f;
      if (options.want_aovs) {
        result.depth = float(hit->t * scene.unit_scale);
        result.normal = dot(hit->n, ray.dir) < 0.f ? hit->n : -hit->n;
      }
    }

    if constexpr (kMedia) {
      const float tmax = hit ? hit->t : kInfinity;
      thread_local std::vector<MajorantSpan> spans;
      scene.media.majorant_spans(ray, tmax, spans);
      if (depth == 0 && options.want_camera_transmittance)
        result.camera_transmittance =
            estimate_transmittance(scene.media, ray, tmax, sampler).average();
      const bool analytic =
          !spans.empty() &&
          std::all_of(spans.begin(), spans.end(), [](const MajorantSpan& s) { return s.analytic; });
      const bool use_equiangular =
          options.equiangular && analytic && have_lights && depth < options.max_depth;
      auto equiangular_pdf = [&](size_t li, float t) -> float {
        const Vec3* lp = point_light_position(scene.lights[li]);
        if (!lp) return 0.f;
        const auto seg =
            EquiangularSegment::make(ray.origin, ray.dir, *lp, spans.front().t0, spans.back().t1);
        return seg ? seg->pdf(t) : 0.f;
      };
      if (use_equiangular) {
        // Equiangular strategy: one distance per segment toward a chosen point/spot light.
        float pmf = 0.f, u_rest = 0.f;
        const size_t li = scene.light_sampler.sample(sampler.next1(), &pmf, &u_rest);
        const Vec2 u_eq = sampler.next2();
        const Vec3* lp = point_light_position(scene.lights[li]);
        const auto seg = lp ? EquiangularSegment::make(ray.origin, ray.dir, *lp, spans.front().t0,
                                                       spans.back().t1)
                            : std::nullopt;
        if (seg && pmf > 0.f) {
          const float t = seg->sample(u_eq.x);
          const float pdf_e = seg->pdf(t);
          const Vec3 x = ray.origin + ray.dir * t;
          const MediumCoefficients c = scene.media.coefficients(x);
          const auto ls = sample_light(scene.lights[li], x, {});
          if (pdf_e > 0.f && !c.sigma_s.is_black() && ls && !ls->radiance.is_black()) {
            const HgPhase phase{scene.media.pick_phase_g(x, u_eq.y)};
            const float f = phase.eval(-ray.dir, ls->wi);
            const Rgb tr_light = shadow_transmittance<kMedia>(
                scene, x, ls->wi, ls->distance * (1.f - 1e-4f), sampler, result.rays);
            if (!tr_light.is_black()) {
              const float pdf_a = analytic_scatter_pdf(scene.media, spans, ray, t);
              const float w = power_heuristic(pdf_e, pdf_a);
              const Rgb tr = analytic_transmittance(scene.media, spans, ray, t);
              const Rgb value =
                  throughput * tr * c.sigma_s * ls->radiance * tr_light * (f * w / (pdf_e * pmf));
              // At depth 0 this scatter would be the path's first event: a volume one.
              if (depth == 0 && options.record) {
                result.radiance += value;
                options.record->add_as(FirstEvent::Volume, false, scene.light_group[li], value);
              } else {
                out.add(value, depth + 1, scene.light_group[li]);
              }
            }
          }
        }
      }
      Rgb emitted;
      const FreeFlight ff =
          sample_free_flight(scene.media, spans, ray, sampler, throughput, emitted);
      if (!emitted.is_black()) out.add(emitted, depth, scene.emission_group, depth == 0);
      if (ff.event == FlightEvent::Absorbed) break;
      if (ff.event == FlightEvent::Scattered) {
        if (depth >= options.max_depth) break;
        if (depth == 0 && options.record) options.record->set_first_volume();
        const Vec3 p = ray.origin + ray.dir * ff.t;
        const Vec3 wo = -ray.dir;
        const HgPhase phase{ff.g};
        if (have_lights) {
          auto eval_phase = [&](const Vec3& wi) {
            const float f = phase.eval(wo, wi);
            return std::tuple{Rgb(f), Rgb{}, f};
          };
          DirectSample ds;
          if (use_equiangular) {
            const float pdf_a = analytic_scatter_pdf(scene.media, spans, ray, ff.t);
            auto delta_weight = [&](size_t li) {
              return power_heuristic(pdf_a, equiangular_pdf(li, ff.t));
            };
            ds = sample_direct<kMedia>(scene, p, Vec3(0.f), sampler, result.rays, eval_phase,
                                       delta_weight);
          } else {
            ds = sample_direct<kMedia>(scene, p, Vec3(0.f), sampler, result.rays, eval_phase);
          }
          if (!ds.value.is_black())
            out.add(throughput * ds.value, depth + 1, scene.light_group[ds.light]);
        } else {
          sampler.next1();
          sampler.next2();
        }
        const Vec3 wi = phase.sample(wo, sampler.next2());
        prev_scatter_pdf = phase.pdf(wo, wi);  // f / pdf = 1: throughput unchanged
        count_emission_fully = false;
        ray = Ray{p, wi};
        if (!russian_roulette(depth, options, sampler, throughput)) break;
        continue;
      }
    }

    if (!hit) {
      add_escaped_radiance(scene, ray.dir, count_emission_fully, prev_scatter_pdf, throughput,
                           depth, out);
      break;
    }

    // Emitters are one-sided and do not reflect: the path ends here.
    if (hit->light >= 0) {
      const auto& ql = std::get<QuadLight>(scene.lights[size_t(hit->light)]);
      const Rgb le = ql.emitted(ray.dir);
      if (!le.is_black()) {
        float w = 1.f;
        if (!count_emission_fully) {
          const float light_pdf =
              scene.light_sampler.pmf(size_t(hit->light)) * ql.pdf(ray.dir, hit->t);
          w = power_heuristic(prev_scatter_pdf, light_pdf);
        }
        out.add(throughput * le * w, depth, scene.light_group[size_t(hit->light)]);
      }
      break;
    }
    if (depth >= options.max_depth) break;

    const Bsdf& bsdf = scene.materials[hit->material];
    // Opaque BSDFs are two-sided: shade with the normal facing the viewer.
    // Dielectrics keep the geometric orientation (outside = normal side).
    const Vec3 wo_world = -ray.dir;
    const bool transmissive = is_transmissive(bsdf);
    const Vec3 n_shading = (!transmissive && dot(hit->n, wo_world) < 0.f) ? -hit->n : hit->n;
    const Frame frame = Frame::from_normal(n_shading);
    const Vec3 wo = frame.to_local(wo_world);
    if (depth == 0 && options.want_aovs) result.albedo = bsdf_albedo(bsdf);

    // Next-event estimation.
    if (have_lights && !bsdf_is_delta(bsdf)) {
      const DirectSample ds = sample_direct<kMedia>(
          scene, hit->p, hit->n, sampler, result.rays, [&](const Vec3& wi_world) {
            const Vec3 wi = frame.to_local(wi_world);
            const float cos = std::abs(wi.z);
            return std::tuple{bsdf_eval(bsdf, wo, wi) * cos,
                              options.record ? bsdf_eval_diffuse(bsdf, wo, wi) * cos : Rgb{},
                              bsdf_pdf(bsdf, wo, wi)};
          });
      if (!ds.value.is_black()) {
        const Rgb fraction = safe_ratio(ds.diffuse, ds.value);
        out.add(throughput * ds.value, depth + 1, scene.light_group[ds.light], false,
                depth == 0 ? &fraction : nullptr);
      }
    } else {
      // Keep the sample dimensions aligned whether or not NEE ran.
      sampler.next1();
      sampler.next2();
    }

    // Continue the path by sampling the BSDF.
    const float uc = sampler.next1();
    const Vec2 u = sampler.next2();
    const auto bs = bsdf_sample(bsdf, wo, uc, u);
    if (!bs || bs->pdf <= 0.f || bs->f.is_black()) break;
    if (depth == 0 && options.record)
      options.record->set_first_surface(
          bs->is_specular ? Rgb{} : safe_ratio(bsdf_eval_diffuse(bsdf, wo, bs->wi), bs->f));
    throughput *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
    count_emission_fully = bs->is_specular;
    prev_scatter_pdf = bs->pdf;

    const Vec3 wi_world = normalize(frame.to_world(bs->wi));
    const Vec3 n_off = dot(wi_world, hit->n) >= 0.f ? hit->n : -hit->n;
    ray = Ray{offset_ray_origin(hit->p, n_off), wi_world};
    if (!russian_roulette(depth, options, sampler, throughput)) break;
  }
  return result;
}

}  // namespace

PathResult trace_path(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                      const PathTracerOptions& options) {
  // Scenes without media get a path tracer compiled without any medium code.
  return scene.media.empty() ? trace<false>(scene, camera_ray, sampler, options)
                             : trace<true>(scene, camera_ray, sampler, options);
}

}  // namespace vesper
