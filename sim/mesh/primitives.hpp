// Tessellated walk meshes for primitive shapes. Physics collides with the exact primitive;
// the god-finger walk runs on these meshes, whose resolution is a parameter.
#pragma once

#include "sim/mesh/mesh.hpp"

namespace gf::sim {

/// Tessellation limits of each primitive (the resolutions the functions below accept).
inline constexpr int kMaxSphereSubdivisions = 7;
inline constexpr int kMinBoxSegments = 1, kMaxBoxSegments = 256;
inline constexpr int kMinCylinderSegments = 3, kMinCapsuleSegments = 4, kMaxRoundSegments = 4096;
inline constexpr int kMinPlaneSegments = 1, kMaxPlaneSegments = 1024;

/// Icosphere of `radius` (m) centred at the origin; `subdivisions` (0..kMaxSphereSubdivisions)
/// splits each of the 20 faces into 4^subdivisions triangles.
Mesh tessellateSphere(double radius, int subdivisions);

/// Box with the given half extents (m) centred at the origin; each face is a
/// `segments` x `segments` grid of quads (two triangles each).
Mesh tessellateBox(const Vec3& half_extents, int segments);

/// Cylinder along y, centred at the origin, `radius` and `half_height` in m; `segments` around,
/// with enough rings along y to keep side triangles close to square.
Mesh tessellateCylinder(double radius, double half_height, int segments);

/// Capsule along y: a cylinder of `half_height` (m, centre to each hemisphere centre) capped by
/// hemispheres of `radius` (m); `segments` around, segments/4 rings per hemisphere.
Mesh tessellateCapsule(double radius, double half_height, int segments);

/// Square in the plane y = 0, normal +y, of `half_size` (m), `segments` x `segments` quads.
Mesh tessellatePlane(double half_size, int segments);

}  // namespace gf::sim
