// Triangle mesh with welded vertices, per-edge adjacency and the per-face data the god-finger
// walk needs. Built once at load time; read-only afterwards and safe to share between threads.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/math.hpp"

namespace gf::sim {

/// How an edge of a triangle is shared.
enum class EdgeKind : std::uint8_t {
  kInterior,     ///< exactly two triangles share the edge
  kBoundary,     ///< one triangle only: the walk stops there
  kNonManifold,  ///< three or more triangles: the neighbour is the most coplanar one (see below)
};

/// Which feature of a triangle a surface point lies on (kVertex last: JSON names them in order).
enum class Feature : std::uint8_t { kFace, kEdge, kVertex };

/// A point on the mesh surface with the feature it lies on.
struct SurfacePoint {
  int face = -1;               ///< triangle holding the point, -1 when the mesh is empty
  Feature feature = Feature::kFace;
  int feature_index = -1;      ///< edge k (corner k to k+1) or corner k of `face`; -1 on a face
  Vec3 point = Vec3::Zero();   ///< closest point, snapped onto the edge or vertex (metres)
  double query_distance = 0.0;  ///< from the query point to `point` (metres)
};

/// Link from one triangle edge to the triangle across it.
struct FaceLink {
  std::int32_t face = -1;  ///< neighbouring triangle, -1 on a boundary edge
  std::int8_t edge = -1;   ///< index (0..2) of the shared edge inside the neighbour
  bool flipped = false;    ///< the neighbour's winding disagrees with this triangle's
  EdgeKind kind = EdgeKind::kBoundary;
};

/// Settings for building a mesh from raw positions and triangles.
struct MeshBuildSettings {
  /// Vertices closer than this fraction of the bounding-box diagonal are welded into one.
  double weld_tolerance_rel = 1e-6;
  /// Triangles whose doubled area is below this fraction of the squared diagonal are dropped.
  double min_area_rel = 1e-14;
};

/// What building a mesh changed, for reports and tests.
struct MeshBuildReport {
  int input_vertices = 0;
  int input_triangles = 0;
  int welded_vertices = 0;        ///< vertices merged into an earlier one
  int dropped_degenerate = 0;     ///< triangles with repeated vertices or (near-)zero area
  int dropped_duplicates = 0;     ///< triangles using the same three vertices as an earlier one
  int boundary_edges = 0;
  int non_manifold_edges = 0;
  int inconsistent_edges = 0;     ///< interior edges whose two triangles disagree on winding
};

/// Welded triangle mesh. Edge k of triangle f runs from vertex k to vertex (k+1)%3.
///
/// Non-manifold edges (three or more triangles): each triangle links to the other triangle on
/// that edge whose normal is most nearly parallel to its own (largest |n_f . n_g|, lowest index
/// on ties), so a walk continues over the flattest continuation. The link need not be mutual.
class Mesh {
 public:
  Mesh() = default;

  /// Number of triangles.
  int faceCount() const { return static_cast<int>(triangles_.size()); }
  /// Number of (welded) vertices.
  int vertexCount() const { return static_cast<int>(vertices_.size()); }

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<std::array<std::int32_t, 3>>& triangles() const { return triangles_; }

  /// Vertex k (0..2) of triangle f.
  const Vec3& corner(int f, int k) const { return vertices_[triangles_[f][k]]; }
  /// Unit normal of triangle f, from its winding (counter-clockwise seen from outside).
  const Vec3& faceNormal(int f) const { return normals_[f]; }
  /// Unit vector in the plane of f, perpendicular to edge k, pointing into f.
  const Vec3& edgeInwardNormal(int f, int k) const { return inward_[f][k]; }
  /// Unit direction of edge k of f, from vertex k to vertex (k+1)%3.
  const Vec3& edgeDirection(int f, int k) const { return edge_dir_[f][k]; }
  /// Mean length of f's three edges (m).
  double meanEdge(int f) const { return mean_edge_[f]; }
  /// The triangle across edge k of f.
  const FaceLink& link(int f, int k) const { return links_[f][k]; }

  /// Triangles that use vertex v, in increasing index order.
  const std::int32_t* vertexFacesBegin(int v) const { return vf_faces_.data() + vf_offsets_[v]; }
  const std::int32_t* vertexFacesEnd(int v) const { return vf_faces_.data() + vf_offsets_[v + 1]; }

  /// Axis-aligned bounds of the vertices (metres).
  const Vec3& boundsMin() const { return bounds_min_; }
  const Vec3& boundsMax() const { return bounds_max_; }
  /// Length of the bounding-box diagonal (metres).
  double diagonal() const { return (bounds_max_ - bounds_min_).norm(); }

  /// What building changed.
  const MeshBuildReport& report() const { return report_; }

  /// Closest point on the surface to p, classified as face, edge or vertex: a point within
  /// `feature_tol` (metres) of a corner is a vertex hit, else within it of an edge an edge hit.
  /// Uses the bounding-volume hierarchy; any thread; does not allocate.
  SurfacePoint closestPoint(const Vec3& p, double feature_tol) const;

  /// Moves every vertex to `positions` (one per vertex, the same order; the topology kept): the
  /// faces' normals and frames, the bounds and the hierarchy's boxes follow (refitted, not
  /// rebuilt). A face squeezed to no area keeps its last normal and frames. For a deformed
  /// surface (a soft body's, each step): its owner's thread only. Does not allocate.
  void moveVertices(const std::vector<Vec3>& positions);

  /// Signed volume enclosed (positive for closed, outward-wound meshes; m^3).
  double signedVolume() const;

  friend struct MeshBuilder;  // buildMesh's steps (mesh.cpp)

 private:
  std::vector<Vec3> vertices_;
  std::vector<std::array<std::int32_t, 3>> triangles_;
  std::vector<Vec3> normals_;
  std::vector<std::array<Vec3, 3>> inward_;
  std::vector<std::array<Vec3, 3>> edge_dir_;
  std::vector<double> mean_edge_;
  std::vector<std::array<FaceLink, 3>> links_;
  std::vector<std::int32_t> vf_offsets_;
  std::vector<std::int32_t> vf_faces_;
  struct BvhNode {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    std::int32_t first = 0;  ///< leaf: first index into bvh_faces_; inner: left child (right +1)
    std::int32_t count = 0;  ///< leaf: number of faces; inner: 0
  };
  void buildBvh();
  void refitBvh();
  std::vector<BvhNode> bvh_nodes_;
  std::vector<std::int32_t> bvh_faces_;
  Vec3 bounds_min_ = Vec3::Zero();
  Vec3 bounds_max_ = Vec3::Zero();
  MeshBuildReport report_;
};

/// The normal a contact at `hit` takes when none is given: the hit face's, or at an edge or vertex
/// the normal of the face around it that `push` (the pressing direction) presses into most.
Vec3 pressedNormal(const Mesh& mesh, const SurfacePoint& hit, const Vec3& push);

/// Volume, centroid and inertia of the solid a closed, outward-wound mesh encloses, per unit
/// density (signed tetrahedra from the origin; an open or inside-out mesh gives a volume <= 0
/// and the rest unset).
struct MassProperties {
  double volume = 0.0;                                ///< m^3
  Vec3 centroid = Vec3::Zero();                       ///< m
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the centroid, unit density (m^5)
};
MassProperties massProperties(const Mesh& mesh);

/// Whether a mesh encloses a volume, so that a dynamic body may take its mass distribution from
/// it: it is closed (no boundary or non-manifold edge), or its openings close up in space (cracks
/// along T-junctions: the faces' vector area sums to zero, so the volume does not depend on
/// where it is measured from), and it is wound outward (volume > 0). `why_not` says what fails
/// ("" when solid), in the words `godfinger mesh-info` and the scene reader use.
struct SolidCheck {
  bool solid = false;
  std::string why_not;
};
SolidCheck solidCheck(const Mesh& mesh);

/// Builds a mesh: welds vertices by position, drops degenerate and duplicate triangles, links
/// neighbours through every edge and marks boundary and non-manifold edges. Deterministic.
/// Throws std::invalid_argument for non-finite positions, positions beyond 1e150 m of the origin
/// or out-of-range indices. Allocates.
Mesh buildMesh(const std::vector<Vec3>& positions,
               const std::vector<std::array<std::int32_t, 3>>& triangles,
               const MeshBuildSettings& settings = {});

}  // namespace gf::sim
