// The loads on a contact's points (ContactSnapshot::force, point_load, loads, rolling_moment,
// torsion_moment) against what the bodies do. A 1 kg box on a frictionless table pressed from above by one
// finger (friction 1, about 4.8 N; tests/sim/pressed_box.hpp): at rest the proxy is in
// equilibrium, so the contact's force is the coupling force (within 1e-4); while the box is
// held, slides or spins under the finger, the finger's friction is the load minus the box's
// change of momentum over the window, and the points' tangential forces must add up to it and
// turn the box with it (within 1e-5). Fig. 8's pinch: the held cylinder's moments close.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/scene/snapshot.hpp"
#include "sim/world/world.hpp"
#include "tests/sim/pressed_box.hpp"
#include "tests/sim/test_context.hpp"

namespace gf::sim {
namespace {

using pressed_box::kHalfWidth, pressed_box::kInertiaY, pressed_box::kLoadStart, pressed_box::kMass;

struct Case {
  const char* name;
  ContactModel model;
  PatchFill fill;
  SolverChoice solver;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

PatchSettings settingsOf(const Case& c) {
  PatchSettings p;
  p.model = c.model;
  p.fill = c.fill;
  p.n_sgo = 8;
  p.contact_solver = c.solver;
  p.friction = 1.0;
  return p;
}

constexpr double kDt = 1e-3;  // s

template <class Observe>
void run(World& w, double until, Observe&& observe) {
  const DeviceTrack track = w.desc().fingers[0].device;
  while (w.time() < until - 0.5 * kDt) {
    const DeviceSample d = track.sample(w.time());
    w.step(kDt, std::span(&d, 1));
    observe();
  }
}

// The sum of a contact's point loads as forces on the body.
Vec3 pointSum(const ContactSnapshot& c) {
  const Vec3& n = c.outward_normal_world;
  Vec3 sum = c.point_load.tangential - c.point_load.normal * n;
  for (const PointLoad& l : c.loads) sum += l.tangential - l.normal * n;
  return sum;
}

// The points' tangential forces: their sum, and with the moment they do not carry
// (torsion_moment) their moment about the vertical through the box's centre (N m).
struct Friction {
  Vec3 force = Vec3::Zero();
  double moment = 0.0;
};
Friction frictionOf(const ContactSnapshot& c, const Vec3& box_centre) {
  Friction f;
  f.moment = c.torsion_moment.y();
  const auto add = [&](const Vec3& at, const PointLoad& l) {
    f.force += l.tangential;
    f.moment += (at - box_centre).cross(l.tangential).y();
  };
  add(c.point_world, c.point_load);
  for (std::size_t i = 0; i < c.loads.size(); ++i) add(c.sgos_world[i], c.loads[i]);
  return f;
}

class PointLoads : public testing::TestWithParam<Case> {};

TEST_P(PointLoads, AtRestAddUpToTheCouplingForceWithoutSlip) {
  World w(pressed_box::scene(settingsOf(GetParam()), 0.0, LoadDesc{}));
  run(w, kLoadStart, [] {});
  Snapshot snap;
  w.snapshot(snap);
  ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
  const ContactSnapshot& c = snap.fingers[0].contacts[0];
  ASSERT_EQ(c.loads.size(), c.sgos_world.size());
  if (GetParam().model == ContactModel::kGodFinger) {
    EXPECT_GE(c.loads.size(), 8u);
  }
  const Vec3 coupling = w.couplingForce(0);
  EXPECT_GT(coupling.norm(), 4.0);
  // The proxy rests: the contact pushes it up as hard as the coupling pulls it down.
  EXPECT_LT((c.force - coupling).norm(), 1e-4 * coupling.norm())
      << c.force.transpose() << " vs " << coupling.transpose();
  EXPECT_LT((pointSum(c) - c.force).norm(), 1e-9 * coupling.norm());
  EXPECT_FALSE(c.sliding);
  EXPECT_FALSE(c.point_load.slipping);
  for (const PointLoad& l : c.loads) {
    EXPECT_GE(l.normal, 0.0);
    EXPECT_FALSE(l.slipping);
  }
  // A flat, even press on a ring: its SGOs carry equal loads (within 1 %).
  if (GetParam().model == ContactModel::kGodFinger && GetParam().fill == PatchFill::kRing) {
    for (const PointLoad& l : c.loads)
      EXPECT_NEAR(l.normal, c.loads[0].normal, 0.01 * c.loads[0].normal);
  }
}

TEST_P(PointLoads, WhileTheBoxSlidesTheyAreTheFingersFrictionAndAllSlip) {
  LoadDesc load;
  load.force =
      Vec3(5.75, 0.0, 0.0);  // N: 1.25 times the finger's friction limit (mu N, about 4.6 N)
  World w(pressed_box::scene(settingsOf(GetParam()), 0.0, load));
  Snapshot snap;
  Vec3 friction = Vec3::Zero();
  int samples = 0;
  run(w, kLoadStart + 0.05, [] {});
  const Vec3 v0 = w.bodyLinearVelocity(1);
  run(w, kLoadStart + 0.2, [&] {
    w.snapshot(snap);
    ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
    const ContactSnapshot& c = snap.fingers[0].contacts[0];
    friction += frictionOf(c, snap.bodies[1].position).force;
    ++samples;
    EXPECT_TRUE(c.sliding) << "t = " << w.time();
    EXPECT_TRUE(c.point_load.slipping || c.point_load.normal == 0.0);
    for (const PointLoad& l : c.loads) EXPECT_TRUE(l.slipping || l.normal == 0.0);
  });
  // The finger's mean friction on the box (N), by the box's change of momentum.
  const double measured =
      load.force.x() - kMass * (w.bodyLinearVelocity(1) - v0).x() / (samples * kDt);
  EXPECT_NEAR(-friction.x() / samples, measured, 1e-5 * measured);
  EXPECT_NEAR(friction.z() / samples, 0.0, 1e-5 * measured);
}

TEST_P(PointLoads, UnderAHeldSideLoadTheyAreItsCounterforceWithoutSlip) {
  LoadDesc load;
  load.force =
      Vec3(0.0, 0.0, 2.0);  // N: well within the finger's friction limit (mu N, about 4.6 N)
  World w(pressed_box::scene(settingsOf(GetParam()), 0.0, load));
  Snapshot snap;
  Vec3 friction = Vec3::Zero();
  int samples = 0;
  run(w, kLoadStart + 0.6, [] {});
  const Vec3 v0 = w.bodyLinearVelocity(1);
  run(w, kLoadStart + 0.8, [&] {
    w.snapshot(snap);
    ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
    const ContactSnapshot& c = snap.fingers[0].contacts[0];
    friction += frictionOf(c, snap.bodies[1].position).force;
    ++samples;
    EXPECT_FALSE(c.sliding);
    EXPECT_FALSE(c.point_load.slipping);
    for (const PointLoad& l : c.loads) EXPECT_FALSE(l.slipping);
  });
  // The finger's mean friction on the box (N), by the box's change of momentum.
  const double measured =
      load.force.z() - kMass * (w.bodyLinearVelocity(1) - v0).z() / (samples * kDt);
  EXPECT_NEAR(-friction.z() / samples, measured, 1e-5 * measured);
  EXPECT_LT(std::abs(w.bodyLinearVelocity(1).z()), 0.01) << "the box is held (m/s)";
}

TEST_P(PointLoads, WhileTheBoxSpinsTheirMomentIsTheFingersTorsion) {
  if (GetParam().model == ContactModel::kGodObject) GTEST_SKIP() << "a point has no torsion";
  LoadDesc load;
  load.torque = Vec3(0.0, 0.05, 0.0);  // N m: above every model's torsion limit here (<= 0.035)
  World w(pressed_box::scene(settingsOf(GetParam()), 0.0, load));
  Snapshot snap;
  double moment = 0.0;
  int samples = 0, sliding = 0;
  run(w, kLoadStart + 0.1, [] {});
  const double omega0 = w.bodyAngularVelocity(1).y();
  run(w, kLoadStart + 0.4, [&] {
    w.snapshot(snap);
    ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
    const ContactSnapshot& c = snap.fingers[0].contacts[0];
    moment += frictionOf(c, snap.bodies[1].position).moment;
    ++samples;
    sliding += c.sliding;
    for (const PointLoad& l : c.loads)
      EXPECT_TRUE(l.slipping || l.normal == 0.0) << "every SGO has a lever: it slips";
  });
  // The finger's mean torsion on the box (N m), by the box's change of angular momentum.
  const double measured =
      load.torque.y() - kInertiaY * (w.bodyAngularVelocity(1).y() - omega0) / (samples * kDt);
  // A soft finger's torsion is a moment of its one point (torsion_moment); a patch's is split
  // over its points' loads.
  EXPECT_NEAR(-moment / samples, measured, 1e-5 * measured);
  EXPECT_EQ(sliding, samples);
}

// Fig. 8's pinch holds the cylinder still: its angular momentum does not change, so the moments
// about its centre of mass of every point load of both fingers (normal and friction) and of
// their rolling rows add up to zero (gravity acts at the centre), with either solver.
TEST(PointLoadsPinch, MakeTheWholeMomentThatHoldsTheCylinder) {
  for (const char* solver : {"points", "aggregate"}) {
    test_support::TestContext ctx("fig8-pinch-oscillation", 8,
                                  {std::string("world.contact_solver=") + solver});
    const int b = ctx.body("cylinder");
    Snapshot snap;
    Vec3 total = Vec3::Zero(), force = Vec3::Zero();
    double size = 0.0;
    int samples = 0;
    ctx.simulate(6.0);
    const Vec3 spin = ctx.world().bodyAngularVelocity(b);
    ctx.simulate(0.5, [&](const World& w) {
      w.snapshot(snap);
      const Vec3 com = snap.bodies[static_cast<std::size_t>(b)].position;
      for (const FingerSnapshot& f : snap.fingers) {
        for (const ContactSnapshot& c : f.contacts) {
          const Vec3& n = c.outward_normal_world;
          Vec3 m = c.rolling_moment + c.torsion_moment +
                   (c.point_world - com).cross(c.point_load.tangential - c.point_load.normal * n);
          for (std::size_t i = 0; i < c.loads.size(); ++i) {
            m += (c.sgos_world[i] - com).cross(c.loads[i].tangential - c.loads[i].normal * n);
          }
          total += m;
          size += m.norm();
          force += c.force;
        }
      }
      ++samples;
    });
    // Held still: its spin changes by less than 1e-5 rad/s in the 0.5 s (the aggregate solver's
    // pinch wobbles at 1.7e-6 rad/s, turning by 5e-6 degrees at most over 5 minutes): an
    // inertial moment of about 1e-9 N m, far below the 1e-6 share of the fingers' moments the
    // balance below allows.
    EXPECT_LT((ctx.world().bodyAngularVelocity(b) - spin).norm(), 1e-5)
        << solver << ": the cylinder is held still";
    EXPECT_NEAR(force.y() / samples, 0.15 * 9.81, 1e-6)
        << solver << ": the fingers carry its weight (N)";
    // Each finger's moment about the centre is about 0.02 to 0.04 N m; together they cancel.
    EXPECT_LT(total.norm() / samples, 1e-6 * size / samples)
        << solver << " " << total.transpose() / samples;
  }
}

const Case kCases[] = {
    {"god_object", ContactModel::kGodObject, PatchFill::kRing, SolverChoice::kPoints},
    {"soft_finger", ContactModel::kSoftFinger, PatchFill::kRing, SolverChoice::kPoints},
    {"ring_points", ContactModel::kGodFinger, PatchFill::kRing, SolverChoice::kPoints},
    {"ring_aggregate", ContactModel::kGodFinger, PatchFill::kRing, SolverChoice::kAggregate},
    {"filled_points", ContactModel::kGodFinger, PatchFill::kFilled, SolverChoice::kPoints},
    {"filled_aggregate", ContactModel::kGodFinger, PatchFill::kFilled, SolverChoice::kAggregate},
};
INSTANTIATE_TEST_SUITE_P(Models, PointLoads, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<Case>& i) {
                           return std::string(i.param.name);
                         });

}  // namespace
}  // namespace gf::sim
