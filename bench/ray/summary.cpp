#include "bench/ray/summary.h"

#include <embree3/rtcore.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace vesper::bench {
namespace {

// `v` formatted with `fmt`, or "-" when there is no figure.
std::string cell(double v, const char* fmt) {
  char buf[64];
  if (v > 0)
    std::snprintf(buf, sizeof buf, fmt, v);
  else
    std::snprintf(buf, sizeof buf, "-");
  return std::string(buf);
}

}  // namespace

// Colour only on a terminal, like Google Benchmark's own default reporter.
SummaryReporter::SummaryReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_Color : OO_None) {}

void SummaryReporter::ReportRuns(const std::vector<Run>& reports) {
  for (const Run& r : reports) {
    if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
    const std::string& name = r.run_name.function_name;  // "<scene>/<measurement>"
    const size_t slash = name.find('/');
    if (slash == std::string::npos) continue;
    auto counter = [&](const char* k) {
      auto it = r.counters.find(k);
      return it == r.counters.end() ? 0.0 : double(it->second.value);
    };
    results_[name.substr(0, slash)][name.substr(slash + 1)].push_back(
        {counter("rays/s"), counter("hit%") / 100.0, counter("rays/sample"), counter("cores")});
  }
  ConsoleReporter::ReportRuns(reports);
}

template <typename F>
double SummaryReporter::median(const std::string& scene, const std::string& what, F f) const {
  const auto s = results_.find(scene);
  if (s == results_.end()) return 0.0;
  const auto it = s->second.find(what);
  if (it == s->second.end() || it->second.empty()) return 0.0;
  std::vector<double> v;
  for (const Sample& m : it->second) v.push_back(f(m));
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double SummaryReporter::rate(const std::string& scene, const std::string& what) const {
  return median(scene, what, [](const Sample& m) { return m.rate; });
}

void SummaryReporter::print_summary(const std::vector<SceneLine>& scenes, int threads,
                                    bool quick) const {
  size_t reps = 0;
  for (const auto& [scene, m] : results_)
    for (const auto& [what, v] : m) reps = std::max(reps, v.size());
  std::printf(
      "\n=== Ray throughput summary (%d threads, Embree %s, median of %zu repetition(s)%s) ===\n",
      threads, RTC_VERSION_STRING, reps,
      quick ? ", QUICK MODE: smoke test only, figures not representative" : "");
  for (const auto& s : scenes) std::printf("  %-11s %s\n", s.name.c_str(), s.info.c_str());
  print_rates(scenes);
  print_run_facts(scenes);
  print_ratios(scenes);
  std::fflush(stdout);
}

void SummaryReporter::print_rates(const std::vector<SceneLine>& scenes) const {
  std::printf("\n%-44s", "Mrays/s");
  for (const auto& s : scenes) std::printf("%16s", s.name.c_str());
  std::printf("\n");
  const char* rows[][2] = {
      {"raw/intersect1/coherent", "raw rtcIntersect1, coherent (camera)"},
      {"raw/intersect1/incoherent", "raw rtcIntersect1, incoherent (surface)"},
      {"raw/intersect1/incoh_volume", "raw rtcIntersect1, incoherent (volume)"},
      {"raw/occluded1/incoherent", "raw rtcOccluded1, incoherent (surface)"},
      {"raw/intersect16/coherent", "raw rtcIntersect16, coherent (upper bound)"},
      {"accel/intersect/coherent", "vesper::Accel::intersect, coherent"},
      {"accel/intersect/incoherent", "vesper::Accel::intersect, incoherent"},
      {"tracer/render", "path tracer (vesper::render)"},
  };
  for (const auto& row : rows) {
    std::printf("%-44s", row[1]);
    for (const auto& s : scenes)
      std::printf("%16s", cell(rate(s.name, row[0]) / 1e6, "%.2f").c_str());
    std::printf("\n");
  }
}

// Hit fractions of the ray sets, cores the process got, tracer rays per sample.
void SummaryReporter::print_run_facts(const std::vector<SceneLine>& scenes) const {
  std::printf("%-44s", "hit fraction: coherent / incoherent");
  for (const auto& s : scenes) {
    auto hf = [&](const char* k) {
      return median(s.name, k, [](const Sample& m) { return m.hit_fraction; });
    };
    std::printf("%16s", (cell(hf("raw/intersect1/coherent"), "%.2f") + " / " +
                         cell(hf("raw/intersect1/incoherent"), "%.2f"))
                            .c_str());
  }
  std::printf("\n%-44s", "cores busy: raw coh / raw incoh / tracer");
  for (const auto& s : scenes) {
    auto cores = [&](const char* k) {
      return median(s.name, k, [](const Sample& m) { return m.cores; });
    };
    std::printf("%16s", (cell(cores("raw/intersect1/coherent"), "%.1f") + "/" +
                         cell(cores("raw/intersect1/incoherent"), "%.1f") + "/" +
                         cell(cores("tracer/render"), "%.1f"))
                            .c_str());
  }
  std::printf("\n%-44s", "tracer rays per camera sample");
  for (const auto& s : scenes) {
    const double rps =
        median(s.name, "tracer/render", [](const Sample& m) { return m.rays_per_sample; });
    std::printf("%16s", cell(rps, "%.2f").c_str());
  }
}

void SummaryReporter::print_ratios(const std::vector<SceneLine>& scenes) const {
  std::printf("\n\nratio (share of the physical limit the tracer keeps)\n");
  const char* ratios[][3] = {
      {"tracer/render", "raw/intersect1/incoherent", "tracer / raw incoherent (surface)"},
      {"tracer/render", "raw/intersect1/incoh_volume", "tracer / raw incoherent (volume)"},
      {"tracer/render", "raw/intersect1/coherent", "tracer / raw coherent"},
      {"tracer/render", "raw/intersect16/coherent", "tracer / raw coherent packets (16)"},
      {"accel/intersect/incoherent", "raw/intersect1/incoherent",
       "Accel wrapper / raw, incoherent"},
      {"accel/intersect/coherent", "raw/intersect1/coherent", "Accel wrapper / raw, coherent"},
  };
  for (const auto& row : ratios) {
    std::printf("%-44s", row[2]);
    for (const auto& s : scenes) {
      const double num = rate(s.name, row[0]), den = rate(s.name, row[1]);
      std::printf("%16s", cell(num > 0 && den > 0 ? num / den : 0, "%.3f").c_str());
    }
    std::printf("\n");
  }
}

}  // namespace vesper::bench
