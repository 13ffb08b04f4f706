// The contact models as the World asks them: which wants a patch, and the rows each adds for
// one contact (its friction block, its points and injected manifolds, or an aggregate block),
// on a hand-made contact between two Bullet objects.
#include <gtest/gtest.h>

#include <memory>

#include "sim/contact/contact_models.hpp"

namespace gf::sim {
namespace {

constexpr double kStiffness = 20000.0;  // N/m
constexpr double kDamping = 1000.0;     // N s/m

// A proxy touching a body 0.1 mm deep at the origin, normal +y, with one manifold point, and
// the World's side of a model's rows (solver, dispatcher, injected manifolds).
class ContactModels : public testing::Test {
 protected:
  ContactModels() {
    proxy_.setCollisionShape(&sphere_);
    object_.setCollisionShape(&sphere_);
    proxy_.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 0.0099, 0)));
    object_.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -0.01, 0)));
    manifold_ = dispatcher_.getNewManifold(&proxy_, &object_);
    manifold_->addManifoldPoint(btManifoldPoint(btVector3(0, -0.01, 0), btVector3(0, 0.01, 0), btVector3(0, 1, 0), -1e-4));
    c_->truth = {&object_, btVector3(0, 0, 0), btVector3(0, 1, 0), -1e-4, 0};
    c_->manifold = manifold_;
    injected_.reserve(64);
  }
  ~ContactModels() override {
    releaseInjected(dispatcher_, injected_);
    dispatcher_.releaseManifold(manifold_);
  }
  // A ring patch of n points at radius r, sharing n / (n + 1) of the load, all pressing.
  void ring(int n, double r) {
    Patch& p = c_->record.patch;
    p.sgos.resize(static_cast<std::size_t>(n));
    p.centre_share = 1.0 / (n + 1.0);
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * 3.141592653589793 * i / n;
      Sgo& s = p.sgos[static_cast<std::size_t>(i)];
      s.radial = i;
      s.load_share = 1.0 / (n + 1.0);
      c_->sgo_world[static_cast<std::size_t>(i)] = btVector3(r * std::cos(a), 0, r * std::sin(a));
      c_->sgo_separation[static_cast<std::size_t>(i)] = -1e-4;
    }
    c_->sgo_count = n;
  }
  const FrictionBlock& rowsOf(const EffectiveSettings& s) {
    fingerModel(s.patch.model).addRows({*c_, nullptr, s, &proxy_, kStiffness, kDamping}, rows_);
    return solver_.block(c_->block);
  }
  static EffectiveSettings settings(ContactModel model, ContactSolver solver = ContactSolver::kPoints,
                                    bool friction = true) {
    PatchSettings p;
    p.model = model;
    EffectSet effects;
    effects.friction = friction;
    return effectiveSettings(p, effects, solver);
  }

  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btSphereShape sphere_{0.01};
  btCollisionObject proxy_, object_;
  btPersistentManifold* manifold_ = nullptr;
  PatchFrictionSolver solver_;
  std::vector<btPersistentManifold*> injected_;
  AggregateScratch scratch_;
  SolveRows rows_{solver_, dispatcher_, injected_, scratch_};
  std::unique_ptr<FingerContact> c_ = std::make_unique<FingerContact>();
};

TEST_F(ContactModels, OnlyTheGodFingerAsksForAPatch) {
  EXPECT_FALSE(fingerModel(ContactModel::kGodObject).wantsPatch());
  EXPECT_FALSE(fingerModel(ContactModel::kSoftFinger).wantsPatch());
  EXPECT_TRUE(fingerModel(ContactModel::kGodFinger).wantsPatch());
}

TEST_F(ContactModels, AGodObjectIsOnePointWithFrictionAgainstSlidingOnly) {
  const FrictionBlock& b = rowsOf(settings(ContactModel::kGodObject));
  EXPECT_EQ(b.point_count, 1);
  EXPECT_EQ(b.friction, 1.0);
  EXPECT_EQ(b.torsion, 0.0);
  EXPECT_FALSE(b.aggregate || c_->aggregate);
  EXPECT_TRUE(injected_.empty());
  ASSERT_EQ(manifold_->getNumContacts(), 1);
  EXPECT_EQ(manifold_->getContactPoint(0).m_combinedContactStiffness1, kStiffness) << "the whole stiffness";
  EXPECT_EQ(manifold_->getContactPoint(0).m_combinedFriction, 0.0) << "friction is the block's";
}

TEST_F(ContactModels, ASoftFingersTorsionLimitIsItsTorsionalFrictionWhileFrictionIsOn) {
  EXPECT_EQ(rowsOf(settings(ContactModel::kSoftFinger)).torsion, PatchSettings{}.torsional_friction);
  const FrictionBlock& off = rowsOf(settings(ContactModel::kSoftFinger, ContactSolver::kPoints, false));
  EXPECT_EQ(off.torsion, 0.0);
  EXPECT_EQ(off.friction, 0.0);
}

// The points solver's torsion limit is the aggregate's (mu times the points' load-weighted mean
// lever), not one taken from the solved normal impulses.
TEST_F(ContactModels, AGodFingerPatchIsItsPointsWithTheAggregatesTorsionLimit) {
  ring(8, 0.005);
  const FrictionBlock& b = rowsOf(settings(ContactModel::kGodFinger));
  EXPECT_EQ(b.point_count, 9) << "the true contact and 8 SGOs";
  EXPECT_NEAR(b.torsion, 8.0 / 9.0 * 0.005, 1e-12) << "mu times the points' mean lever";
  EXPECT_EQ(injected_.size(), 2u) << "4 points per manifold";
  EXPECT_NEAR(b.centre.length(), 0.0, 1e-12) << "a balanced ring: the load's centre at the contact";
  EXPECT_NEAR(c_->sgo_material[0].stiffness, kStiffness / 9.0, 1e-9);
  EXPECT_NEAR(manifold_->getContactPoint(0).m_combinedContactStiffness1, kStiffness / 9.0, 1e-9);
}

TEST_F(ContactModels, AGodFingerWithoutFrictionHasNoTorsionRow) {
  ring(8, 0.005);
  EXPECT_EQ(rowsOf(settings(ContactModel::kGodFinger, ContactSolver::kPoints, false)).torsion, 0.0);
}

TEST_F(ContactModels, TheAggregateSolverMakesOneBlockOfAPatch) {
  ring(8, 0.005);
  const FrictionBlock& b = rowsOf(settings(ContactModel::kGodFinger, ContactSolver::kAggregate));
  EXPECT_TRUE(b.aggregate && c_->aggregate);
  EXPECT_EQ(b.point_count, 0);
  EXPECT_TRUE(injected_.empty());
  EXPECT_EQ(manifold_->getNumContacts(), 0) << "no Bullet row for the true contact";
  EXPECT_NEAR(b.press.stiffness, kStiffness, 1e-9) << "every point presses";
  EXPECT_NEAR(b.torsion, 8.0 / 9.0 * 0.005, 1e-12) << "mu times the points' mean lever";
}

TEST_F(ContactModels, TheAggregateSolverLeavesAContactWithoutPatchAsAPoint) {
  const FrictionBlock& b = rowsOf(settings(ContactModel::kGodFinger, ContactSolver::kAggregate));
  EXPECT_FALSE(b.aggregate);
  EXPECT_EQ(b.point_count, 1);
}

}  // namespace
}  // namespace gf::sim
