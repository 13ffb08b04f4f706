// The ring of a god-finger patch in its contact's tangent plane: its axes and angles, and the
// 6-DOF pad model (docs/pad-model.md): how the contact area of Eq. 1 changes
// when the device's pad meets the surface at an angle. A flat pad gives the paper's disc of
// radius r; a pad tilted by beta gives an ellipse whose semi-axis along the tilt shrinks from r
// towards the tip's size tip_ratio r, and across it half as fast:
//   k_along  = 1 - (1 - tip_ratio) (1 - cos beta)
//   k_across = 1 - (1 - tip_ratio) (1 - cos beta) / 2
// (beta beyond 90 degrees counts as 90: the tip). The radial vectors keep their angles; each
// walks the ellipse's radius in its direction, times Eq. 2's stretch. Pure functions, any
// thread, no allocation. Internal to sim/.
#pragma once

#include <array>

#include "sim/math.hpp"
#include "sim/patch/patch_settings.hpp"

namespace gf::sim {

/// The ring's in-plane axes (t1, t2 = n x t1) for unit normal n: t1 along the part of `ref` in
/// the tangent plane when it keeps a thousandth of its length there, else a fixed basis of n.
void ringAxes(const Vec3& ref, const Vec3& n, Vec3& t1, Vec3& t2);

/// cos and sin of the ring's angles 2 pi i / n.
struct RingAngles {
  int n = 0;
  std::array<double, kMaxSgo> c{}, s{};
};

/// The ring's angles for n radial vectors, kept per thread for the last n asked for.
const RingAngles& ringAngles(int n);

/// The pad's ellipse in one contact's tangent plane, as scales of Eq. 1's radius.
struct PadEllipse {
  bool on = false;             ///< false: the disc (every scale exactly 1)
  double cos_beta = 1.0;       ///< cos of the pad angle beta, clamped to [0, 1]
  Vec3 along = Vec3::Zero();   ///< unit tilt direction in the tangent plane (the along axis)
  double k_along = 1.0;        ///< semi-axis along the tilt over r
  double k_across = 1.0;       ///< semi-axis across the tilt over r
};

/// The pad angle beta (rad) between the pad's outward normal and the press direction
/// -outward_normal (both unit, one frame): 0 for a flat pad, pi/2 for a pad standing on its tip.
double padAngle(const Vec3& pad_normal, const Vec3& outward_normal);

/// The ellipse of settings' pad model for a pad of outward normal `pad_normal` (unit, or zero:
/// no pad) on a surface of unit `outward_normal`: off for pad_model disc, no pad, or a pad too
/// flat to change a scale (the disc, exactly).
PadEllipse padEllipse(const PatchSettings& s, const Vec3& pad_normal, const Vec3& outward_normal);

/// The ellipse's radius over r in the direction of unit tangent `radial`: 1 when off.
double padRadiusScale(const PadEllipse& pad, const Vec3& radial);

/// Filled patch: the angle of the disc sector (rad) whose area at radius padRadiusScale(radial)
/// equals the ellipse's sector between the angles of `radial` -+ sector / 2 (exact: the
/// eccentric anomaly's span times k_along k_across over the radius squared); `sector` when off.
/// So the filled points' area weights follow the ellipse, summing to its area pi k_a k_c r^2.
double padSectorAngle(const PadEllipse& pad, const Vec3& radial, const Vec3& normal, double sector);

/// The uniform-pressure ellipse's mean distance from its centre over the disc's (2 r / 3): the
/// ellipse's perimeter over the unit circle's (Ramanujan's second formula, relative error below
/// 5e-5 at any aspect, exact for a circle). 1 when off. Scales the soft finger's torsion limit.
double padTorsionFactor(const PadEllipse& pad);

}  // namespace gf::sim
