// A finger pad as tetrahedra: the cap of soft tissue on the contact side of a fingertip, between
// the rigid distal bone (a sphere) and the skin. The cap spans `cap_angle` around the pad's axis
// (-y, the way a finger presses); its nodes on the bone are the ones a deformable body anchors
// to it. Built in code, deterministic: a structured grid over the cap at equal angles (one face
// of an equiangular cubed sphere, so no pole), layers through the thickness, each curved
// hexahedron split into six tetrahedra along its main diagonal (Kuhn), which conforms across
// cells. The limits keep cells within about 2:1, so no tetrahedron is a sliver. Pure geometry:
// no Bullet here.
#pragma once

#include <array>
#include <vector>

#include "sim/math.hpp"

namespace gf::sim {

/// The pad's shape and resolution. Lengths in m, angles in rad.
struct PadShape {
  double bone_radius = 0.006;  ///< the distal bone, a sphere centred at the origin
  double thickness = 0.003;    ///< soft tissue from the bone to the skin, at most bone_radius
  double cap_angle = 0.7;      ///< half-angle of the cap from -y, measured to its edges' midpoints
  double element_size = 0.0015;  ///< the cells' size, thickness / 16 .. thickness
};

/// Limits generatePad() accepts (it throws std::invalid_argument outside them, naming the field),
/// beside those on each field above.
inline constexpr double kMinPadLength = 1e-4, kMaxPadLength = 0.1;  ///< m: bone radius, thickness
inline constexpr double kMinCapAngle = 0.1, kMaxCapAngle = 0.8;     ///< rad
inline constexpr int kMaxPadElementsAcross = 64;  ///< cells across the cap and through the thickness, each

struct TetMesh {
  std::vector<Vec3> nodes;                ///< m
  std::vector<std::array<int, 4>> tets;   ///< node indices, each of positive volume
  std::vector<int> bone_nodes;            ///< nodes on the bone (anchored to it)
  std::vector<std::array<int, 3>> surface;  ///< boundary triangles, wound outward
  int cells_across = 0;   ///< grid cells across the cap, each way
  int layers = 0;         ///< cell layers through the thickness
};

/// The pad of `shape`: cells across the cap and layers through the thickness chosen so each cell
/// is about `element_size` each way (at least one layer). Throws std::invalid_argument naming
/// the field when `shape` is outside the limits above. Allocates.
TetMesh generatePad(const PadShape& shape);

/// Signed volume of the tetrahedron (a, b, c, d), m³: positive when (b−a, c−a, d−a) is right-handed.
double tetVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// How good a mesh's tetrahedra are, worst over all of them.
struct TetQuality {
  double volume = 0.0;            ///< m³, all tetrahedra
  double min_volume = 0.0;        ///< m³ (≤ 0: an inverted or flat one)
  double min_dihedral_deg = 0.0;  ///< the smallest dihedral angle (a sliver has one near 0)
  double max_dihedral_deg = 0.0;  ///< the largest (a sliver has one near 180)
  double min_radius_ratio = 0.0;  ///< 3 × inradius / circumradius: 1 regular, 0 degenerate
};

/// The quality of `mesh`'s tetrahedra at its nodes' current positions.
TetQuality tetQuality(const TetMesh& mesh);

}  // namespace gf::sim
