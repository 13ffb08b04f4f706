#include "sim/scene/effective_settings.hpp"

namespace gf::sim {

EffectiveSettings effectiveSettings(const PatchSettings& patch, const EffectSet& effects,
                                    ContactSolver world_solver) {
  EffectiveSettings e;
  e.patch = patch;
  // The model: n_sgo 0 makes a god-finger a god-object, and so does the god_finger effect off.
  e.patch.model = effectiveModel(patch);
  if (e.patch.model == ContactModel::kGodFinger && !effects.god_finger) {
    e.patch.model = ContactModel::kGodObject;
  }
  // The patch's effect switches: a finger keeps an effect only where the scene has it.
  e.patch.tangential_stretch &= effects.tangential_stretch;
  e.patch.angular_threshold &= effects.angular_threshold;
  e.patch.friction_cone &= effects.friction_cone;
  // A frictionless scene: no friction against sliding, no torsion limit.
  e.friction_effect = effects.friction;
  if (!effects.friction) {
    e.patch.friction = 0.0;
    e.patch.torsional_friction = 0.0;
  }
  e.solver = resolveSolver(patch.contact_solver, world_solver);
  return e;
}

}  // namespace gf::sim
