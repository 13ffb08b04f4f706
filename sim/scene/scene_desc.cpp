#include "sim/scene/scene_desc.hpp"

#include "sim/mesh/mesh_import.hpp"
#include "sim/mesh/tet_files.hpp"
#include "sim/mesh/tet_shapes.hpp"
#include "sim/scene/settings.hpp"

namespace gf::sim {

std::shared_ptr<const Mesh> bodyMesh(const BodyDesc& body) {
  if (body.mesh) return body.mesh;
  return std::make_shared<const Mesh>(loadMesh(body.mesh_path, body.mesh_scale));
}

namespace {

// `mesh` without the nodes no tetrahedron uses (a file's mid-edge nodes of second-order elements,
// stray points): a node of no element has no mass and no stiffness, and would leave the solve
// singular.
TetMesh withoutUnusedNodes(TetMesh mesh) {
  std::vector<int> index(mesh.nodes.size(), -1);
  for (const std::array<int, 4>& t : mesh.tets) {
    for (int n : t) index[static_cast<std::size_t>(n)] = 0;
  }
  std::vector<Vec3> kept;
  for (std::size_t n = 0; n < index.size(); ++n) {
    if (index[n] < 0) continue;
    index[n] = static_cast<int>(kept.size());
    kept.push_back(mesh.nodes[n]);
  }
  if (kept.size() == mesh.nodes.size()) return mesh;
  mesh.nodes = std::move(kept);
  for (std::array<int, 4>& t : mesh.tets) {
    for (int& n : t) n = index[static_cast<std::size_t>(n)];
  }
  for (std::array<int, 3>& t : mesh.surface) {
    for (int& n : t) n = index[static_cast<std::size_t>(n)];
  }
  return mesh;
}

}  // namespace

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
    return std::make_shared<const TetMesh>(withoutUnusedNodes(readVtkTets(path, body.mesh_scale)));
  }
  const std::string stem = path.size() > 5 && path.compare(path.size() - 5, 5, ".node") == 0 ? path.substr(0, path.size() - 5) : path;
  return std::make_shared<const TetMesh>(withoutUnusedNodes(readTetGen(stem + ".node", stem + ".ele", body.mesh_scale)));
}

std::optional<FieldError> validateSoftBody(const BodyDesc& body) {
  if (!isSoftShape(body.shape)) return std::nullopt;
  if (body.mass == 0.0) {
    return FieldError{"static", "a soft body is dynamic: hold it with pinned boxes instead"};
  }
  if (body.shape == ShapeKind::kSoftMesh && body.soft.tet_path.empty() && !body.soft.tets) {
    return FieldError{"tets", "is empty"};
  }
  if (body.soft.tets && body.mass > 0.0) {  // its material's density: its mass over its volume
    double volume = 0.0;
    for (const std::array<int, 4>& t : body.soft.tets->tets) {
      const std::vector<Vec3>& x = body.soft.tets->nodes;
      volume += tetVolume(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])], x[static_cast<std::size_t>(t[2])], x[static_cast<std::size_t>(t[3])]);
    }
    const double density = body.mass / volume;
    if (!(density >= kMinSoftDensity && density <= kMaxSoftDensity)) {
      return FieldError{"mass", "gives a soft body of " + numberText(density) + " kg/m^3 over its " + numberText(volume) +
                                    " m^3 of tetrahedra; its material takes " + numberText(kMinSoftDensity) + ".." + numberText(kMaxSoftDensity)};
    }
  }
  return std::nullopt;
}

double loadFactor(const LoadDesc& load, double t) {
  if (t < load.start || t >= load.stop) return 0.0;
  if (t < load.start + load.ramp) return (t - load.start) / load.ramp;  // never reached with ramp 0
  return 1.0;
}

}  // namespace gf::sim
