#include "sim/world/body_factory.hpp"

#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <HACD/hacdHACD.h>

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cstdio>
#include <span>
#include <stdexcept>

#include "sim/assert.hpp"
#include "sim/mesh/decomposition_cache.hpp"
#include "sim/mesh/mesh_import.hpp"
#include "sim/mesh/primitives.hpp"
#include "sim/scene/settings.hpp"

namespace gf::sim {
namespace {

// Collision margin of boxes, cylinders, hulls and meshes (m): small, so edges stay sharp.
constexpr double kMargin = 0.0005;
// Half size of the walk mesh of a ground plane (m).
constexpr double kPlaneHalfSize = 50.0;
// HACD decomposition: the mesh is normalised to this size, and parts may be this concave in
// those units (2 % of the size); at most this many vertices per part.
constexpr double kHacdScale = 1000.0;
constexpr double kHacdConcavity = 20.0;
constexpr int kHacdVerticesPerPart = 64;

[[noreturn]] void fail(const BodyDesc& d, const std::string& field, const std::string& why) {
  throw DescriptionError("body '" + d.name + "'", {field, why});
}

// Moves a loaded mesh into its principal frame and fills mass properties of `out`.
std::shared_ptr<const Mesh> toBodyFrame(const BodyDesc& d, const Mesh& mesh, BodyShapes& out) {
  const MassProperties mp = massProperties(mesh);
  if (d.mass > 0.0) {
    const SolidCheck solid = solidCheck(mesh);
    if (!solid.solid || !(mp.volume > 1e-15)) {
      fail(d, "mesh", "'" + d.mesh_path + "': " + (solid.solid ? "its volume is too small" : solid.why_not) +
                          "; a dynamic body takes its mass distribution from that volume (make it static, or close the mesh)");
    }
  }
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Vec3 principal = Vec3::Zero();
  if (mp.volume > 1e-15) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(mp.inertia);
    axes = eig.eigenvectors();
    if (axes.determinant() < 0) axes.col(2) *= -1.0;
    principal = eig.eigenvalues() * (d.mass / mp.volume);
  }
  std::vector<Vec3> pos;
  pos.reserve(mesh.vertexCount());
  for (const Vec3& p : mesh.vertices()) pos.push_back(axes.transpose() * (p - mp.centroid));
  const btMatrix3x3 basis(axes(0, 0), axes(0, 1), axes(0, 2), axes(1, 0), axes(1, 1), axes(1, 2),
                          axes(2, 0), axes(2, 1), axes(2, 2));
  out.desc_from_body = btTransform(basis, toBt(mp.centroid));
  out.local_inertia = toBt(principal);
  return std::make_shared<const Mesh>(buildMesh(pos, mesh.triangles()));
}

std::unique_ptr<btConvexHullShape> hullOf(std::span<const Vec3> points) {
  auto hull = std::make_unique<btConvexHullShape>();
  for (const Vec3& p : points) hull->addPoint(toBt(p), false);
  hull->recalcLocalAabb();
  hull->setMargin(kMargin);
  return hull;
}

// A decomposition taking longer than a second reports its progress on stderr about once a
// second (a 350k-face mesh takes tens of seconds). HACD's callback is a plain function: the
// decomposition running on this thread is found through a thread_local.
struct DecompositionProgress {
  std::string mesh;
  std::size_t triangles = 0;
  std::chrono::steady_clock::time_point start, last;
  bool reported = false;
};
thread_local DecompositionProgress* t_progress = nullptr;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

bool reportDecomposition(const char*, double percent, double, std::size_t) {
  DecompositionProgress* p = t_progress;
  if (!p || secondsSince(p->last) < 1.0) return true;
  p->last = std::chrono::steady_clock::now();
  p->reported = true;
  std::fprintf(stderr, "godfinger: convex decomposition of %s (%zu triangles): %.0f %%, %.0f s\n", p->mesh.c_str(),
               p->triangles, percent, secondsSince(p->start));
  return true;
}

// HACD's parts of `m`: each part's hull points, in the body frame.
HullParts runHacd(const BodyDesc& d, const Mesh& m) {
  std::vector<HACD::Vec3<HACD::Real>> points;
  std::vector<HACD::Vec3<long>> triangles;
  for (const Vec3& p : m.vertices()) points.emplace_back(p.x(), p.y(), p.z());
  for (const auto& t : m.triangles()) triangles.emplace_back(t[0], t[1], t[2]);
  HACD::HACD hacd;
  hacd.SetPoints(points.data());
  hacd.SetNPoints(points.size());
  hacd.SetTriangles(triangles.data());
  hacd.SetNTriangles(triangles.size());
  hacd.SetScaleFactor(kHacdScale);
  hacd.SetConcavity(kHacdConcavity);
  hacd.SetNClusters(1);
  hacd.SetNVerticesPerCH(kHacdVerticesPerPart);
  hacd.SetAddExtraDistPoints(false);
  hacd.SetAddNeighboursDistPoints(false);
  hacd.SetAddFacesPoints(false);
  DecompositionProgress progress{d.mesh_path, triangles.size(), std::chrono::steady_clock::now(), {}, false};
  progress.last = progress.start;
  t_progress = &progress;
  hacd.SetCallBack(&reportDecomposition);
  const bool computed = hacd.Compute();
  t_progress = nullptr;
  if (!computed || hacd.GetNClusters() == 0) fail(d, "mesh", "convex decomposition of '" + d.mesh_path + "' failed");
  if (progress.reported) {
    std::fprintf(stderr, "godfinger: convex decomposition of %s: %zu parts in %.1f s\n", d.mesh_path.c_str(),
                 hacd.GetNClusters(), secondsSince(progress.start));
  }
  HullParts parts(hacd.GetNClusters());
  for (std::size_t c = 0; c < parts.size(); ++c) {
    std::vector<HACD::Vec3<HACD::Real>> part(hacd.GetNPointsCH(c));
    std::vector<HACD::Vec3<long>> part_triangles(hacd.GetNTrianglesCH(c));
    hacd.GetCH(c, part.data(), part_triangles.data());
    for (const auto& p : part) parts[c].emplace_back(p.X(), p.Y(), p.Z());
  }
  return parts;
}

// Approximate convex decomposition (HACD) into a compound of hulls, in the body frame. The
// parts come from the on-disk cache (decomposition_cache.hpp) when this mesh was decomposed
// with these settings before; otherwise HACD computes them and they are stored.
std::unique_ptr<btCollisionShape> decompose(const BodyDesc& d, const Mesh& m, BodyShapes& out) {
  const std::string dir = decompositionCacheDir();
  char settings[96];
  std::snprintf(settings, sizeof settings, "HACD scale %.17g concavity %.17g vertices %d", kHacdScale, kHacdConcavity,
                kHacdVerticesPerPart);
  const std::uint64_t key = decompositionKey(m, settings);
  std::optional<HullParts> parts = loadDecomposition(dir, key);
  if (!parts) {
    parts = runHacd(d, m);
    storeDecomposition(dir, key, *parts);
  }
  auto compound = std::make_unique<btCompoundShape>();
  for (const std::vector<Vec3>& part : *parts) {
    out.parts.push_back(hullOf(part));
    compound->addChildShape(btTransform::getIdentity(), out.parts.back().get());
  }
  return compound;
}

void makeMeshShapes(const BodyDesc& d, BodyShapes& out) {
  out.walk_mesh = toBodyFrame(d, *bodyMesh(d), out);
  const Mesh& m = *out.walk_mesh;
  if (d.shape == ShapeKind::kConvexHull) {
    out.shape = hullOf(m.vertices());
    return;
  }
  if (d.shape == ShapeKind::kConvexDecomposition) {
    out.shape = decompose(d, m, out);
    return;
  }
  // Concave: Bullet reads our welded arrays in place (doubles, 32-bit indices).
  btIndexedMesh part;
  part.m_numTriangles = m.faceCount();
  part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(m.triangles().data());
  part.m_triangleIndexStride = sizeof(std::array<std::int32_t, 3>);
  part.m_numVertices = m.vertexCount();
  part.m_vertexBase = reinterpret_cast<const unsigned char*>(m.vertices().data());
  part.m_vertexStride = sizeof(Vec3);
  part.m_indexType = PHY_INTEGER;
  part.m_vertexType = PHY_DOUBLE;
  auto arrays = std::make_unique<btTriangleIndexVertexArray>();
  arrays->addIndexedMesh(part, PHY_INTEGER);
  if (d.mass > 0.0) {
    auto gimpact = std::make_unique<btGImpactMeshShape>(arrays.get());
    gimpact->setMargin(kMargin);
    gimpact->updateBound();
    out.shape = std::move(gimpact);
  } else {
    out.shape = std::make_unique<btBvhTriangleMeshShape>(arrays.get(), true);
  }
  out.mesh_interface = std::move(arrays);
}

int resolution(const BodyDesc& d) {
  return d.walk_resolution > 0 ? d.walk_resolution : shapeInfo(d.shape).default_resolution;
}

}  // namespace

BodyShapes makeBodyShapes(const BodyDesc& d) {
  GF_ASSERT(!validateBody(d) && "build bodies from a checked description (World checks it with requireValid)");
  BodyShapes out;
  try {
    switch (d.shape) {
      case ShapeKind::kSphere:
        out.walk_mesh = std::make_shared<const Mesh>(tessellateSphere(d.radius, resolution(d)));
        out.shape = std::make_unique<btSphereShape>(d.radius);
        break;
      case ShapeKind::kBox:
        out.walk_mesh = std::make_shared<const Mesh>(tessellateBox(d.half_extents, resolution(d)));
        out.shape = std::make_unique<btBoxShape>(toBt(d.half_extents));
        out.shape->setMargin(kMargin);
        break;
      case ShapeKind::kCylinder:
        out.walk_mesh = std::make_shared<const Mesh>(
            tessellateCylinder(d.radius, d.half_height, resolution(d)));
        out.shape = std::make_unique<btCylinderShape>(btVector3(d.radius, d.half_height, d.radius));
        out.shape->setMargin(kMargin);
        break;
      case ShapeKind::kCapsule:
        out.walk_mesh = std::make_shared<const Mesh>(
            tessellateCapsule(d.radius, d.half_height, resolution(d)));
        out.shape = std::make_unique<btCapsuleShape>(d.radius, 2.0 * d.half_height);
        break;
      case ShapeKind::kPlane:
        out.walk_mesh = std::make_shared<const Mesh>(tessellatePlane(kPlaneHalfSize, resolution(d)));
        out.shape = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0.0);
        break;
      case ShapeKind::kConvexHull:
      case ShapeKind::kConvexDecomposition:
      case ShapeKind::kConcaveMesh:
        makeMeshShapes(d, out);
        break;
      case ShapeKind::kSoftBox:
      case ShapeKind::kSoftSphere:
      case ShapeKind::kSoftCylinder:
      case ShapeKind::kSoftMesh:  // a soft body's placeholder (world_soft.cpp): no walk mesh of its own
        out.shape = std::make_unique<btSphereShape>(1e-3);
        return out;
    }
  } catch (const DescriptionError&) {
    throw;
  } catch (const MeshLoadError& e) {
    fail(d, "mesh", e.what());
  } catch (const std::invalid_argument& e) {  // geometry the primitives or the mesh builder refuse
    fail(d, isMeshShape(d.shape) ? "mesh" : std::string(shapeInfo(d.shape).dimensions[0]), e.what());
  }
  if (d.mass > 0.0 && !isMeshShape(d.shape)) out.shape->calculateLocalInertia(d.mass, out.local_inertia);
  // Boxes and cylinders round inside their extents, hulls and GImpact meshes outside their
  // vertices; a sphere's or capsule's margin is its radius (no rounding of the walk mesh), and
  // a static triangle mesh has none.
  const bool rounded = d.shape == ShapeKind::kBox || d.shape == ShapeKind::kCylinder ||
                       d.shape == ShapeKind::kConvexHull || d.shape == ShapeKind::kConvexDecomposition ||
                       (d.shape == ShapeKind::kConcaveMesh && d.mass > 0.0);
  out.rounding = rounded ? kMargin : 0.0;
  return out;
}

}  // namespace gf::sim
