// A fem_pad finger's soft pad as triangles to draw: its skin at the snapshot's node positions,
// rebuilt every frame from a pad snapshot. Render thread (or any, one at a time); reuses its
// buffers.
#pragma once

#include <array>
#include <vector>

#include "render/gl/vertex.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// Builds pad surfaces, reusing its scratch array from one pad to the next (no allocation once
/// it has grown to the largest pad).
class PadMeshBuilder {
 public:
  /// Appends the skin of `pad` (world frame) to `out` as unwelded triangles, three corners per
  /// skin triangle in its winding (outward), each corner with the area-weighted mean normal of
  /// the skin triangles at its node: the deformed pad shades smooth. Nothing for a pad without
  /// nodes or skin (the other contact models').
  void build(const sim::PadSnapshot& pad, std::vector<Vertex>& out);
  /// The same for any surface of `triangles` over `nodes` (a soft body's, deformed).
  void build(const std::vector<sim::Vec3>& nodes, const std::vector<std::array<int, 3>>& triangles, std::vector<Vertex>& out);

 private:
  std::vector<sim::Vec3> normals_;  // per node: the sum of its triangles' area vectors
};

/// The farthest a node of `pad` lies from `centre` (m); 0 without nodes. A pressed pad bulges
/// past its skin's sphere.
double padReach(const sim::PadSnapshot& pad, const sim::Vec3& centre);

}  // namespace gf::render
