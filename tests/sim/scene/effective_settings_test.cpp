// A finger's effective settings: the scene's effect switches applied to its PatchSettings once,
// its effective model and its resolved solver.
#include "sim/scene/effective_settings.hpp"

#include <gtest/gtest.h>

namespace gf::sim {
namespace {

PatchSettings softFinger() {
  PatchSettings p;
  p.model = ContactModel::kSoftFinger;
  p.friction = 0.7;
  p.torsional_friction = 0.004;
  return p;
}

TEST(EffectiveSettings, EveryEffectOnKeepsTheFingersOwnSettings) {
  const PatchSettings p = softFinger();
  const EffectiveSettings e = effectiveSettings(p, EffectSet{}, ContactSolver::kPoints);
  EXPECT_EQ(e.patch.model, ContactModel::kSoftFinger);
  EXPECT_EQ(e.patch.friction, 0.7);
  EXPECT_EQ(e.patch.torsional_friction, 0.004);
  EXPECT_TRUE(e.patch.tangential_stretch && e.patch.angular_threshold && e.patch.friction_cone);
  EXPECT_TRUE(e.friction_effect);
  EXPECT_EQ(e.solver, ContactSolver::kPoints);
}

TEST(EffectiveSettings, NoFrictionEffectZeroesFrictionAndTorsion) {
  EffectSet effects;
  effects.friction = false;
  const EffectiveSettings e = effectiveSettings(softFinger(), effects, ContactSolver::kPoints);
  EXPECT_EQ(e.patch.friction, 0.0);
  EXPECT_EQ(e.patch.torsional_friction, 0.0);
  EXPECT_FALSE(e.friction_effect);
  EXPECT_EQ(e.patch.model, ContactModel::kSoftFinger) << "the model stays";
}

TEST(EffectiveSettings, AGodFingerWithoutSgosOrWithoutItsEffectIsAGodObject) {
  PatchSettings p;
  EXPECT_EQ(effectiveSettings(p, EffectSet{}, ContactSolver::kPoints).patch.model, ContactModel::kGodFinger);
  p.n_sgo = 0;
  EXPECT_EQ(effectiveSettings(p, EffectSet{}, ContactSolver::kPoints).patch.model, ContactModel::kGodObject);
  p.n_sgo = 8;
  EffectSet effects;
  effects.god_finger = false;
  EXPECT_EQ(effectiveSettings(p, effects, ContactSolver::kPoints).patch.model, ContactModel::kGodObject);
  EXPECT_EQ(effectiveSettings(softFinger(), effects, ContactSolver::kPoints).patch.model,
            ContactModel::kSoftFinger)
      << "the god_finger effect turns god-fingers only";
}

TEST(EffectiveSettings, PatchSwitchesNeedTheSceneAndTheFinger) {
  PatchSettings p;
  p.friction_cone = false;
  EffectSet effects;
  effects.tangential_stretch = false;
  const EffectiveSettings e = effectiveSettings(p, effects, ContactSolver::kPoints);
  EXPECT_FALSE(e.patch.tangential_stretch) << "off in the scene";
  EXPECT_TRUE(e.patch.angular_threshold) << "on in both";
  EXPECT_FALSE(e.patch.friction_cone) << "off for the finger";
}

TEST(EffectiveSettings, TheFingersSolverChoiceWinsOverTheWorlds) {
  PatchSettings p;
  EXPECT_EQ(effectiveSettings(p, EffectSet{}, ContactSolver::kAggregate).solver, ContactSolver::kAggregate);
  p.contact_solver = SolverChoice::kPoints;
  EXPECT_EQ(effectiveSettings(p, EffectSet{}, ContactSolver::kAggregate).solver, ContactSolver::kPoints);
  p.contact_solver = SolverChoice::kAggregate;
  EXPECT_EQ(effectiveSettings(p, EffectSet{}, ContactSolver::kPoints).solver, ContactSolver::kAggregate);
}

}  // namespace
}  // namespace gf::sim
