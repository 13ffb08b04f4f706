#include "app/measures/contact_whole.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/patch/god_finger.hpp"

namespace gf::app {
namespace {

using sim::Vec3;

// Directions the outline is taken along, 1 degree apart: a ring's radial vectors (turned to
// the ring's reference, which the trace does not give) fall at most half a degree from one, so
// the outline errs by at most r (1 - cos 0.5 deg), 4e-5 r.
constexpr int kOutlineDirections = 360;

// The pressed face in the body's frame: the axis of its normal and the two axes across it.
struct Face {
  int normal = 1, a = 0, b = 2;
};

// How far a point of the face's plane (body frame) lies beyond the face's edge (m).
double beyondEdge(const sim::BodyDesc& body, const Face& f, const Vec3& p) {
  if (body.shape == sim::ShapeKind::kCylinder) return std::hypot(p[f.a], p[f.b]) - body.radius;
  return std::max(std::abs(p[f.a]) - body.half_extents[f.a], std::abs(p[f.b]) - body.half_extents[f.b]);
}

// The face nearest `normal` (body frame, unit): a box's face along its largest component; a
// cylinder's cap when the normal is nearer the axis (y) than the side, else none.
std::optional<Face> pressedFace(const sim::BodyDesc& body, const Vec3& normal) {
  if (body.shape == sim::ShapeKind::kCylinder) {
    if (std::abs(normal.y()) < std::sqrt(0.5)) return std::nullopt;
    return Face{1, 0, 2};
  }
  int k = 0;
  normal.cwiseAbs().maxCoeff(&k);
  return Face{k, (k + 1) % 3, (k + 2) % 3};
}

}  // namespace

bool hasFlatFaces(sim::ShapeKind shape) { return shape == sim::ShapeKind::kBox || shape == sim::ShapeKind::kCylinder; }

std::optional<double> contactOverhang(const sim::BodyDesc& body, const sim::PatchSettings& patch,
                                      const Vec3& axis, const PressState& s) {
  // The face on the proxy's side of the body along the axis.
  const sim::Quat to_body = s.body.orientation.inverse();
  const Vec3 normal = to_body * (axis.dot(s.proxy - s.body.position) >= 0.0 ? axis : Vec3(-axis));
  const std::optional<Face> face = pressedFace(body, normal.normalized());
  if (!face) return std::nullopt;
  // The contact point: a sphere pressing a flat face touches it under its centre.
  const Vec3 point = to_body * (s.proxy - s.body.position);
  if (!(s.patch_radius > 0.0)) return beyondEdge(body, *face, point);
  // The patch's outline: Eq. 2's distance along each direction of the face, the stretch from
  // the device's offset v = p_I - p_GO in the face's plane, as the patch function takes it.
  Vec3 v_t = to_body * (s.device - s.proxy);
  v_t[face->normal] = 0.0;
  double out = -HUGE_VAL;
  for (int j = 0; j < kOutlineDirections; ++j) {
    const double angle = 2.0 * std::numbers::pi * j / kOutlineDirections;
    Vec3 u = Vec3::Zero();
    u[face->a] = std::cos(angle);
    u[face->b] = std::sin(angle);
    const double d = sim::stretchedDistance(s.patch_radius, v_t, u, patch);
    out = std::max(out, beyondEdge(body, *face, point + d * u));
  }
  return out;
}

}  // namespace gf::app
