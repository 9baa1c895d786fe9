#include "renderer/integrator/path_tracer.h"

#include <cmath>

#include "renderer/math/frame.h"

namespace vesper {
namespace {

bool is_transmissive(const Bsdf& bsdf) { return std::holds_alternative<DielectricBsdf>(bsdf); }

// Emitted radiance from infinite lights for an escaped ray, MIS-weighted
// against the BSDF sample that produced it.
Rgb escaped_radiance(const Scene& scene, const Vec3& dir, bool count_fully, float bsdf_pdf) {
  Rgb sum;
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
        count_fully ? 1.f : power_heuristic(bsdf_pdf, scene.light_sampler.pmf(li) * light_pdf);
    sum += le * w;
  }
  return sum;
}

}  // namespace

PathResult trace_path(const Scene& scene, const Ray& camera_ray, Sampler& sampler,
                      const PathTracerOptions& options) {
  PathResult result;
  Rgb throughput(1.f);
  Ray ray = camera_ray;
  bool count_emission_fully = true;  // camera ray or delta BSDF bounce: no MIS partner
  float prev_bsdf_pdf = 0.f;
  const bool have_lights = !scene.light_sampler.empty();

  for (int depth = 0;; ++depth) {
    const std::optional<SurfaceHit> hit = scene.accel->intersect(ray);
    ++result.rays;
    if (!hit) {
      result.radiance +=
          throughput * escaped_radiance(scene, ray.dir, count_emission_fully, prev_bsdf_pdf);
      break;
    }
    if (depth == 0) {
      result.alpha = 1.f;
      if (options.want_aovs) {
        result.depth = float(hit->t * scene.unit_scale);
        result.normal = dot(hit->n, ray.dir) < 0.f ? hit->n : -hit->n;
      }
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
          w = power_heuristic(prev_bsdf_pdf, light_pdf);
        }
        result.radiance += throughput * le * w;
      }
      if (depth == 0 && options.want_aovs) result.albedo = Rgb{};
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
      float pmf = 0.f, u_rest = 0.f;
      const size_t li = scene.light_sampler.sample(sampler.next1(), &pmf, &u_rest);
      const Vec2 u_light = sampler.next2();
      if (pmf > 0.f) {
        const auto ls = sample_light(scene.lights[li], hit->p, u_light);
        if (ls && ls->pdf > 0.f && !ls->radiance.is_black()) {
          const Vec3 wi = frame.to_local(ls->wi);
          const Rgb f = bsdf_eval(bsdf, wo, wi);
          if (!f.is_black()) {
            const Vec3 n_off = dot(ls->wi, hit->n) >= 0.f ? hit->n : -hit->n;
            const Vec3 origin = offset_ray_origin(hit->p, n_off);
            // Stop short of the light's surface so it does not occlude itself.
            const float tmax =
                std::isinf(ls->distance) ? ls->distance : ls->distance * (1.f - 1e-4f);
            ++result.rays;
            if (!scene.accel->occluded(origin, ls->wi, tmax)) {
              const float light_pdf = pmf * ls->pdf;
              const float w =
                  ls->is_delta ? 1.f : power_heuristic(light_pdf, bsdf_pdf(bsdf, wo, wi));
              result.radiance += throughput * f * ls->radiance * (std::abs(wi.z) * w / light_pdf);
            }
          }
        }
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
    throughput *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
    count_emission_fully = bs->is_specular;
    prev_bsdf_pdf = bs->pdf;

    const Vec3 wi_world = normalize(frame.to_world(bs->wi));
    const Vec3 n_off = dot(wi_world, hit->n) >= 0.f ? hit->n : -hit->n;
    ray = Ray{offset_ray_origin(hit->p, n_off), wi_world};

    if (depth + 1 >= options.rr_start_depth) {
      const float q = std::max(0.05f, 1.f - throughput.max_component());
      if (sampler.next1() < q) break;
      throughput *= 1.f / (1.f - q);
    }
    if (!throughput.is_finite()) break;
  }
  return result;
}

}  // namespace vesper
