#include "sim/scene_desc.hpp"

#include "sim/mesh_import.hpp"

namespace gf::sim {

std::shared_ptr<const Mesh> bodyMesh(const BodyDesc& body) {
  if (body.mesh) return body.mesh;
  return std::make_shared<const Mesh>(loadMesh(body.mesh_path, body.mesh_scale));
}

}  // namespace gf::sim
