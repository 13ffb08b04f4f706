#include "sim/scene/scene_desc.hpp"

#include "sim/mesh/mesh_import.hpp"

namespace gf::sim {

std::shared_ptr<const Mesh> bodyMesh(const BodyDesc& body) {
  if (body.mesh) return body.mesh;
  return std::make_shared<const Mesh>(loadMesh(body.mesh_path, body.mesh_scale));
}

double loadFactor(const LoadDesc& load, double t) {
  if (t < load.start || t >= load.stop) return 0.0;
  if (t < load.start + load.ramp) return (t - load.start) / load.ramp;  // never reached with ramp 0
  return 1.0;
}

}  // namespace gf::sim
