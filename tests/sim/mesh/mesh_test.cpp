#include "sim/mesh/mesh.hpp"

#include <gtest/gtest.h>

#include <random>

#include "sim/mesh/primitives.hpp"

namespace gf::sim {
namespace {

using Tris = std::vector<std::array<std::int32_t, 3>>;

// Unit cube [0,1]^3 as six separate quads: 24 vertices, outward winding.
void cubeAsSeparateQuads(std::vector<Vec3>& pos, Tris& tris, double noise) {
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-noise, noise);
  for (const auto& q : quads) {
    const auto base = static_cast<std::int32_t>(pos.size());
    for (int c : q) {
      pos.emplace_back((c & 1) + jitter(rng), ((c >> 1) & 1) + jitter(rng), ((c >> 2) & 1) + jitter(rng));
    }
    tris.push_back({base, base + 1, base + 2});
    tris.push_back({base, base + 2, base + 3});
  }
}

TEST(Mesh, WeldsSeparateQuadsIntoClosedCube) {
  std::vector<Vec3> pos;
  Tris tris;
  cubeAsSeparateQuads(pos, tris, 1e-8);  // well inside 1e-6 of the diagonal
  const Mesh m = buildMesh(pos, tris);
  EXPECT_EQ(m.vertexCount(), 8);
  EXPECT_EQ(m.report().welded_vertices, 16);
  EXPECT_EQ(m.faceCount(), 12);
  EXPECT_EQ(m.report().boundary_edges, 0);
  EXPECT_EQ(m.report().non_manifold_edges, 0);
  EXPECT_EQ(m.report().inconsistent_edges, 0);
  EXPECT_NEAR(m.signedVolume(), 1.0, 1e-6);
  for (int f = 0; f < m.faceCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const FaceLink& l = m.link(f, k);
      ASSERT_GE(l.face, 0);
      EXPECT_EQ(m.link(l.face, l.edge).face, f) << "adjacency must be mutual on a manifold";
      EXPECT_FALSE(l.flipped);
    }
  }
}

TEST(Mesh, DoesNotWeldBeyondTolerance) {
  std::vector<Vec3> pos;
  Tris tris;
  cubeAsSeparateQuads(pos, tris, 0.0);
  pos[0].x() += 1e-3;  // 1e-3 / sqrt(3) of the diagonal, far above 1e-6
  const Mesh m = buildMesh(pos, tris);
  EXPECT_EQ(m.vertexCount(), 9);
  EXPECT_EQ(m.report().boundary_edges, 4);
}

TEST(Mesh, DropsDegenerateAndDuplicateTriangles) {
  const std::vector<Vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0.5, 0, 0}};
  const Tris tris = {{0, 1, 2}, {0, 0, 1}, {0, 4, 1}, {1, 2, 0}, {0, 3, 1}};
  const Mesh m = buildMesh(pos, tris);
  EXPECT_EQ(m.faceCount(), 1);
  EXPECT_EQ(m.report().dropped_degenerate, 3);  // repeated index, two collinear
  EXPECT_EQ(m.report().dropped_duplicates, 1);  // {1,2,0} is {0,1,2} rotated
  EXPECT_EQ(m.report().boundary_edges, 3);
}

TEST(Mesh, KeepsSliverTriangles) {
  const std::vector<Vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0.5, 1e-9, 0}};
  const Mesh m = buildMesh(pos, {{0, 1, 2}});
  ASSERT_EQ(m.faceCount(), 1);
  EXPECT_NEAR(m.faceNormal(0).z(), 1.0, 1e-12);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.edgeInwardNormal(0, k).norm(), 1.0, 1e-12);
}

TEST(Mesh, NonManifoldEdgeLinksToMostCoplanarFace) {
  // Edge (0,1) along x is shared by a flat continuation (face 1) and a vertical fin (face 2).
  const std::vector<Vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  const Tris tris = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const Mesh m = buildMesh(pos, tris);
  EXPECT_EQ(m.report().non_manifold_edges, 1);
  EXPECT_EQ(m.link(0, 0).kind, EdgeKind::kNonManifold);
  EXPECT_EQ(m.link(0, 0).face, 1);
  EXPECT_EQ(m.link(1, 0).face, 0);
  EXPECT_EQ(m.link(2, 0).face, 0) << "tie between faces 0 and 1 goes to the lower index";
}

TEST(Mesh, MarksInconsistentWinding) {
  std::vector<Vec3> pos;
  Tris tris;
  cubeAsSeparateQuads(pos, tris, 0.0);
  std::swap(tris[0][1], tris[0][2]);  // flip one triangle
  const Mesh m = buildMesh(pos, tris);
  EXPECT_EQ(m.report().inconsistent_edges, 3);
  int flipped = 0;
  for (int k = 0; k < 3; ++k) flipped += m.link(0, k).flipped;
  EXPECT_EQ(flipped, 3);
}

TEST(Mesh, RejectsNonFiniteAndBadIndices) {
  EXPECT_THROW(buildMesh({{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}}, {{0, 1, 2}}), std::invalid_argument);
  EXPECT_THROW(buildMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}}), std::invalid_argument);
}

TEST(Mesh, EmptyInputGivesEmptyMesh) {
  const Mesh m = buildMesh({}, {});
  EXPECT_EQ(m.faceCount(), 0);
  EXPECT_EQ(m.closestPoint(Vec3::Zero(), 0.0).face, -1);
}

TEST(MeshQuery, ClassifiesFaceEdgeAndVertexHitsOnABox) {
  const Mesh box = tessellateBox(Vec3(0.05, 0.05, 0.05), 1);
  const double tol = 1e-6;
  const SurfacePoint face = box.closestPoint(Vec3(0.01, 0.2, 0.02), tol);
  EXPECT_EQ(face.feature, Feature::kFace);
  EXPECT_NEAR(face.point.y(), 0.05, 1e-15);
  EXPECT_NEAR(face.query_distance, 0.15, 1e-12);
  const SurfacePoint edge = box.closestPoint(Vec3(0.1, 0.1, 0.01), tol);
  EXPECT_EQ(edge.feature, Feature::kEdge);
  EXPECT_TRUE(edge.point.isApprox(Vec3(0.05, 0.05, 0.01), 1e-12));
  const SurfacePoint corner = box.closestPoint(Vec3(0.2, 0.3, 0.4), tol);
  EXPECT_EQ(corner.feature, Feature::kVertex);
  EXPECT_TRUE(corner.point.isApprox(Vec3(0.05, 0.05, 0.05), 1e-12));
  // Within the tolerance of an edge, a face hit becomes an edge hit, snapped onto the edge.
  const SurfacePoint near_edge = box.closestPoint(Vec3(0.05 - 5e-7, 0.06, 0.0), tol);
  EXPECT_EQ(near_edge.feature, Feature::kEdge);
  EXPECT_NEAR(near_edge.point.x(), 0.05, 1e-15);
}

// Naive reference: the projection on the plane if it falls inside, else the nearest segment.
double referenceDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a).normalized();
  const Vec3 q = p - (p - a).dot(n) * n;
  const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                      (a - c).cross(q - c).dot(n) >= 0;
  if (inside) return (p - q).norm();
  auto seg = [&](const Vec3& u, const Vec3& w) {
    const double t = std::clamp((p - u).dot(w - u) / (w - u).squaredNorm(), 0.0, 1.0);
    return (p - (u + t * (w - u))).norm();
  };
  return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

TEST(MeshQuery, BvhMatchesBruteForce) {
  const Mesh sphere = tessellateSphere(0.3, 3);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int i = 0; i < 300; ++i) {
    const Vec3 p(u(rng), u(rng), u(rng));
    double brute = 1e300;
    for (int f = 0; f < sphere.faceCount(); ++f) {
      brute = std::min(brute, referenceDistance(p, sphere.corner(f, 0), sphere.corner(f, 1),
                                                sphere.corner(f, 2)));
    }
    const SurfacePoint sp = sphere.closestPoint(p, 0.0);
    EXPECT_NEAR(sp.query_distance, brute, 1e-12);
    EXPECT_NEAR(referenceDistance(p, sphere.corner(sp.face, 0), sphere.corner(sp.face, 1),
                                  sphere.corner(sp.face, 2)),
                brute, 1e-12);
  }
}

}  // namespace
}  // namespace gf::sim
