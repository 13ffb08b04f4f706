// The region two fingers' patches on one body both cover (docs/overlap.md), drawn over the
// patches in its own tint. Render thread; reuses the caller's buffers.
#pragma once

#include <vector>

#include "render/gl/vertex.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// Linear RGB of the overlap region: magenta, apart from every finger's colour.
inline constexpr float kOverlapColour[3] = {0.95f, 0.1f, 0.75f};

/// Whether contacts `a` and `b` are on one body and their Eq. 1 discs overlap in their common
/// tangent plane (as sim::discOverlap measures it). Any thread.
bool patchesOverlap(const sim::ContactSnapshot& a, const sim::ContactSnapshot& b);

/// Appends the region contacts `a` and `b` (on the same body) both cover: the intersection of
/// their Eq. 1 discs in the common tangent plane (the lens the overlap area measures), as a fan
/// of triangles projected onto `mesh` (the body's render surface in its description frame, at
/// `pose`) and lifted `lift` (m) along its normal, and its edge as line segments. Nothing when
/// the discs do not overlap. Allocates only while the buffers grow.
void buildOverlapRegion(const sim::ContactSnapshot& a, const sim::ContactSnapshot& b, const sim::Mesh& mesh,
                        const sim::Pose& pose, double lift, std::vector<Vertex>& triangles,
                        std::vector<Vertex>& outline);

}  // namespace gf::render
