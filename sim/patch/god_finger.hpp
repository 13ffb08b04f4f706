// The god-finger contact patch (Talvas, Marchal, Lecuyer, 3DUI 2013, Section 3): from one
// contact point to sub-god-objects (SGOs) spread over the object's mesh. A pure function of its
// inputs: no Bullet, no globals. Everything is in the touched object's local frame.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sim/mesh/mesh.hpp"
#include "sim/patch/patch_settings.hpp"

namespace gf::sim {

/// The contact as collision detection reports it, in the object's local frame.
struct PatchContact {
  Vec3 point_local = Vec3::Zero();            ///< c_p: contact point on the object surface (m)
  Vec3 outward_normal_local = Vec3::UnitY();  ///< unit surface normal, from the object to the proxy
  double separation = 0.0;  ///< c_d: signed separation, negative when penetrating (m)
  /// Collision margin of the shape that reported the contact (m): its edges and corners are
  /// rounded with this radius, so an edge or vertex contact lands up to this far (sqrt(2) times
  /// for a corner) from the mesh feature, with a normal between the faces' normals. 0: sharp.
  double rounding = 0.0;
  /// Radial vector 0 points along this direction projected onto the contact's tangent plane:
  /// pass the previous step's Patch::ring_tangent so the ring does not turn between steps.
  /// Zero (or along the normal): a fixed tangent basis of the normal.
  Vec3 ring_reference_local = Vec3::Zero();
  /// The 6-DOF pad's outward normal (unit; the device's orientation times the finger's
  /// pad_axis), read when the settings' pad_model is oriented: the patch becomes the pad's
  /// ellipse (sim/patch/patch_ring.hpp). Zero: no pad, the disc.
  Vec3 pad_normal_local = Vec3::Zero();
};

/// Why the walk of one radial vector ended.
enum class WalkStop : std::uint8_t {
  kDistance,          ///< travelled the full d_i
  kAngularThreshold,  ///< next face beyond tau_a (paper Fig. 2c)
  kFrictionCone,      ///< next face outside the friction cone
  kBoundary,          ///< reached a boundary edge of an open mesh
  kCrossingLimit,     ///< used up its budget of edge crossings (PatchSettings::max_face_crossings)
  kDegenerate,        ///< direction vanished on a face (numerically degenerate geometry)
  kFacingAway,        ///< next face turned 90 degrees or more from the contact normal: an SGO
                      ///< there could not push along it, whatever the thresholds
  kDropped,           ///< radial vector dropped at an edge or vertex contact (paper Fig. 3b);
                      ///< keep it last: app/runs/contacts.cpp names every value up to it
};

/// One sub-god-object.
struct Sgo {
  Vec3 position = Vec3::Zero();  ///< on the mesh surface (m)
  int face = -1;                 ///< triangle holding it
  int radial = -1;               ///< index of its radial vector
  double walked = 0.0;           ///< length of the walked path (m)
  WalkStop stop = WalkStop::kDistance;
  /// Its share of the patch's load, stiffness and damping: with Patch::centre_share and the
  /// other points' shares it sums to 1. Ring: the SGOs share n / (n + 1) inversely to their
  /// distance from the contact across the normal, so the load's centre stays at the contact
  /// whatever Eq. 2 stretches (exactly when the radial vectors are balanced, none dropped).
  /// Filled: in proportion to `area`, so a flat press gives a uniform pressure.
  double load_share = 0.0;
  /// Filled patch: which point of its path it is, 1 .. rings (rings: the walk's end); its
  /// stretch of the patch (m^2): the annular sector of angle 2 pi / n_sgo between the
  /// midpoints to its path neighbours (out to the walk's end for the last). 0 for a ring.
  int ring = 0;
  double area = 0.0;
};

/// Result of one patch computation, in the object's local frame (the mesh's frame). Reused
/// between calls: after the first call with a given n_sgo and path length, computing into the
/// same Patch does not allocate.
struct Patch {
  bool valid = false;                      ///< false when the input was rejected
  double press_depth = 0.0;                ///< v . c_n with c_n into the object (m)
  double radius = 0.0;                     ///< r of Eq. 1 (m)
  SurfacePoint hit;                        ///< contact point on the mesh with its feature
  Vec3 press_dir = Vec3::Zero();           ///< c_n of the paper: -outward_normal
  Vec3 ring_tangent = Vec3::Zero();        ///< direction of radial vector 0 (unit, tangent plane)
  std::vector<Vec3> radial;                ///< r_i: unit radial vectors, on their start face
  std::vector<double> d_i;                 ///< d_i of Eq. 2: length walked along r_i (m)
  std::vector<WalkStop> radial_stop;       ///< how each radial vector's walk ended
  std::vector<Sgo> sgos;                   ///< SGOs of the radial vectors not dropped
  /// Filled patch: the points along the walked paths short of their ends, rings 1 .. rings-1
  /// of each path in path order (SGOs as well: the World injects them with `sgos`).
  std::vector<Sgo> inner;
  /// The contact point's share of the load (ring: 1 / (1 + SGOs); filled: its disc's area over
  /// the patch's), and the area (m^2) it stands for in a filled patch (0 for a ring).
  double centre_share = 1.0;
  double centre_area = 0.0;
  std::vector<Vec3> path_points;           ///< walked paths, concatenated (m)
  std::vector<std::int32_t> path_offsets;  ///< SGO k's path: [offsets[k], offsets[k+1])
  /// A ring computed with a WalkCache: the crossings of the walks carried within their slack
  /// are not in `path_points` (their slots unset) until placePendingCrossings places them.
  bool crossings_pending = false;
};

/// Tolerance (rad) of every angle comparison of the patch: threshold ties and whether a normal
/// differs from a face's normal. Far above the rounding of float contact normals (~1e-7).
inline constexpr double kAngleTolerance = 1e-5;

/// Empties `patch`: not valid, no radius, no SGO, keeping its storage. Does not allocate.
void clearPatch(Patch& patch);

/// The press depth v . c_n (m) of Eq. 1, with c_n = -outward_normal the press direction: > 0
/// while the device is pressed into the object, <= 0 when it pulls away. Both vectors in one
/// frame, `outward_normal` of unit length.
double pressDepth(const Vec3& v, const Vec3& outward_normal);

/// Eq. 1: contact radius (m) for press depth v . c_n (m). Zero when not pressing.
double contactRadius(double press_depth, double r_max, double d0);

/// Eq. 2 with the exponent made dimensionless by `stretch_length`, bounded by max_stretch:
/// d_i = clamp(r * alpha^(-(v_t . r_i) / stretch_length), r / max_stretch, r * max_stretch).
/// `v_tangential` is the part of v in the contact's tangent plane and `radial_unit` the radial
/// vector r_i in that plane (before it is mapped onto a face), so pressing alone stretches
/// nothing.
double stretchedDistance(double radius, const Vec3& v_tangential, const Vec3& radial_unit,
                         const PatchSettings& s);

/// Classifies the surface point of `contact` on `mesh`: the closest point, promoted to an edge
/// (vertex) hit when the contact normal points strictly between the faces around that edge
/// (vertex) and the reported point lies within the rounding (sqrt(2) rounding for a vertex)
/// plus `feature_tolerance` of it; the point is then snapped onto the feature.
SurfacePoint contactFeature(const Mesh& mesh, const PatchContact& contact, double feature_tolerance);

/// Computes the god-finger patch: Eq. 1 radius, n radial vectors mapped onto the faces around
/// the contact (dropped beyond the thresholds), Eq. 2 distances and the Algorithm 1 walk.
/// Angles are compared with a tolerance of kAngleTolerance, so exact ties (a 45-degree normal
/// at a 90-degree edge with friction 1, tau_a 0 on a flat face) keep the face. The faces the
/// contact lies on (the hit face; at an edge or vertex, the faces best aligned with the normal)
/// always count; no SGO walks onto a face turned 90 degrees or more from the contact normal.
/// `v` is p_I - p_GO (device minus god-object, m). Input it cannot compute (non-finite numbers,
/// n_sgo outside kMinSgo..kMaxSgo, d0, stretch_length or alpha not > 0, a zero normal) gives
/// `valid == false` and no SGO; the legal ranges users may give are narrower (settings.hpp). No
/// radius (not pressing) gives no SGO. A filled patch (settings.fill) also places settings.rings
/// - 1 points along each walked path at k / rings of its length, and weights every point by
/// the area it stands for; what a walk did not reach (dropped vectors, walks stopped at a
/// threshold or boundary) counts for nothing. Any thread.
void computePatch(const Mesh& mesh, const PatchContact& contact, const Vec3& v,
                  const PatchSettings& settings, Patch& out);

struct WalkCache;

/// computePatch with warm-started walks (warm_walk.hpp): on a face hit, each radial vector's
/// walk is carried from the path `warm` holds from the last call for the same finger and body
/// when that path still holds, else walked from the contact; `warm` then holds this patch's
/// paths. Edge and vertex hits walk from the contact. A ring's path points may be left pending
/// (Patch::crossings_pending). SGOs agree
/// with computePatch's to rounding (tests: 1e-9 m). Null `warm`: computePatch. Any thread;
/// allocates only the first time a cache is used.
void computePatch(const Mesh& mesh, const PatchContact& contact, const Vec3& v, const PatchSettings& settings,
                  Patch& out, WalkCache* warm);

/// Places the crossings `patch` left pending (Patch::crossings_pending) from `warm`, the cache
/// it was computed with, before that cache computes another patch: bitwise the points placed at
/// once. Any thread; no allocation.
void placePendingCrossings(const WalkCache& warm, Patch& patch);

}  // namespace gf::sim
