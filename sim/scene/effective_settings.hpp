// A finger's settings as its contacts use them: its PatchSettings after the scene's effect
// switches, its effective contact model and its resolved solver. The World computes them once
// per change of the finger's settings (construction, a scripted change, setPatchSettings) and
// reads nothing else when it handles the finger's contacts.
#pragma once

#include "sim/scene/scene_desc.hpp"

namespace gf::sim {

/// One finger's effective settings (plain data).
struct EffectiveSettings {
  /// What the patch function and the contact model use: `model` is the effective model (a
  /// god-object for n_sgo 0 or without the god_finger effect); `friction` and
  /// `torsional_friction` are 0 without the friction effect; `tangential_stretch`,
  /// `angular_threshold` and `friction_cone` are off where the scene turns those effects off.
  /// The other fields are the finger's own.
  PatchSettings patch;
  /// How its god-finger contacts are solved: the finger's `contact_solver` under the world's.
  ContactSolver solver = ContactSolver::kPoints;
  /// The scene's friction effect: off, the finger's contacts have no friction and no torsion
  /// limit at all (not even a god-finger patch's own).
  bool friction_effect = true;
};

/// The effective settings of a finger set to `patch` in a scene with `effects` and the world's
/// `world_solver`. Pure: any thread; does not allocate.
EffectiveSettings effectiveSettings(const PatchSettings& patch, const EffectSet& effects,
                                    ContactSolver world_solver);

}  // namespace gf::sim
