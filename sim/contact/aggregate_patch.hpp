// The pressing rows of an aggregate block (sim/contact/patch_friction.hpp) from a patch's points:
// the load centre, the normal row's stiffness, damping and depth, the tilt rows' axes, moments
// and error, and the support of the points' hull that bounds the tilt moment. A pure function of
// the points (no solver state). Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <array>

namespace gf::sim {

/// Directions in which an aggregate block bounds the tilt moment by the points' hull: the hull's
/// support is sampled every 360 / kTiltDirections degrees (an outer polygon of the hull, within
/// 1 / cos(pi / 16) - 1 = 2 % of it for a disc).
inline constexpr int kTiltDirections = 16;

/// The pressing rows of an aggregate block, from the patch's points (aggregatePatch).
struct PressRows {
  double stiffness = 0.0;   ///< N/m: the contact's total
  double damping = 0.0;     ///< N s/m: the contact's total
  double separation = 0.0;  ///< the load centre's depth: sum_i w_i s_i (m, negative when pressing)
  /// Unit tilt axes in the tangent plane: principal axes of the points' second moment
  /// S = sum_i w_i u_i u_i^T, u_i = rho_i x n (rho_i: point i from the centre, across n).
  std::array<btVector3, 2> tilt_axis{btVector3(1, 0, 0), btVector3(0, 0, 1)};
  std::array<double, 2> tilt_moment{};  ///< S's eigenvalues (m^2): tilt stiffness per N/m
  /// The tilt the points' depths make about each axis: sum_i w_i (u_i . a_k) s_i / S_k (rad).
  std::array<double, 2> tilt_error{};
  /// Support of the points' hull in the (a_0, a_1) plane of the u_i: h_j = max_i u_i . d_j with
  /// d_j = cos(2 pi j / K) a_0 + sin(2 pi j / K) a_1 (m). The tilt impulse over the normal
  /// impulse stays within {x : x . d_j <= h_j}.
  std::array<double, kTiltDirections> support{};
  double mean_lever = 0.0;   ///< sum_i w_i |rho_i| (m): torsion limit per unit mu N
  double warm_normal = 0.0;  ///< last step's normal impulse (N s)
  btVector3 warm_tilt{0, 0, 0};  ///< last step's tilt impulse on the proxy side (world, N m s)
  btVector3 tilt{0, 0, 0};       ///< result: the solved tilt impulse (world, N m s)
};

/// The load centre and pressing rows of a patch: `count` points (world), their load shares
/// (summing to 1) and separations (m, negative when penetrating), with the contact's outward
/// normal (unit) and total stiffness and damping. The centre is the share-weighted centroid
/// moved along `normal` onto the plane through `on_plane`; each point's distance from the
/// centre across the normal (m) into lever_lengths[0 .. count). Does not allocate.
void aggregatePatch(const btVector3* points, const double* shares, const double* separations, int count,
                    const btVector3& normal, const btVector3& on_plane, double stiffness, double damping,
                    btVector3& centre, PressRows& out, double* lever_lengths);

/// cos and sin of the tilt limit's directions d_j at 2 pi j / kTiltDirections, the quarter
/// turns exact (cos(pi / 2) would be 6e-17, and on a flat patch a ratio of two such rounding
/// residues could cap a tilt that has no extent there).
struct TiltDirections {
  std::array<double, kTiltDirections> c{}, s{};
};
/// The directions' table: built once before main, read-only (any thread).
extern const TiltDirections kTiltDirectionTable;

}  // namespace gf::sim
