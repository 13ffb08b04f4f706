#include "sim/mesh_import.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>

namespace gf::sim {

RawMesh readMeshFile(const std::string& path, double scale) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    throw MeshLoadError(path + ": scale must be a positive finite number");
  }
  Assimp::Importer importer;
  // Only triangles are kept; welding is ours (assimp's ignores tolerance and splits by normals).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (scene == nullptr) {
    throw MeshLoadError(path + ": cannot read mesh: " + importer.GetErrorString());
  }
  RawMesh raw;
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* mesh = scene->mMeshes[mi];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const auto base = static_cast<std::int32_t>(raw.positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const Vec3 q = scale * Vec3(p.x, p.y, p.z);
      if (!q.allFinite()) {
        throw MeshLoadError(path + ": vertex " + std::to_string(v) + " of mesh " +
                            std::to_string(mi) + " is not finite");
      }
      raw.positions.push_back(q);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      raw.triangles.push_back({base + static_cast<std::int32_t>(face.mIndices[0]),
                               base + static_cast<std::int32_t>(face.mIndices[1]),
                               base + static_cast<std::int32_t>(face.mIndices[2])});
    }
  }
  if (raw.triangles.empty()) throw MeshLoadError(path + ": the file holds no triangle");
  return raw;
}

Mesh loadMesh(const std::string& path, double scale, const MeshBuildSettings& settings) {
  const RawMesh raw = readMeshFile(path, scale);
  Mesh mesh = buildMesh(raw.positions, raw.triangles, settings);
  if (mesh.faceCount() == 0) {
    throw MeshLoadError(path + ": every triangle is degenerate (zero area)");
  }
  return mesh;
}

std::shared_ptr<const Mesh> MeshCache::load(const std::string& path, double scale) {
  std::shared_ptr<const Mesh>& slot = meshes_[{path, scale}];
  if (!slot) {
    slot = std::make_shared<const Mesh>(loadMesh(path, scale));
    ++files_read_;
  }
  return slot;
}

}  // namespace gf::sim
