#include "regress/verdicts.h"

namespace vesper::regress {
namespace {

int severity(Verdict v) {
  switch (v) {
    case Verdict::Pass:
      return 0;
    case Verdict::Regressed:
      return 1;
    case Verdict::Error:
      return 2;
  }
  return 2;
}

}  // namespace

Verdict worse(Verdict a, Verdict b) { return severity(a) >= severity(b) ? a : b; }

void summarize_layers(SceneResult& scene) {
  for (const LayerResult& layer : scene.layers) {
    scene.verdict = worse(scene.verdict, layer.verdict);
    if (layer.verdict == Verdict::Pass) continue;
    for (const std::string& reason : layer.reasons)
      scene.reasons.push_back(layer.layer + ": " + reason);
  }
}

void summarize_run(RunResult& run) {
  run.verdict = Verdict::Pass;
  for (const SceneResult& scene : run.scenes) run.verdict = worse(run.verdict, scene.verdict);
}

SceneResult error_result(const std::string& scene, const std::string& reason) {
  SceneResult r;
  r.name = scene;
  r.verdict = Verdict::Error;
  r.reasons.push_back(reason);
  return r;
}

}  // namespace vesper::regress
