#include "sim/patch/patch_ring.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gf::sim {
namespace {

// The across semi-axis shrinks at this share of the along one's rate: a fingertip narrows
// towards its tip less than its contact shortens along the finger (docs/pad-model.md).
constexpr double kAcrossShare = 0.5;
// Below this length (unit vectors) the pad's tilt has no direction on the tangent plane.
constexpr double kNoTilt = 1e-12;
// Below this length a direction has vanished (unit vectors; dimensionless).
constexpr double kDegenerateLength = 1e-12;
// The reference direction of the ring must keep this fraction of its length on the tangent
// plane to be used.
constexpr double kMinReferenceFraction = 1e-3;

// Orthonormal tangent basis of a unit normal (Duff et al., JCGT 2017, branchless form).
void tangentBasis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  t1 = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

}  // namespace

void ringAxes(const Vec3& ref, const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 ref_t = ref - ref.dot(n) * n;
  if (ref_t.norm() > kMinReferenceFraction * ref.norm() && ref_t.norm() > kDegenerateLength) {
    t1 = ref_t.normalized();
    t2 = n.cross(t1);
  } else {
    tangentBasis(n, t1, t2);
  }
}

const RingAngles& ringAngles(int n) {
  thread_local RingAngles ring;
  if (ring.n != n) {
    for (int i = 0; i < n; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / n;
      ring.c[static_cast<std::size_t>(i)] = std::cos(angle);
      ring.s[static_cast<std::size_t>(i)] = std::sin(angle);
    }
    ring.n = n;
  }
  return ring;
}

double padAngle(const Vec3& pad_normal, const Vec3& outward_normal) {
  return std::acos(std::clamp(-pad_normal.dot(outward_normal), -1.0, 1.0));
}

PadEllipse padEllipse(const PatchSettings& s, const Vec3& pad_normal_any, const Vec3& outward_normal) {
  PadEllipse pad;
  if (s.pad_model != PadModel::kOriented || !(pad_normal_any.squaredNorm() > 0.0)) return pad;
  const Vec3 pad_normal = pad_normal_any.normalized();
  // beta past 90 degrees (the pad facing away) is the tip: cos beta clamped at 0.
  pad.cos_beta = std::clamp(-pad_normal.dot(outward_normal), 0.0, 1.0);
  const double shrink = (1.0 - s.tip_ratio) * (1.0 - pad.cos_beta);
  pad.k_along = 1.0 - shrink;
  pad.k_across = 1.0 - kAcrossShare * shrink;
  const Vec3 tilt = pad_normal - pad_normal.dot(outward_normal) * outward_normal;
  const double len = tilt.norm();
  pad.on = len > kNoTilt && (pad.k_along != 1.0 || pad.k_across != 1.0);
  if (!pad.on) return PadEllipse{};
  pad.along = tilt / len;
  return pad;
}

double padRadiusScale(const PadEllipse& pad, const Vec3& radial) {
  if (!pad.on) return 1.0;
  // Polar radius of the ellipse x^2/a^2 + y^2/b^2 = 1 at direction (c, s): ab / sqrt(b^2 c^2 + a^2 s^2).
  const double c = radial.dot(pad.along);
  const double s2 = std::max(0.0, radial.squaredNorm() - c * c);
  const double a = pad.k_along, b = pad.k_across;
  return a * b / std::sqrt(b * b * c * c + a * a * s2);
}

double padSectorAngle(const PadEllipse& pad, const Vec3& radial, const Vec3& normal, double sector) {
  if (!pad.on) return sector;
  const Vec3 across = normal.cross(pad.along);
  const double c = radial.dot(pad.along), s = radial.dot(across);
  const double ch = std::cos(0.5 * sector), sh = std::sin(0.5 * sector);
  // The sector's edges at angles theta -+ sector / 2 from the along axis.
  const double c1 = c * ch + s * sh, s1 = s * ch - c * sh;
  const double c2 = c * ch - s * sh, s2 = s * ch + c * sh;
  // Eccentric anomaly E = atan2(a sin theta, b cos theta); the sector's area is a b (E2 - E1) / 2.
  const double a = pad.k_along, b = pad.k_across;
  const double span = std::atan2(a * b * std::sin(sector), b * b * c1 * c2 + a * a * s1 * s2);
  const double rho = padRadiusScale(pad, radial);
  return a * b * span / (rho * rho);
}

double padTorsionFactor(const PadEllipse& pad) {
  if (!pad.on) return 1.0;
  // Mean distance of a uniform ellipse from its centre: its perimeter / (3 pi); the disc's 2 r / 3.
  const double a = pad.k_along, b = pad.k_across;
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  const double perimeter = std::numbers::pi * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
  return perimeter / (2.0 * std::numbers::pi);
}

}  // namespace gf::sim
