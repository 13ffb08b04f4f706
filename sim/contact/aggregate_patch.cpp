#include "sim/contact/aggregate_patch.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "sim/patch/patch_settings.hpp"

namespace gf::sim {
namespace {

// A tilt axis whose second moment is below this fraction of the patch's (its trace) has no
// row: the points lie on a line across it and cannot hold a moment about it.
constexpr double kFlatMoment = 1e-9;

TiltDirections makeTiltDirections() {
  TiltDirections d;
  for (int j = 0; j < kTiltDirections; ++j) {
    const double a = 2.0 * 3.14159265358979323846 * j / kTiltDirections;
    d.c[static_cast<std::size_t>(j)] = std::cos(a);
    d.s[static_cast<std::size_t>(j)] = std::sin(a);
  }
  // Quarter turns exact.
  for (int q = 0; q < 4; ++q) {
    const auto j = static_cast<std::size_t>(q * kTiltDirections / 4);
    d.c[j] = q == 0 ? 1.0 : q == 2 ? -1.0 : 0.0;
    d.s[j] = q == 1 ? 1.0 : q == 3 ? -1.0 : 0.0;
  }
  return d;
}

// Points whose u_i the second pass reads back (beyond, they are computed again).
constexpr int kStoredLevers = kMaxSgo * kMaxRings + 1;
using Directions = Eigen::Array<double, kTiltDirections, 1>;

// u = rho x n for a point, rho its offset from the centre across unit n; |rho| in `length`.
btVector3 leverOf(const btVector3& p, const btVector3& centre, const btVector3& n, double* length = nullptr) {
  btVector3 rho = p - centre;
  rho -= rho.dot(n) * n;
  if (length) *length = rho.length();
  return rho.cross(n);
}

// The tilt error's sums and the support of the u_i in the tilt axes' plane. The support is
// kept in registers (as a local: shares and separations could alias out's), 2 directions a
// packet; Eigen's max is std::max lane by lane.
void tiltSupport(const btVector3* levers, const btVector3* points, const double* shares, const double* separations,
                 int count, const btVector3& centre, const btVector3& n, PressRows& out) {
  const Eigen::Map<const Directions> dc(kTiltDirectionTable.c.data()), ds(kTiltDirectionTable.s.data());
  Directions support = Directions::Zero();
  double g0 = 0.0, g1 = 0.0;
  for (int i = 0; i < count; ++i) {
    const btVector3 u = i < kStoredLevers ? levers[i] : leverOf(points[i], centre, n);
    // An axis without a moment has no row: its coordinate (rounding residue) is left out.
    const double x = out.tilt_moment[0] > 0.0 ? u.dot(out.tilt_axis[0]) : 0.0;
    const double y = out.tilt_moment[1] > 0.0 ? u.dot(out.tilt_axis[1]) : 0.0;
    g0 += shares[i] * x * separations[i];
    g1 += shares[i] * y * separations[i];
    support = support.max(x * dc + y * ds);
  }
  Eigen::Map<Directions>(out.support.data()) = support;
  out.tilt_error = {out.tilt_moment[0] > 0.0 ? g0 / out.tilt_moment[0] : 0.0,
                    out.tilt_moment[1] > 0.0 ? g1 / out.tilt_moment[1] : 0.0};
}

}  // namespace

const TiltDirections kTiltDirectionTable = makeTiltDirections();

void aggregatePatch(const btVector3* points, const double* shares, const double* separations, int count,
                    const btVector3& n, const btVector3& on_plane, double stiffness, double damping,
                    btVector3& centre, PressRows& out, double* lever_lengths) {
  btVector3 c(0, 0, 0);
  double depth = 0.0;
  for (int i = 0; i < count; ++i) {
    c += shares[i] * points[i];
    depth += shares[i] * separations[i];
  }
  const btVector3 off = c - on_plane;
  centre = on_plane + off - off.dot(n) * n;
  out.stiffness = stiffness;
  out.damping = damping;
  out.separation = depth;
  // The second moment of u_i = rho_i x n in a basis of the tangent plane, then its axes.
  btVector3 t1, t2;
  btPlaneSpace1(n, t1, t2);
  std::array<btVector3, kStoredLevers> levers;
  double sxx = 0.0, sxy = 0.0, syy = 0.0, lever = 0.0;
  // Copies the stores to lever_lengths cannot alias (so they stay in registers).
  const btVector3 at = centre, across = n;
  for (int i = 0; i < count; ++i) {
    double length = 0.0;
    const btVector3 u = leverOf(points[i], at, across, &length);
    if (i < kStoredLevers) levers[static_cast<std::size_t>(i)] = u;
    const double x = u.dot(t1), y = u.dot(t2), w = shares[i];
    sxx += w * x * x, sxy += w * x * y, syy += w * y * y;
    lever += w * length;
    lever_lengths[i] = length;
  }
  const double phi = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const double cp = std::cos(phi), sp = std::sin(phi);
  out.tilt_axis = {cp * t1 + sp * t2, -sp * t1 + cp * t2};
  const double m0 = sxx * cp * cp + 2.0 * sxy * cp * sp + syy * sp * sp;
  const double m1 = sxx * sp * sp - 2.0 * sxy * cp * sp + syy * cp * cp;
  const double flat = kFlatMoment * (sxx + syy);
  out.tilt_moment = {m0 > flat ? m0 : 0.0, m1 > flat ? m1 : 0.0};
  out.mean_lever = lever;
  tiltSupport(levers.data(), points, shares, separations, count, centre, n, out);
}

}  // namespace gf::sim
