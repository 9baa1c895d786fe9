#pragma once
// Google Benchmark's console table, plus a summary of the ray-throughput
// benchmark: Mrays/s per measurement and scene (median over repetitions),
// hit fractions, cores busy, and the tracer/raw ratios (bench/README.md).
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

namespace vesper::bench {

// One reported run (a repetition), as captured from the counters: runs that
// only estimate the iteration count are never reported, so they do not enter
// the summary.
struct Sample {
  double rate = 0;             // rays/s
  double hit_fraction = 0;     // raw and accel measurements
  double rays_per_sample = 0;  // tracer
  double cores = 0;            // process CPU time / wall time while measuring
};

struct SceneLine {
  std::string name, info;
};

class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  SummaryReporter();
  // Benchmark names are "<scene>/<measurement>".
  void ReportRuns(const std::vector<Run>& reports) override;
  void print_summary(const std::vector<SceneLine>& scenes, int threads, bool quick) const;

 private:
  // Median over repetitions of f(sample) (robust to a burst of load); 0 when absent.
  template <typename F>
  double median(const std::string& scene, const std::string& what, F f) const;
  double rate(const std::string& scene, const std::string& what) const;
  void print_rates(const std::vector<SceneLine>& scenes) const;
  void print_run_facts(const std::vector<SceneLine>& scenes) const;
  void print_ratios(const std::vector<SceneLine>& scenes) const;

  // results_[scene][measurement]: one entry per repetition.
  std::map<std::string, std::map<std::string, std::vector<Sample>>> results_;
};

}  // namespace vesper::bench
