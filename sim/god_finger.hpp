// The god-finger contact patch (Talvas, Marchal, Lecuyer, 3DUI 2013, Section 3): from one
// contact point to sub-god-objects (SGOs) spread over the object's mesh. A pure function of its
// inputs: no Bullet, no globals. Everything is in the touched object's local frame.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sim/mesh.hpp"
#include "sim/patch_settings.hpp"

namespace gf::sim {

/// The contact as collision detection reports it, in the object's local frame.
struct PatchContact {
  Vec3 point_local = Vec3::Zero();            ///< c_p: contact point on the object surface (m)
  Vec3 outward_normal_local = Vec3::UnitY();  ///< unit surface normal, from the object to the proxy
  double separation = 0.0;  ///< c_d: signed separation, negative when penetrating (m)
};

/// Why the walk of one radial vector ended.
enum class WalkStop : std::uint8_t {
  kDistance,          ///< travelled the full d_i
  kAngularThreshold,  ///< next face beyond tau_a (paper Fig. 2c)
  kFrictionCone,      ///< next face outside the friction cone
  kBoundary,          ///< reached a boundary edge of an open mesh
  kCrossingLimit,     ///< crossed max_face_crossings edges
  kDegenerate,        ///< direction vanished on a face (numerically degenerate geometry)
  kDropped,           ///< radial vector dropped at an edge or vertex contact (paper Fig. 3b);
                      ///< keep it last: app/patch_json.cpp names every value up to it
};

/// One sub-god-object.
struct Sgo {
  Vec3 position = Vec3::Zero();  ///< on the mesh surface (m)
  int face = -1;                 ///< triangle holding it
  int radial = -1;               ///< index of its radial vector
  double walked = 0.0;           ///< length of the walked path (m)
  WalkStop stop = WalkStop::kDistance;
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
  std::vector<Vec3> radial;                ///< r_i: unit radial vectors, on their start face
  std::vector<double> d_i;                 ///< d_i of Eq. 2: length walked along r_i (m)
  std::vector<WalkStop> radial_stop;       ///< how each radial vector's walk ended
  std::vector<Sgo> sgos;                   ///< SGOs of the radial vectors not dropped
  std::vector<Vec3> path_points;           ///< walked paths, concatenated (m)
  std::vector<std::int32_t> path_offsets;  ///< SGO k's path: [offsets[k], offsets[k+1])
};

/// Empties `patch`: not valid, no radius, no SGO, keeping its storage. Does not allocate.
void clearPatch(Patch& patch);

/// The press depth v . c_n (m) of Eq. 1, with c_n = -outward_normal the press direction: > 0
/// while the device is pressed into the object, <= 0 when it pulls away. Both vectors in one
/// frame, `outward_normal` of unit length.
double pressDepth(const Vec3& v, const Vec3& outward_normal);

/// Eq. 1: contact radius (m) for press depth v . c_n (m). Zero when not pressing.
double contactRadius(double press_depth, double r_max, double d0);

/// Eq. 2, with the exponent made dimensionless by `stretch_length` and clamped:
/// d_i = r * alpha^clamp(-(v . r_i) / stretch_length).
double stretchedDistance(double radius, const Vec3& v, const Vec3& radial_unit,
                         const PatchSettings& s);

/// Computes the god-finger patch: Eq. 1 radius, n radial vectors mapped onto the faces around
/// the contact (dropped beyond the thresholds), Eq. 2 distances and the Algorithm 1 walk.
/// `v` is p_I - p_GO (device minus god-object, m). Input it cannot compute (non-finite numbers,
/// n_sgo outside kMinSgo..kMaxSgo, d0, stretch_length or alpha not > 0, a zero normal) gives
/// `valid == false` and no SGO; the legal ranges users may give are narrower (settings.hpp). No
/// radius (not pressing) gives no SGO. Any thread.
void computePatch(const Mesh& mesh, const PatchContact& contact, const Vec3& v,
                  const PatchSettings& settings, Patch& out);

}  // namespace gf::sim
