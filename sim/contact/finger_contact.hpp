// One finger's contact with one body during a step, and what it leaves for the next step: the
// state the World's contact pipeline and the contact models share. Haptic thread only; plain
// storage sized at compile time (nothing allocates per step). Internal to sim/.
#pragma once

#include <array>

#include "sim/contact/contact_record.hpp"
#include "sim/patch/warm_walk.hpp"
#include "sim/contact/contact_injection.hpp"

namespace gf::sim {

/// How far a sticking contact has slid since it started sticking: its friction block's relative
/// motion at its centre (the proxy's side against the body's, across the normal) and about its
/// normal, summed step by step from the solved velocities, as the positions move. While the
/// contact sticks its block takes the slip back, so what the solve leaves of a sticking contact's
/// sliding does not add up step after step. (Not material points: a ball rolling under a point
/// contact slides nowhere.)
struct FrictionAnchor {
  bool set = false;            ///< sticking: `slip` counts
  btVector3 slip{0, 0, 0};     ///< proxy side against the body's, world (m)
  double turn = 0.0;           ///< the proxy's turn against the body's about the normal (rad)
};

/// Points a patch injects besides the true contact: the SGOs and a filled patch's inner points.
inline constexpr int kMaxPatchPoints = kMaxSgo * kMaxRings;

/// What a snapshot needs of a contact's last solve to split its loads over its points
/// (solvedLoads): kept by keepSolved after the solve.
struct SolvedContact {
  std::array<double, kMaxPatchPoints + 1> normal{};  ///< points solver: the true contact's, then each patch point's normal impulse (N s)
  double dt = 0.0;                                   ///< the step (s)
  btMatrix3x3 body_basis = btMatrix3x3::getIdentity();  ///< the body's orientation during the solve
};

/// A finger's contact with one body this step: the deepest point over every manifold between
/// the proxy and the body (one per child hull of a compound).
struct FingerContact {
  ContactRecord record;  ///< body frame: what snapshots show, kept until the next step
  // Bullet's side, valid during the solve only (manifolds are Bullet's and change every step).
  TrueContact truth;
  Vec3 v_local = Vec3::Zero();               ///< p_I - p_GO in the body frame (Eq. 1, Eq. 2)
  btPersistentManifold* manifold = nullptr;  ///< holds the true point; null outside the solve
  // The patch's points: its SGOs, then a filled patch's inner points.
  std::array<btVector3, kMaxPatchPoints> sgo_world;    ///< where the solver sees them (world)
  std::array<double, kMaxPatchPoints> sgo_separation;  ///< their depth below the pad plane (m)
  std::array<WarmStart, kMaxPatchPoints> sgo_warm;     ///< points solver: their warm starts
  std::array<PointMaterial, kMaxPatchPoints> sgo_material;  ///< points solver: their materials
  int sgo_count = 0;
  int first_injected = 0;  ///< index of its first injected manifold (points solver)
  int block = -1;          ///< its friction block this step (PatchFrictionSolver::block)
  bool aggregate = false;  ///< solved as one aggregate block (no injected points, no Bullet row)
  Vec3 pad_normal = Vec3::UnitY();  ///< the pad plane's normal (world)
  FrictionAnchor anchor;            ///< where its block sticks (set by the contact model)
  /// Its walks, carried from the body's last contact with the finger (warm-started walks).
  WalkCache walks;
  SolvedContact solved;  ///< after the solve, for snapshots
};

/// What a finger's contact with one body leaves for the next step: the solved impulses (to
/// warm-start the solver), the ring's frame and whether it had a patch.
struct ContactMemory {
  int body = -1;
  WarmStart truth;  ///< the true contact's point (points solver)
  int n_sgo = 0;        ///< radial vectors of the patch the impulses belong to
  int layer_count = 0;  ///< layers of `layers` holding them (the rest is stale)
  /// By ring (a filled patch's point k of its path in layer k - 1; a ring's SGOs in layer 0)
  /// and radial index: radial i at angle 2 pi i / n_sgo.
  std::array<std::array<WarmStart, kMaxSgo>, kMaxRings> layers;
  Vec3 ring_tangent_local = Vec3::Zero();  ///< radial 0's direction, body frame
  bool had_patch = false;
  Vec3 pad_normal = Vec3::UnitY();    ///< the pad plane's normal (world)
  btVector3 friction_force{0, 0, 0};  ///< the friction block's impulses (warm start, N s)
  double friction_torque = 0.0;       ///< N m s
  btVector3 rolling_impulse{0, 0, 0};  ///< a points block's rolling impulse (N m s)
  double normal_impulse = 0.0;        ///< the contact's total normal impulse (N s)
  btVector3 tilt_impulse{0, 0, 0};    ///< an aggregate block's tilt impulse (N m s)
  FrictionAnchor anchor;              ///< kept while the block sticks (unset after it slid)
};

/// Injected point i of a patch: its SGOs, then a filled patch's inner points.
inline const Sgo& injectedPoint(const Patch& patch, int i) {
  const auto k = static_cast<std::size_t>(i);
  return k < patch.sgos.size() ? patch.sgos[k] : patch.inner[k - patch.sgos.size()];
}

/// The layer of ContactMemory::layers that keeps a patch point's impulses.
inline int layerOf(const Sgo& p) { return p.ring > 0 ? p.ring - 1 : 0; }

}  // namespace gf::sim
