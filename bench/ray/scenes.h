#pragma once
// The ray-throughput benchmark's scenes and their ray sets (bench/README.md):
// each scene as vesper::build_scene makes it, the raw Embree scene built by
// the renderer's own EmbreeScene from the geometry in the scene's Accel, and
// the ray sets generated once before timing.
#include <memory>
#include <string>
#include <vector>

#include "renderer/core/embree_scene.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_description.h"

namespace vesper::bench {

struct RayRec {
  Vec3 o, d;
};

struct BenchScene {
  std::string name;
  SceneDescription desc;
  Scene scene;
  // Shares the Accel's mesh buffers: declared after `scene`, destroyed first.
  std::unique_ptr<EmbreeScene> raw;
  std::vector<RayRec> coherent, incoherent, incoherent_volume;
  std::string info;  // primitives, film, max_depth: for the summary
};

// Builds the scene, its raw Embree scene and `rays_per_set` rays of each set.
std::unique_ptr<BenchScene> make_bench_scene(std::string name, SceneDescription desc,
                                             size_t rays_per_set);

// The Cornell room (walls, ceiling light) with a displaced UV sphere of
// 2 * segments * (rings - 1) triangles inside.
SceneDescription dense_mesh_scene(int segments, int rings);

}  // namespace vesper::bench
