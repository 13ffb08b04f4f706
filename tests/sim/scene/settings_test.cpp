// The settings tables: one validator per setting, units, JSON names and the rules between
// fields that the World, the scene reader, the command line, `live` and the overlay all use.
#include "sim/scene/settings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <set>
#include <vector>

namespace gf::sim {
namespace {

const Setting<FingerDesc>& finger(std::string_view name) { return *findSetting(fingerSettings(), name); }

TEST(Settings, NamesAreUniqueAndDefaultsAreLegal) {
  std::set<std::string_view> names;
  for (const auto& s : fingerSettings()) EXPECT_TRUE(names.insert(s.name).second) << s.name;
  names.clear();
  for (const auto& s : bodySettings()) EXPECT_TRUE(names.insert(s.name).second) << s.name;
  names.clear();
  for (const auto& s : sceneSettings()) EXPECT_TRUE(names.insert(s.name).second) << s.name;
  names.clear();
  for (const auto& s : loadSettings()) EXPECT_TRUE(names.insert(s.name).second) << s.name;
  EXPECT_FALSE(validateFinger(FingerDesc{}));
  EXPECT_FALSE(validateBody(BodyDesc{}));
  EXPECT_FALSE(validateScene(SceneDesc{}));
  EXPECT_FALSE(validatePatch(PatchSettings{}));
}

TEST(Settings, NSgoIsZeroOrTheLegalPatchCount) {
  const Setting<FingerDesc>& n = finger("n_sgo");
  EXPECT_EQ(n.kind, SettingKind::kInteger);
  EXPECT_FALSE(checkGiven(n, 0.0)) << "0: a god-object";
  EXPECT_FALSE(checkGiven(n, kMinSgo));
  EXPECT_FALSE(checkGiven(n, kMaxSgo));
  EXPECT_EQ(checkGiven(n, 2.0).value_or(""), "must be 0 (god-object) or 3..64");
  EXPECT_EQ(checkGiven(n, 65.0).value_or(""), "must be in 0..64, got 65");
  EXPECT_EQ(checkGiven(n, 8.5).value_or(""), "expected an integer, got 8.5");
  EXPECT_EQ(checkGiven(n, std::nan("")).value_or(""), "must be finite");
}

TEST(Settings, AnglesAreGivenInDegreesAndStoredInRadians) {
  const Setting<FingerDesc>& tau = finger("tau_a");
  EXPECT_EQ(tau.unit, "deg");
  FingerDesc f;
  setGiven(tau, f, 90.0);
  EXPECT_DOUBLE_EQ(f.patch.tau_a, std::numbers::pi / 2);
  EXPECT_NEAR(givenValue(tau, f), 90.0, 1e-12);
  EXPECT_FALSE(checkGiven(tau, 90.0));
  // Beyond 90 degrees a face turns away from the press: no SGO may stand there anyway.
  EXPECT_EQ(checkGiven(tau, 91.0).value_or(""), "must be in [0, 90], got 91");
  f.patch.tau_a = 1.6;  // rad, beyond 90 degrees
  ASSERT_TRUE(validateFinger(f));
  EXPECT_EQ(validateFinger(f)->field, "tau_a");
}

TEST(Settings, ExcludedMinimumsAndJsonNamesCarryTheUnit) {
  EXPECT_EQ(checkGiven(finger("coupling_stiffness"), 0.0).value_or(""), "must be in (0, 1e+06], got 0");
  EXPECT_FALSE(checkGiven(finger("coupling_stiffness"), 800.0));
  EXPECT_EQ(jsonKey(finger("r_max")), "r_max_m");
  EXPECT_EQ(jsonKey(finger("tau_a")), "tau_a_deg");
  EXPECT_EQ(jsonKey(finger("n_sgo")), "n_sgo");
  EXPECT_EQ(jsonKey(finger("max_force")), "max_force_n");
  EXPECT_EQ(jsonKey(finger("contact_damping")), "contact_damping_ns_per_m");
  EXPECT_EQ(jsonKey(*findSetting(sceneSettings(), "world.gravity")), "world_gravity_m_per_s2");
}

TEST(Settings, LiveSettingsAreTheGodFingerOnes) {
  for (const Setting<FingerDesc>& s : fingerSettings()) {
    FingerDesc f;
    const double extreme = s.kind == SettingKind::kInteger ? kMaxSgo : s.max;
    if (s.kind == SettingKind::kVector) {
      s.set_vector(f, Vec3::Constant(s.max));  // a vector setting: every component at its largest
    } else {
      setGiven(s, f, extreme != givenValue(s, FingerDesc{}) ? extreme : s.min);
    }
    const bool patch_changed = f.patch.n_sgo != PatchSettings{}.n_sgo || f.patch.r_max != PatchSettings{}.r_max ||
                               f.patch.d0 != PatchSettings{}.d0 || f.patch.alpha != PatchSettings{}.alpha ||
                               f.patch.stretch_length != PatchSettings{}.stretch_length ||
                               f.patch.max_stretch != PatchSettings{}.max_stretch ||
                               f.patch.tau_a != PatchSettings{}.tau_a || f.patch.friction != PatchSettings{}.friction;
    EXPECT_EQ(s.live, patch_changed) << s.name << ": live exactly when it is a god-finger (PatchSettings) field";
  }
}

TEST(Settings, BodyRulesBetweenFields) {
  BodyDesc plane;
  plane.shape = ShapeKind::kPlane;
  plane.mass = 0.0;
  EXPECT_FALSE(validateBody(plane)) << "a static plane";
  plane.mass = 1.0;
  ASSERT_TRUE(validateBody(plane));
  EXPECT_EQ(validateBody(plane)->reason, "a plane must be static (mass 0)");
  BodyDesc sphere;
  sphere.shape = ShapeKind::kSphere;
  sphere.walk_resolution = shapeInfo(ShapeKind::kSphere).max_resolution + 1;
  ASSERT_TRUE(validateBody(sphere));
  EXPECT_EQ(validateBody(sphere)->field, "walk_resolution");
  BodyDesc box;
  box.mass = -1.0;
  ASSERT_TRUE(validateBody(box));
  EXPECT_EQ(validateBody(box)->field, "mass");
  box.mass = 0.0;
  EXPECT_FALSE(validateBody(box)) << "mass 0: static";
  box.half_extents.y() = 0.0;
  ASSERT_TRUE(validateBody(box));
  EXPECT_EQ(validateBody(box)->field, "half_extents");
}

TEST(Settings, TracksNeedIncreasingFiniteKeyframes) {
  DeviceTrack t;
  t.keyframes = {{0.0, Vec3::Zero()}, {0.5, Vec3::Ones()}, {0.5, Vec3::Zero()}};
  std::optional<FieldError> e = validateTrack(t);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field, "keyframes.t");
  EXPECT_EQ(e->index, 2);
  t.keyframes[2].time = 1.0;
  t.keyframes[1].position.x() = std::nan("");
  e = validateTrack(t);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field, "keyframes.p");
  EXPECT_EQ(e->index, 1);
}

TEST(Settings, DescriptionErrorsNameSubjectFieldAndReason) {
  SceneDesc scene;
  FingerDesc f;
  f.name = "left";
  f.coupling.max_force = 0.0;
  scene.fingers.push_back(f);
  try {
    requireValid(scene);
    FAIL() << "accepted max_force 0";
  } catch (const DescriptionError& e) {
    EXPECT_EQ(e.subject(), "finger 'left'");
    EXPECT_EQ(e.error().field, "max_force");
    EXPECT_STREQ(e.what(), "finger 'left': max_force: must be in (0, 10000], got 0");
  }
}

// Each kind of bad load: its body (missing, static), a value that is not finite, negative
// start or ramp, a stop not after the start. No stop (+inf) is legal.
TEST(Settings, LoadRules) {
  BodyDesc ground, ball;
  ground.name = "ground";
  ground.mass = 0.0;
  ball.name = "ball";
  const std::vector<BodyDesc> bodies = {ground, ball};
  LoadDesc good;
  good.body = 1;
  good.force = Vec3(0, 0, 1);
  EXPECT_FALSE(validateLoad(good, bodies)) << "no stop: +inf";
  struct Case {
    void (*change)(LoadDesc&);
    std::string field, reason;
  };
  const Case cases[] = {
      {[](LoadDesc& l) { l.body = 2; }, "body", "no body of index 2 (the scene has 2)"},
      {[](LoadDesc& l) { l.body = -1; }, "body", "no body of index -1 (the scene has 2)"},
      {[](LoadDesc& l) { l.body = 0; }, "body",
       "'ground' is static (mass 0): a load needs a dynamic body"},
      {[](LoadDesc& l) { l.force.y() = std::nan(""); }, "force", "must be finite"},
      {[](LoadDesc& l) { l.torque.z() = HUGE_VAL; }, "torque", "must be finite"},
      {[](LoadDesc& l) { l.start = HUGE_VAL; }, "start", "must be finite"},
      {[](LoadDesc& l) { l.ramp = std::nan(""); }, "ramp", "must be finite"},
      {[](LoadDesc& l) { l.stop = std::nan(""); }, "stop", "must be finite"},
      {[](LoadDesc& l) { l.stop = -HUGE_VAL; }, "stop", "must be finite"},
      {[](LoadDesc& l) { l.start = -0.1; }, "start", "must be in [0, 1e+06], got -0.1"},
      {[](LoadDesc& l) { l.ramp = -1.0; }, "ramp", "must be in [0, 1e+06], got -1"},
      {[](LoadDesc& l) {
         l.start = 0.5;
         l.stop = 0.5;
       },
       "stop", "must be after start (0.5 s), got 0.5"},
      {[](LoadDesc& l) {
         l.start = 0.5;
         l.stop = 0.2;
       },
       "stop", "must be after start (0.5 s), got 0.2"},
  };
  for (const Case& c : cases) {
    LoadDesc bad = good;
    c.change(bad);
    const std::optional<FieldError> e = validateLoad(bad, bodies);
    ASSERT_TRUE(e) << c.reason;
    EXPECT_EQ(e->field, c.field);
    EXPECT_EQ(e->reason, c.reason);
  }
  EXPECT_EQ(jsonKey(*findSetting(loadSettings(), "torque")), "torque_nm");
  EXPECT_EQ(jsonKey(*findSetting(loadSettings(), "force")), "force_n");
}

TEST(Settings, ShapesAndEffectsComeFromTables) {
  ASSERT_EQ(shapeInfos().size(), 12u);
  for (std::size_t i = 0; i < shapeInfos().size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(shapeInfos()[i].kind), i) << "rows in ShapeKind order";
  }
  EXPECT_TRUE(isMeshShape(ShapeKind::kConcaveMesh));
  EXPECT_FALSE(isMeshShape(ShapeKind::kCapsule));
  EXPECT_FALSE(isMeshShape(ShapeKind::kSoftMesh)) << "a soft mesh is tetrahedra, no triangle mesh";
  EXPECT_TRUE(isSoftShape(ShapeKind::kSoftBox) && isSoftShape(ShapeKind::kSoftMesh) && !isSoftShape(ShapeKind::kConcaveMesh));
  EffectSet e;
  for (const EffectSwitch& s : effectSwitches()) e.*s.on = false;
  EXPECT_FALSE(e.gravity || e.friction || e.god_finger || e.tangential_stretch || e.angular_threshold ||
               e.friction_cone || e.force_feedback)
      << "every physics effect has a row";
}

// A refusal never reads "got X" with X the bound it violates: values take the digits they need
// to read back as themselves (d0 = 1.000001 is "got 1.000001", not "got 1"), while round values
// print as before; a computed bound and its violator print with digits enough to differ.
TEST(Settings, RefusedValuesNeverPrintAsTheBoundTheyViolate) {
  const Setting<FingerDesc>& d0 = *findSetting(fingerSettings(), "d0");
  const std::optional<std::string> why = checkGiven(d0, 1.000001);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("got 1.000001"), std::string::npos) << *why;
  EXPECT_NE(why->find("1e-06, 1]"), std::string::npos) << *why;
  EXPECT_EQ(numberText(1.000001), "1.000001");
  EXPECT_EQ(numberText(0.1), "0.1");
  EXPECT_EQ(numberText(1e6), "1e+06");
  EXPECT_EQ(numberText(1.0 + 1e-15), "1.000000000000001");
  for (const double x : {1.000001, 0.1 + 0.2, 1e-6 * (1 - 1e-12), 123456.7890123}) {
    EXPECT_EQ(std::strtod(numberText(x).c_str(), nullptr), x) << numberText(x);
  }
  const auto [bound, got] = distinctTexts(0.0010004, 0.001);
  EXPECT_EQ(bound, "0.0010004");
  EXPECT_EQ(got, "0.001");
  EXPECT_EQ(distinctTexts(2.5, 3.0).first, "2.5");
  EXPECT_EQ(distinctTexts(1e5, 100001).first, "1e+05") << "a round bound stays short";
  EXPECT_EQ(distinctTexts(0.00100049, 0.0010003).first, "0.0010005") << "0.001 would lie below the value it exceeds";
  FingerDesc f;
  f.proxy.radius = f.coupling.max_force / f.proxy.contact_stiffness * (1 - 1e-9);
  const std::optional<FieldError> e = validateFinger(f);
  ASSERT_TRUE(e.has_value());
  const std::size_t eq = e->reason.find("= "), at = e->reason.find("got ");
  EXPECT_NE(e->reason.substr(eq + 2, e->reason.find(' ', eq + 2) - eq - 2), e->reason.substr(at + 4)) << e->reason;
}

}  // namespace
}  // namespace gf::sim
