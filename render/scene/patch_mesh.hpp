// The highlighted contact patch: a translucent surface that follows the walked paths over the
// body, built per frame from a contact snapshot. Render thread; reuses its buffers.
#pragma once

#include <vector>

#include "render/gl/vertex.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// How finely the patch surface is built.
struct PatchMeshSettings {
  int rings = 8;              ///< samples along each walked path, contact point excluded
  int rays_between = 3;       ///< interpolated rays between two neighbouring paths
  double lift = 0.0002;       ///< m the surface is raised along the body normal (no z-fighting)
};

/// Builds patch surfaces, reusing its scratch arrays from one patch to the next (no allocation
/// once they have grown to the largest patch). Render thread.
class PatchMeshBuilder {
 public:
  explicit PatchMeshBuilder(const PatchMeshSettings& settings = {}) : settings_(settings) {}

  /// Appends the patch of `contact` (world frame) as triangles lying on `mesh`, the body's
  /// render surface in its description frame, at the body pose `pose`. The region between
  /// neighbouring walked paths is filled with rays interpolated between them, each sample
  /// projected onto the surface, so the patch bends with the body (over edges and round
  /// shapes) instead of floating. `rim` receives the outer quarter of that surface (a band along
  /// the patch's edge, drawn strong so the edge reads at any size), `triangles` the rest; `outline` line segments (GL_LINES) of the walked paths and
  /// the rim through the SGOs. Contacts with fewer than two paths add nothing.
  void build(const sim::ContactSnapshot& contact, const sim::Mesh& mesh, const sim::Pose& pose,
             std::vector<Vertex>& triangles, std::vector<Vertex>& rim, std::vector<Vertex>& outline);

 private:
  /// A sample projected onto the body surface: lifted point and face normal (world).
  struct Projected {
    sim::Vec3 point, normal;
  };
  Projected project(const sim::Vec3& world, const sim::Mesh& mesh, const sim::Pose& pose) const;

  PatchMeshSettings settings_;
  std::vector<Projected> grid_;
  std::vector<sim::Vec3> resampled_;
};

}  // namespace gf::render
