#include "sim/scene/scene_desc.hpp"

#include "sim/mesh/mesh_import.hpp"
#include "sim/mesh/tet_files.hpp"
#include "sim/mesh/tet_shapes.hpp"

namespace gf::sim {

std::shared_ptr<const Mesh> bodyMesh(const BodyDesc& body) {
  if (body.mesh) return body.mesh;
  return std::make_shared<const Mesh>(loadMesh(body.mesh_path, body.mesh_scale));
}

std::shared_ptr<const TetMesh> softMesh(const BodyDesc& body) {
  if (body.soft.tets) return body.soft.tets;
  const double h = body.soft.element_size;
  switch (body.shape) {
    case ShapeKind::kSoftBox: return std::make_shared<const TetMesh>(generateSoftBox(body.half_extents, h));
    case ShapeKind::kSoftSphere: return std::make_shared<const TetMesh>(generateSoftSphere(body.radius, h));
    case ShapeKind::kSoftCylinder: return std::make_shared<const TetMesh>(generateSoftCylinder(body.radius, body.half_height, h));
    default: break;
  }
  const std::string& path = body.soft.tet_path;
  if (path.size() > 4 && path.compare(path.size() - 4, 4, ".vtk") == 0) {
    return std::make_shared<const TetMesh>(readVtkTets(path, body.mesh_scale));
  }
  const std::string stem = path.size() > 5 && path.compare(path.size() - 5, 5, ".node") == 0 ? path.substr(0, path.size() - 5) : path;
  return std::make_shared<const TetMesh>(readTetGen(stem + ".node", stem + ".ele", body.mesh_scale));
}

double loadFactor(const LoadDesc& load, double t) {
  if (t < load.start || t >= load.stop) return 0.0;
  if (t < load.start + load.ramp) return (t - load.start) / load.ramp;  // never reached with ramp 0
  return 1.0;
}

}  // namespace gf::sim
