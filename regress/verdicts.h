#pragma once
// Verdicts roll up: a layer's into its scene's, a scene's into the run's;
// the worst wins (error > regressed > pass).
#include <string>

#include "regress/regress_result.h"

namespace vesper::regress {

Verdict worse(Verdict a, Verdict b);

// The scene's verdict becomes the worst of its own and its layers'; every
// reason of a layer that did not pass is added to the scene's reasons as
// "<layer>: <reason>", so the scene's reasons read on their own.
void summarize_layers(SceneResult& scene);

// The run's verdict: the worst of its scenes'.
void summarize_run(RunResult& run);

// A scene that could not be compared (missing golden, failed render, ...).
SceneResult error_result(const std::string& scene, const std::string& reason);

}  // namespace vesper::regress
