// Two fingers' patches on one body: how much they overlap, the force that pushes them apart and
// one merged patch for their shared region (docs/overlap.md). Pure functions: no Bullet, no
// World; any thread; none allocates but mergePatches, which reuses its output's storage.
#pragma once

#include <vector>

#include "sim/math.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::sim {

/// Area (m^2) two discs of radii `r1`, `r2` (m) in one plane cover together when their centres
/// are `distance` (m) apart: the lens of the two circles in closed form, 0 when they do not
/// meet, the smaller disc's area when it lies inside the other. Non-positive radii: 0.
double discOverlapArea(double r1, double r2, double distance);

/// One contact's patch as the overlap sees it: the Eq. 1 disc of radius `radius` (m) around the
/// contact point in the plane normal to `outward_normal` (world frame).
struct PatchDisc {
  Vec3 centre = Vec3::Zero();
  Vec3 outward_normal = Vec3::UnitY();  ///< unit
  double radius = 0.0;                  ///< m; 0: no patch
};

/// How two patch discs on one body meet, in their common tangent plane (normal to the mean of
/// their normals). Discs whose normals are 90 degrees or more apart (opposite faces of a pinched
/// body) do not meet.
struct DiscOverlap {
  double area = 0.0;          ///< m^2, discOverlapArea of the projected discs
  double depth = 0.0;         ///< m: r1 + r2 - distance, 0 when they do not meet
  double distance = 0.0;      ///< m: between the projected centres
  Vec3 apart = Vec3::Zero();  ///< unit, in the tangent plane, from disc b towards disc a (zero when they coincide)
};

/// The overlap of discs `a` and `b`. Any thread; no allocation.
DiscOverlap discOverlap(const PatchDisc& a, const PatchDisc& b);

/// push_apart: the force (N) on finger a's proxy, along `o.apart`, `stiffness` (N/m) times the
/// discs' overlap depth, at most `max_force` (N); finger b's is its opposite. Zero while the
/// discs only touch, growing from zero with the overlap.
Vec3 pushApartForce(const DiscOverlap& o, double stiffness, double max_force);

/// merge: two coinciding points (closer than this fraction of the smaller radius) are one point.
inline constexpr double kMergeDistanceFraction = 0.1;

/// One point of a merged patch (world frame).
struct MergedPoint {
  Vec3 position = Vec3::Zero();  ///< m
  double normal = 0.0;           ///< N: the load pressing the body there
  double share_a = 1.0;          ///< fraction of `normal` finger a's, the rest finger b's
};

/// Two contacts' points (each contact's true point, then its SGOs and filled points, with their
/// solved loads) as one patch: a point of b closer than kMergeDistanceFraction times the smaller
/// radius to a point of a is merged into it (its load added once, the sum split between the
/// fingers by their presses `press_a`, `press_b`, N); the other points are kept. `out` reuses
/// its storage. Any thread.
void mergePatches(const ContactSnapshot& a, const ContactSnapshot& b, double press_a, double press_b,
                  std::vector<MergedPoint>& out);

/// The smallest distance (m) between two points of `points`; +inf for fewer than two.
double minPointDistance(const std::vector<MergedPoint>& points);

}  // namespace gf::sim
