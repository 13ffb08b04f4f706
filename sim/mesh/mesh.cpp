#include "sim/mesh/mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "sim/assert.hpp"

namespace gf::sim {
namespace {

// Smallest weld tolerance (metres), so a mesh whose points all coincide still welds.
constexpr double kMinWeldTolerance = 1e-12;
// Largest coordinate magnitude (metres): squared distances and cross products of the mesh's
// points stay finite in double.
constexpr double kMaxCoordinate = 1e150;
// Largest weld grid cell index along an axis: exact in double and in int64. Points further out
// share cells (welding still compares their distances).
constexpr double kMaxCell = 0x1p52;

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
};

struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    const auto h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull ^
                   static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full ^
                   static_cast<std::uint64_t>(k.z) * 0x165667B19E3779F9ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

void checkInput(const std::vector<Vec3>& positions,
                const std::vector<std::array<std::int32_t, 3>>& triangles) {
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!positions[i].allFinite()) {
      throw std::invalid_argument("mesh vertex " + std::to_string(i) + " is not finite");
    }
    if (positions[i].cwiseAbs().maxCoeff() > kMaxCoordinate) {
      throw std::invalid_argument("mesh vertex " + std::to_string(i) + " lies beyond 1e150 m of the origin");
    }
  }
  const auto n = static_cast<std::int64_t>(positions.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (std::int32_t idx : triangles[t]) {
      if (idx < 0 || idx >= n) {
        throw std::invalid_argument("mesh triangle " + std::to_string(t) +
                                    " has vertex index " + std::to_string(idx) +
                                    " outside 0.." + std::to_string(n - 1));
      }
    }
  }
}

// Welds positions closer than `tol` (first occurrence wins). Returns old-to-new index map.
// Grid cells of size `tol` are counted from `lo`, the positions' lower bounds, so their indices
// stay small wherever the mesh lies (from the origin, a micrometre mesh 10 km away needs cell
// indices past the range of int64).
std::vector<std::int32_t> weld(const std::vector<Vec3>& positions, const Vec3& lo, double tol,
                               std::vector<Vec3>& welded) {
  std::unordered_map<CellKey, std::vector<std::int32_t>, CellHash> grid;
  std::vector<std::int32_t> remap(positions.size());
  const double tol2 = tol * tol;
  auto cellOf = [tol, &lo](const Vec3& p) {
    const auto index = [&](int k) {
      return static_cast<std::int64_t>(std::min(std::floor((p[k] - lo[k]) / tol), kMaxCell));
    };
    return CellKey{index(0), index(1), index(2)};
  };
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    const CellKey c = cellOf(p);
    std::int32_t found = -1;
    for (int dx = -1; dx <= 1 && found < 0; ++dx) {
      for (int dy = -1; dy <= 1 && found < 0; ++dy) {
        for (int dz = -1; dz <= 1 && found < 0; ++dz) {
          auto it = grid.find(CellKey{c.x + dx, c.y + dy, c.z + dz});
          if (it == grid.end()) continue;
          for (std::int32_t w : it->second) {
            if ((welded[w] - p).squaredNorm() <= tol2) {
              found = w;
              break;
            }
          }
        }
      }
    }
    if (found < 0) {
      found = static_cast<std::int32_t>(welded.size());
      welded.push_back(p);
      grid[c].push_back(found);
    }
    remap[i] = found;
  }
  return remap;
}

std::array<std::int32_t, 3> sortedCorners(const std::array<std::int32_t, 3>& t) {
  std::array<std::int32_t, 3> s = t;
  std::sort(s.begin(), s.end());
  return s;
}

struct EdgeUse {
  std::int32_t face;
  std::int8_t edge;
};

std::uint64_t edgeKey(std::int32_t a, std::int32_t b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

}  // namespace

double Mesh::signedVolume() const {
  double six_v = 0.0;
  for (const auto& t : triangles_) {
    six_v += vertices_[t[0]].dot(vertices_[t[1]].cross(vertices_[t[2]]));
  }
  return six_v / 6.0;
}

// The steps of buildMesh, with access to the Mesh they fill.
struct MeshBuilder {
  struct Welded {
    std::vector<std::int32_t> remap;  // input vertex to welded vertex
    double diagonal = 0.0;            // of the input's bounding box (m)
  };

  // Step 1: weld vertices with a tolerance relative to the bounding box.
  static Welded weldVertices(Mesh& m, const std::vector<Vec3>& positions, const MeshBuildSettings& settings) {
    Vec3 lo = Vec3::Constant(0.0), hi = Vec3::Constant(0.0);
    if (!positions.empty()) {
      lo = hi = positions[0];
      for (const Vec3& p : positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
    Welded out;
    out.diagonal = (hi - lo).norm();
    const double tol = std::max(settings.weld_tolerance_rel * out.diagonal, kMinWeldTolerance);
    out.remap = weld(positions, lo, tol, m.vertices_);
    m.report_.welded_vertices = m.report_.input_vertices - static_cast<int>(m.vertices_.size());
    return out;
  }

  // Step 2: drop degenerate and duplicate triangles; the kept ones get their unit normals.
  static void keepTriangles(Mesh& m, const std::vector<std::array<std::int32_t, 3>>& triangles,
                            const std::vector<std::int32_t>& remap, double min_area2) {
    MeshBuildReport& rep = m.report_;
    std::unordered_map<std::uint64_t, std::vector<std::array<std::int32_t, 3>>> seen;
    for (const auto& t : triangles) {
      const std::array<std::int32_t, 3> w = {remap[t[0]], remap[t[1]], remap[t[2]]};
      const Vec3 n = (m.vertices_[w[1]] - m.vertices_[w[0]]).cross(m.vertices_[w[2]] - m.vertices_[w[0]]);
      if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || !(n.norm() > min_area2)) {
        ++rep.dropped_degenerate;
        continue;
      }
      const auto s = sortedCorners(w);
      auto& bucket = seen[edgeKey(s[0], s[1]) ^ (static_cast<std::uint64_t>(s[2]) * 0x9E3779B97F4A7C15ull)];
      if (std::find(bucket.begin(), bucket.end(), s) != bucket.end()) {
        ++rep.dropped_duplicates;
        continue;
      }
      bucket.push_back(s);
      m.triangles_.push_back(w);
      m.normals_.push_back(n.normalized());
    }
  }

  // Step 3: per-face inward edge normals (in the face plane, pointing into the face), edge
  // directions and mean edge length.
  static void buildFaceFrames(Mesh& m) {
    const int nf = m.faceCount();
    m.inward_.resize(nf);
    m.edge_dir_.resize(nf);
    m.mean_edge_.resize(nf);
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        const Vec3 e = m.corner(f, (k + 1) % 3) - m.corner(f, k);
        m.inward_[f][k] = m.normals_[f].cross(e).normalized();
        m.edge_dir_[f][k] = e.normalized();
      }
      m.mean_edge_[f] = ((m.corner(f, 1) - m.corner(f, 0)).norm() + (m.corner(f, 2) - m.corner(f, 1)).norm() +
                         (m.corner(f, 0) - m.corner(f, 2)).norm()) / 3.0;
    }
  }

  // Step 4: edge adjacency, from the faces using each edge.
  static void linkEdges(Mesh& m) {
    const int nf = m.faceCount();
    std::unordered_map<std::uint64_t, std::vector<EdgeUse>> edges;
    edges.reserve(static_cast<std::size_t>(nf) * 2);
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) {
        const auto& t = m.triangles_[f];
        edges[edgeKey(t[k], t[(k + 1) % 3])].push_back({f, static_cast<std::int8_t>(k)});
      }
    }
    m.links_.assign(nf, {});
    for (const auto& [key, uses] : edges) {
      (void)key;
      linkEdge(m, uses);
    }
  }

  // The links of one edge's faces: its kind, and for each face the neighbour across it.
  static void linkEdge(Mesh& m, const std::vector<EdgeUse>& uses) {
    MeshBuildReport& rep = m.report_;
    const EdgeKind kind = uses.size() == 1   ? EdgeKind::kBoundary
                          : uses.size() == 2 ? EdgeKind::kInterior
                                             : EdgeKind::kNonManifold;
    if (kind == EdgeKind::kBoundary) ++rep.boundary_edges;
    if (kind == EdgeKind::kNonManifold) ++rep.non_manifold_edges;
    for (const EdgeUse& u : uses) {
      FaceLink& link = m.links_[u.face][u.edge];
      link.kind = kind;
      if (kind == EdgeKind::kBoundary) continue;
      // The neighbour: the other face on this edge with the most parallel normal.
      double best = -1.0;
      for (const EdgeUse& o : uses) {
        if (o.face == u.face) continue;
        const double c = std::abs(m.normals_[u.face].dot(m.normals_[o.face]));
        if (c > best || (c == best && o.face < link.face)) {
          best = c;
          link.face = o.face;
          link.edge = o.edge;
        }
      }
      // Consistent winding runs a shared edge in opposite directions.
      const auto& tu = m.triangles_[u.face];
      const auto& tn = m.triangles_[link.face];
      link.flipped = tu[u.edge] == tn[link.edge];
    }
    if (kind == EdgeKind::kInterior && m.links_[uses[0].face][uses[0].edge].flipped) {
      ++rep.inconsistent_edges;
    }
  }

  // Step 5: vertex-to-face lists (compressed rows, faces in increasing order).
  static void buildVertexFaces(Mesh& m) {
    m.vf_offsets_.assign(m.vertices_.size() + 1, 0);
    for (const auto& t : m.triangles_) {
      for (std::int32_t v : t) ++m.vf_offsets_[v + 1];
    }
    for (std::size_t v = 0; v < m.vertices_.size(); ++v) m.vf_offsets_[v + 1] += m.vf_offsets_[v];
    m.vf_faces_.resize(m.vf_offsets_.back());
    std::vector<std::int32_t> fill(m.vf_offsets_.begin(), m.vf_offsets_.end() - 1);
    for (int f = 0; f < m.faceCount(); ++f) {
      for (std::int32_t v : m.triangles_[f]) m.vf_faces_[fill[v]++] = f;
    }
  }

  // Step 6: bounds of the welded vertices.
  static void computeBounds(Mesh& m) {
    if (m.vertices_.empty()) return;
    m.bounds_min_ = m.bounds_max_ = m.vertices_[0];
    for (const Vec3& p : m.vertices_) {
      m.bounds_min_ = m.bounds_min_.cwiseMin(p);
      m.bounds_max_ = m.bounds_max_.cwiseMax(p);
    }
  }

  // The steps in order: each reads what the ones before it filled.
  static Mesh build(const std::vector<Vec3>& positions, const std::vector<std::array<std::int32_t, 3>>& triangles,
                    const MeshBuildSettings& settings) {
    Mesh m;
    m.report_.input_vertices = static_cast<int>(positions.size());
    m.report_.input_triangles = static_cast<int>(triangles.size());
    const Welded welded = weldVertices(m, positions, settings);
    const double diag = welded.diagonal;
    keepTriangles(m, triangles, welded.remap, settings.min_area_rel * diag * diag);
    buildFaceFrames(m);
    linkEdges(m);
    buildVertexFaces(m);
    computeBounds(m);
    m.buildBvh();
    return m;
  }
};

void Mesh::moveVertices(const std::vector<Vec3>& positions) {
  GF_ASSERT(positions.size() == vertices_.size());  // one position per vertex
  std::copy(positions.begin(), positions.end(), vertices_.begin());
  for (int f = 0; f < faceCount(); ++f) {
    const Vec3 n = (corner(f, 1) - corner(f, 0)).cross(corner(f, 2) - corner(f, 0));
    const double area2 = n.norm();
    if (!(area2 > 0.0) || !std::isfinite(area2)) continue;  // squeezed flat: its last frames kept
    normals_[f] = n / area2;
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = corner(f, (k + 1) % 3) - corner(f, k);
      const double length = e.norm();
      sum += length;
      if (!(length > 0.0)) continue;
      edge_dir_[f][k] = e / length;
      inward_[f][k] = normals_[f].cross(edge_dir_[f][k]).normalized();
    }
    mean_edge_[f] = sum / 3.0;
  }
  MeshBuilder::computeBounds(*this);
  refitBvh();
}

Mesh buildMesh(const std::vector<Vec3>& positions,
               const std::vector<std::array<std::int32_t, 3>>& triangles,
               const MeshBuildSettings& settings) {
  checkInput(positions, triangles);
  return MeshBuilder::build(positions, triangles, settings);
}

MassProperties massProperties(const Mesh& m) {
  // Covariance of the canonical tetrahedron (0, e1, e2, e3), unit density.
  Eigen::Matrix3d c0;
  c0 << 2, 1, 1, 1, 2, 1, 1, 1, 2;
  c0 /= 120.0;
  MassProperties mp;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int f = 0; f < m.faceCount(); ++f) {
    Eigen::Matrix3d a;
    a << m.corner(f, 0), m.corner(f, 1), m.corner(f, 2);
    const double det = a.determinant();
    mp.volume += det / 6.0;
    mp.centroid += det / 24.0 * (m.corner(f, 0) + m.corner(f, 1) + m.corner(f, 2));
    cov += det * a * c0 * a.transpose();
  }
  if (!(mp.volume > 0.0)) return mp;
  mp.centroid /= mp.volume;
  cov -= mp.volume * mp.centroid * mp.centroid.transpose();
  mp.inertia = cov.trace() * Eigen::Matrix3d::Identity() - cov;
  return mp;
}

SolidCheck solidCheck(const Mesh& m) {
  // Openings that close up in space leave the faces' vector area (sum of area times normal) at
  // zero, as for a closed surface; relative to the total area, up to rounding.
  constexpr double kOpenVectorArea = 1e-9;
  const MeshBuildReport& r = m.report();
  Vec3 vector_area = Vec3::Zero();
  double area = 0.0;
  for (int f = 0; f < m.faceCount(); ++f) {
    const Vec3 n = (m.corner(f, 1) - m.corner(f, 0)).cross(m.corner(f, 2) - m.corner(f, 0));
    vector_area += 0.5 * n;
    area += 0.5 * n.norm();
  }
  const bool closed = r.boundary_edges == 0 && r.non_manifold_edges == 0;
  SolidCheck c;
  if (!closed && vector_area.norm() > kOpenVectorArea * area) {
    c.why_not = "not closed (" + std::to_string(r.boundary_edges) + " boundary and " +
                std::to_string(r.non_manifold_edges) + " non-manifold edges): it encloses no volume";
    return c;
  }
  if (!(massProperties(m).volume > 0.0)) {
    c.why_not = "it encloses no volume (inside-out: its faces are wound inward)";
    return c;
  }
  c.solid = true;
  return c;
}

}  // namespace gf::sim
