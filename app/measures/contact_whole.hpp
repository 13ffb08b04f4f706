// Whether a finger's contact lies whole on the flat face of the body it presses: the condition
// under which the studies' friction measures (friction_force, friction_torque) mean what they
// say. A contact that reaches over the face's edge has its patch cut short there and, once its
// point is over the edge, its normal tilted: the press and the friction then mix, and the
// measure is no longer the face's friction.
#pragma once

#include <optional>

#include "sim/math.hpp"
#include "sim/patch/patch_settings.hpp"
#include "sim/scene/scene_desc.hpp"

namespace gf::app {

/// A finger pressing a body at one trace row (world frame; trace.csv's columns).
struct PressState {
  sim::Pose body;                         ///< <body>.px .. .qw
  sim::Vec3 proxy = sim::Vec3::Zero();    ///< <finger>.px .py .pz: the proxy's centre (m)
  sim::Vec3 device = sim::Vec3::Zero();   ///< <finger>.dx .dy .dz (m)
  double patch_radius = 0.0;              ///< <finger>.r: Eq. 1 radius (m); 0 for a point contact
};

/// True for the shapes whose pressed face contactOverhang knows: boxes and cylinders (the caps).
bool hasFlatFaces(sim::ShapeKind shape);

/// How far the finger's contact reaches beyond the face it presses (m): <= 0 while it lies whole
/// on the face. The face is the flat face of `body` (a box's face, a cylinder's cap) whose
/// outward normal is nearest `axis` on the proxy's side. The contact's outline is its point (the
/// proxy's centre projected onto the face) and, for a patch, the Eq. 2 distance along every
/// direction u of the face (sim::stretchedDistance of the radius, with the device's offset from
/// the proxy in the face's plane: a patch stretches away from the push) under `patch`, the
/// finger's effective settings. A point contact's outline is its point. nullopt when no flat
/// face is pressed along `axis` (a cylinder pressed on its side). Any thread; does not allocate.
std::optional<double> contactOverhang(const sim::BodyDesc& body, const sim::PatchSettings& patch,
                                      const sim::Vec3& axis, const PressState& s);

}  // namespace gf::app
