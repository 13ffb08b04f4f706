#include "render/scene/patch_mesh.hpp"

#include <algorithm>

namespace gf::render {
namespace {

using sim::Vec3;

// Point at arc-length fraction s (0..1) along the polyline [first, last).
Vec3 alongPath(const Vec3* first, const Vec3* last, double s) {
  double total = 0.0;
  for (const Vec3* p = first; p + 1 < last; ++p) total += (p[1] - p[0]).norm();
  if (total <= 0.0 || last - first < 2) return *first;
  double remaining = s * total;
  for (const Vec3* p = first; p + 1 < last; ++p) {
    const double len = (p[1] - p[0]).norm();
    if (remaining <= len && len > 0.0) return p[0] + (remaining / len) * (p[1] - p[0]);
    remaining -= len;
  }
  return *(last - 1);
}

}  // namespace

// Projects a world point onto the body surface; returns the lifted point and the face normal.
PatchMeshBuilder::Projected PatchMeshBuilder::project(const Vec3& world, const sim::Mesh& mesh,
                                                      const sim::Pose& pose) const {
  const Vec3 local = pose.orientation.conjugate() * (world - pose.position);
  const sim::SurfacePoint sp = mesh.closestPoint(local, 0.0);
  if (sp.face < 0) return {world, Vec3::UnitY()};
  const Vec3 n = pose.orientation * mesh.faceNormal(sp.face);
  return {pose.toWorld(sp.point) + settings_.lift * n, n};
}

void PatchMeshBuilder::build(const sim::ContactSnapshot& contact, const sim::Mesh& mesh, const sim::Pose& pose,
                             std::vector<Vertex>& triangles, std::vector<Vertex>& rim, std::vector<Vertex>& outline) {
  const PatchMeshSettings& settings = settings_;
  const int paths = static_cast<int>(contact.path_offsets.size()) - 1;
  if (paths < 2) return;
  const int rings = std::max(1, settings.rings), sub = std::max(0, settings.rays_between) + 1;
  // grid[r][ring]: ray r (paths x sub rays around), sample `ring` from the centre outwards.
  const int rays = paths * sub;
  std::vector<Projected>& grid = grid_;
  std::vector<Vec3>& resampled = resampled_;
  grid.resize(static_cast<std::size_t>(rays) * (rings + 1));
  resampled.resize(static_cast<std::size_t>(paths) * (rings + 1));
  for (int k = 0; k < paths; ++k) {
    const Vec3* first = contact.path_points_world.data() + contact.path_offsets[k];
    const Vec3* last = contact.path_points_world.data() + contact.path_offsets[k + 1];
    for (int j = 0; j <= rings; ++j) resampled[k * (rings + 1) + j] = alongPath(first, last, double(j) / rings);
  }
  for (int r = 0; r < rays; ++r) {
    const int k = r / sub, next = (k + 1) % paths;
    const double w = double(r % sub) / sub;
    for (int j = 0; j <= rings; ++j) {
      const Vec3 p = (1 - w) * resampled[k * (rings + 1) + j] + w * resampled[next * (rings + 1) + j];
      grid[r * (rings + 1) + j] = project(p, mesh, pose);
    }
  }
  // Fill: a fan around the centre, quads between rings; the outer quarter of the rings is the
  // rim band.
  const auto at = [&](int r, int j) -> const Projected& { return grid[(r % rays) * (rings + 1) + j]; };
  for (int r = 0; r < rays; ++r) {
    for (int j = 0; j < rings; ++j) {
      std::vector<Vertex>& out = j >= rings - std::max(1, rings / 4) && rings > 1 ? rim : triangles;
      const Projected &a = at(r, j), &b = at(r, j + 1), &c = at(r + 1, j + 1), &d = at(r + 1, j);
      for (const Projected* p : {&a, &b, &c}) out.push_back(makeVertex(p->point, p->normal));
      if (j > 0) {
        for (const Projected* p : {&a, &c, &d}) out.push_back(makeVertex(p->point, p->normal));
      }
    }
  }
  // Outline: the walked paths and the rim.
  for (int k = 0; k < paths; ++k) {
    for (int j = 0; j < rings; ++j) {
      outline.push_back(makeVertex(at(k * sub, j).point, at(k * sub, j).normal));
      outline.push_back(makeVertex(at(k * sub, j + 1).point, at(k * sub, j + 1).normal));
    }
  }
  for (int r = 0; r < rays; ++r) {
    outline.push_back(makeVertex(at(r, rings).point, at(r, rings).normal));
    outline.push_back(makeVertex(at(r + 1, rings).point, at(r + 1, rings).normal));
  }
}

}  // namespace gf::render
