// Soft objects as tetrahedra, generated: a box, a ball and a cylinder, each centred at the origin
// and built in code, deterministic. Each is a structured grid of hexahedra, mapped onto the shape
// and split into six tetrahedra each by Kuhn's split, which conforms across cells. The ball and the
// cylinder map their grid with a blend from a cube (a square) at the centre to the sphere (the
// circle) at the surface, the surface's directions at equal angles (as a cubed sphere's), and split
// each cell along the diagonal that points away from the centre, so the mesh is symmetric and the
// cells near the grid's corners stay well shaped. Pure geometry: no Bullet here.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "sim/math.hpp"
#include "sim/mesh/tet_pad.hpp"

namespace gf::sim {

/// Limits the generators accept (they throw std::invalid_argument outside them, naming the field),
/// and the most a tetrahedral mesh may hold, generated or read (tet_files.hpp).
inline constexpr double kMinSoftLength = 1e-3,
                        kMaxSoftLength = 1.0;        ///< m: half extents, radius, half height
inline constexpr double kMinSoftElementSize = 1e-4;  ///< m; at most the shape's largest dimension
inline constexpr long kMaxTetrahedra = 200'000;
inline constexpr long kMaxTetNodes = 1'000'000;

/// A box of `half_extents` (m): cells of about `element_size` (m) along each axis (at least one),
/// each split along its diagonal that points away from the centre. `element_size` may be up to the
/// box's largest dimension (2 × its largest half extent). cells_across and layers are 0: the three
/// axes have counts of their own (6 tetrahedra a cell). Allocates.
TetMesh generateSoftBox(const Vec3& half_extents, double element_size);

/// A ball of `radius` (m): an even number of cells across each way (at least 2), each about
/// `element_size` (m, up to the diameter) at the surface. Its surface nodes lie on the sphere.
/// cells_across is the grid's cells across each way; layers is 0. Allocates.
TetMesh generateSoftSphere(double radius, double element_size);

/// A cylinder along y, `radius` and `half_height` in m: its disc an even number of cells across
/// each way (at least 2), extruded in layers along y (at least one), cells about `element_size`
/// (m, up to the cylinder's largest dimension). Its side's nodes lie on the cylinder.
/// cells_across is the disc's cells across each way; layers the cells along y. Allocates.
TetMesh generateSoftCylinder(double radius, double half_height, double element_size);

/// The faces of `tets` that belong to one tetrahedron only (the boundary), each wound outward: its
/// nodes counter-clockwise seen from outside, the tetrahedron's fourth node behind it at `nodes`.
/// Sorted by their nodes, so the same tetrahedra give the same surface. Allocates.
std::vector<std::array<int, 3>> boundaryTriangles(const std::vector<std::array<int, 4>>& tets,
                                                  const std::vector<Vec3>& nodes);

/// A grid of cells[0] × cells[1] × cells[2] hexahedra whose node (i, j, k) is at `node`(i, j, k),
/// nodes numbered with i fastest, then j, then k; each cell split into six tetrahedra (Kuhn) along
/// its diagonal from corner (i, j, k) to (i+1, j+1, k+1), or, when `outward` is set, along the
/// diagonal that points away from the grid's middle on each axis. Every tetrahedron is turned to
/// positive volume; the surface is boundaryTriangles'. The mesh's other fields are left empty.
/// The shapes' and the pad's generator. Allocates.
TetMesh kuhnGrid(const std::array<int, 3>& cells, const std::function<Vec3(int, int, int)>& node,
                 bool outward);

}  // namespace gf::sim
