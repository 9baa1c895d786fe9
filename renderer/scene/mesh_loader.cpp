#include "renderer/scene/mesh_loader.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <limits>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "renderer/scene/scene_loader.h"

namespace vesper {
namespace {

// assimp 5.2's PLY reader loops forever on a header without "end_header", so
// the header is checked here first. Returns an empty string when it is fine.
std::string ply_header_problem(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || (line.rfind("ply", 0) != 0 && line.rfind("PLY", 0) != 0)) {
    return "expected a PLY file starting with 'ply'";
  }
  size_t bytes = line.size();
  while (std::getline(in, line) && bytes < (1u << 20)) {
    bytes += line.size() + 1;
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (line == "end_header") return {};
  }
  return "invalid PLY header: no 'end_header' line";
}

}  // namespace

MeshShapeDesc load_mesh_file(const std::filesystem::path& path, const std::string& scene_file,
                             const std::string& json_path) {
  // Built by appending: `"'" + std::string` trips GCC 12's false -Wrestrict (PR 105329).
  std::string where(1, '\'');
  where.append(path.string()).push_back('\'');
  auto fail = [&](const std::string& message) -> void {
    throw SceneError(scene_file, json_path, message);
  };

  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".ply" && ext != ".obj") {
    fail("expected a .ply or .obj mesh file, got " + where);
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("mesh file not found: " + where);

  if (ext == ".ply") {
    if (const std::string problem = ply_header_problem(path); !problem.empty()) {
      fail("cannot read mesh " + where + ": " + problem);
    }
  }

  Assimp::Importer importer;
  // Drop points and lines entirely instead of keeping them as separate meshes.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // No aiProcess_FindDegenerates: degenerate triangles must stay triangles so
  // indices keep their meaning; the renderer handles zero-area triangles.
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                           aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!scene) {
    const std::string error = importer.GetErrorString();
    // How assimp words "nothing usable in the file" (validation, or only points/lines).
    if (error.find("contains no faces") != std::string::npos ||
        error.find("mNumMeshes is 0") != std::string::npos ||
        error.find("No meshes remaining") != std::string::npos) {
      fail("mesh file " + where + " contains no triangles");
    }
    fail("cannot read mesh " + where + ": " + error);
  }

  MeshShapeDesc mesh;
  mesh.source = path.string();
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* m = scene->mMeshes[mi];
    if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const size_t base = mesh.positions.size();
    if (base + m->mNumVertices > std::numeric_limits<uint32_t>::max()) {
      fail("mesh " + where + " has more than 2^32 - 1 vertices");
    }
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D& p = m->mVertices[v];
      const Vec3d q{p.x, p.y, p.z};
      if (!is_finite(q)) {
        fail("mesh " + where + " has a non-finite vertex position (vertex " + std::to_string(v) +
             " of mesh " + std::to_string(mi) + ")");
      }
      mesh.positions.push_back(q);
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;
      mesh.triangles.push_back({uint32_t(base + face.mIndices[0]),
                                uint32_t(base + face.mIndices[1]),
                                uint32_t(base + face.mIndices[2])});
    }
  }
  if (mesh.triangles.empty()) fail("mesh file " + where + " contains no triangles");
  return mesh;
}

}  // namespace vesper
