#include "render/scene/geometry.hpp"

#include <cmath>
#include <numbers>

#include "sim/mesh/primitives.hpp"

namespace gf::render {
namespace {

// Render tessellations: fine enough that silhouettes look round at 1080p.
constexpr int kSphereSubdivisions = 4;
constexpr int kRoundSegments = 64;
constexpr double kCreaseDeg = 35.0;

}  // namespace

std::vector<Vertex> shadedTriangles(const sim::Mesh& mesh, double crease_deg) {
  const double cos_crease = std::cos(crease_deg * std::numbers::pi / 180.0);
  std::vector<Vertex> out;
  out.reserve(3 * static_cast<std::size_t>(mesh.faceCount()));
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const sim::Vec3& nf = mesh.faceNormal(f);
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles()[f][k];
      sim::Vec3 sum = sim::Vec3::Zero();
      for (const std::int32_t* g = mesh.vertexFacesBegin(v); g != mesh.vertexFacesEnd(v); ++g) {
        const sim::Vec3& ng = mesh.faceNormal(*g);
        if (ng.dot(nf) >= cos_crease) sum += ng;
      }
      out.push_back(makeVertex(mesh.vertices()[v], sum.squaredNorm() > 0 ? sum.normalized() : nf));
    }
  }
  return out;
}

std::shared_ptr<const sim::Mesh> bodyRenderMesh(const sim::BodyDesc& body) {
  switch (body.shape) {
    case sim::ShapeKind::kSphere:
      return std::make_shared<sim::Mesh>(sim::tessellateSphere(body.radius, kSphereSubdivisions));
    case sim::ShapeKind::kBox:
      return std::make_shared<sim::Mesh>(sim::tessellateBox(body.half_extents, 1));
    case sim::ShapeKind::kCylinder:
      return std::make_shared<sim::Mesh>(
          sim::tessellateCylinder(body.radius, body.half_height, kRoundSegments));
    case sim::ShapeKind::kCapsule:
      return std::make_shared<sim::Mesh>(
          sim::tessellateCapsule(body.radius, body.half_height, kRoundSegments));
    case sim::ShapeKind::kPlane:
      return nullptr;
    case sim::ShapeKind::kConvexHull:
    case sim::ShapeKind::kConvexDecomposition:
    case sim::ShapeKind::kConcaveMesh:
      return sim::bodyMesh(body);  // the mesh the scene loaded, shared with the World
    case sim::ShapeKind::kSoftBox:
    case sim::ShapeKind::kSoftSphere:
    case sim::ShapeKind::kSoftCylinder:
    case sim::ShapeKind::kSoftMesh:
      return nullptr;  // drawn deformed from each snapshot (draw_list.cpp)
  }
  return nullptr;
}

std::vector<Vertex> unitSphere(int subdivisions) {
  return shadedTriangles(sim::tessellateSphere(1.0, subdivisions), kCreaseDeg);
}

std::vector<Vertex> unitCylinder(int segments) {
  const sim::Mesh m = sim::tessellateCylinder(1.0, 0.5, segments);
  std::vector<Vertex> out = shadedTriangles(m, kCreaseDeg);
  for (Vertex& v : out) v.position[1] += 0.5f;
  return out;
}

std::vector<Vertex> unitCone(int segments) {
  std::vector<Vertex> out;
  const sim::Vec3 tip(0, 1, 0);
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2 * std::numbers::pi * i / segments, a1 = 2 * std::numbers::pi * (i + 1) / segments;
    const sim::Vec3 p0(std::cos(a0), 0, -std::sin(a0)), p1(std::cos(a1), 0, -std::sin(a1));
    // Side normal of a 45-degree cone, per corner for smooth shading.
    const auto side = [](const sim::Vec3& p) { return sim::Vec3(p.x(), 1.0, p.z()).normalized(); };
    out.push_back(makeVertex(p0, side(p0)));
    out.push_back(makeVertex(p1, side(p1)));
    out.push_back(makeVertex(tip, side(0.5 * (p0 + p1)).normalized()));
    out.push_back(makeVertex(sim::Vec3::Zero(), -sim::Vec3::UnitY()));
    out.push_back(makeVertex(p1, -sim::Vec3::UnitY()));
    out.push_back(makeVertex(p0, -sim::Vec3::UnitY()));
  }
  return out;
}

}  // namespace gf::render
