// The scene reader on [[loads]] (forces and torques on bodies) and [[changes]] (finger settings
// from a time on): what it reads, and the errors it names.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "app/scene/scene_file.hpp"
#include "tests/app/scene_text.hpp"

namespace gf::app {
namespace {

std::string withLoad(const std::string& entry) {
  return kMinimal + "[[loads]]\n" + entry;
}

// The error of kMinimal with `entry` as the first element of array of tables `array` names
// "scene.toml:LINE:COLUMN: ARRAY.0.FIELD: " and then `reason`; `entry_line` counts from the
// [[ARRAY]] header (0).
void expectEntryError(const std::string& array, const std::string& entry, int entry_line, int column,
                      const std::string& field, const std::string& reason) {
  const InputError e = errorOf(kMinimal + "[[" + array + "]]\n" + entry);
  const int line =
      static_cast<int>(std::count(kMinimal.begin(), kMinimal.end(), '\n')) + 1 + entry_line;
  const std::string where = "scene.toml:" + std::to_string(line) + ":" + std::to_string(column) +
                            ": " + array + ".0." + field + ": ";
  EXPECT_EQ(std::string(e.what()).rfind(where, 0), 0u)
      << e.what() << "\nexpected it to start with " << where;
  EXPECT_EQ(e.field(), array + ".0." + field);
  EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
}

void expectLoadError(const std::string& entry, int entry_line, int column, const std::string& field,
                     const std::string& reason) {
  expectEntryError("loads", entry, entry_line, column, field, reason);
}

const std::string kBallForce = "body = \"ball\"\nforce = [1, 0, 0]\n";  // entry lines 1 and 2

TEST(SceneFileLoads, ReadsBodyForceTorqueAndTimes) {
  const SessionDesc s = parseSceneText(
      withLoad(
          "body = \"ball\"\nforce = [0, 0, 0.5]\ntorque = [0, 0.01, 0]\nstart = 0.05\nramp = 0.1\n"
          "[[loads]]\nbody = \"ball\"\ntorque = [0, 0, 1e-3]\nstop = 0.1\n"),
      "scene.toml", "");
  ASSERT_EQ(s.scene.loads.size(), 2u);
  const sim::LoadDesc& a = s.scene.loads[0];
  EXPECT_EQ(a.body, 1);
  EXPECT_EQ(a.body_name, "ball");
  EXPECT_EQ(a.force, sim::Vec3(0, 0, 0.5));
  EXPECT_EQ(a.torque, sim::Vec3(0, 0.01, 0));
  EXPECT_EQ(a.start, 0.05);
  EXPECT_EQ(a.ramp, 0.1);
  EXPECT_EQ(a.stop, HUGE_VAL) << "no stop";
  const sim::LoadDesc& b = s.scene.loads[1];
  EXPECT_EQ(b.force, sim::Vec3::Zero()) << "a torque alone";
  EXPECT_EQ(b.start, 0.0);
  EXPECT_EQ(b.ramp, 0.0) << "a step";
  EXPECT_EQ(b.stop, 0.1);
  sim::World world(s.scene);  // the World accepts what the reader accepted
}

TEST(SceneFileLoads, UnknownBodyIsNamed) {
  expectLoadError("body = \"cup\"\nforce = [1, 0, 0]\n", 1, 8, "body",
                  "no body called 'cup' (one of ground, ball)");
}

TEST(SceneFileLoads, StaticBodyIsNamed) {
  expectLoadError("body = \"ground\"\nforce = [1, 0, 0]\n", 1, 8, "body",
                  "'ground' is static (mass 0): a load needs a dynamic body");
}

TEST(SceneFileLoads, NonFiniteValuesAreNamed) {
  expectLoadError("body = \"ball\"\nforce = [nan, 0, 0]\n", 2, 10, "force", "must be finite");
  expectLoadError("body = \"ball\"\ntorque = [0, -inf, 0]\n", 2, 14, "torque", "must be finite");
  expectLoadError(kBallForce + "start = inf\n", 3, 9, "start", "must be finite");
  expectLoadError(kBallForce + "ramp = nan\n", 3, 8, "ramp", "must be finite");
  expectLoadError(kBallForce + "stop = inf\n", 3, 8, "stop", "must be finite");
}

TEST(SceneFileLoads, NegativeRampIsNamed) {
  expectLoadError(kBallForce + "ramp = -0.1\n", 3, 8, "ramp", "must be in [0, 1e+06], got -0.1");
}

TEST(SceneFileLoads, NegativeStartIsNamed) {
  expectLoadError(kBallForce + "start = -1\n", 3, 9, "start", "must be in [0, 1e+06], got -1");
}

TEST(SceneFileLoads, StopNotAfterStartIsNamed) {
  expectLoadError(kBallForce + "start = 0.1\nstop = 0.1\n", 4, 8, "stop",
                  "must be after start (0.1 s), got 0.1");
  expectLoadError(kBallForce + "stop = 0\n", 3, 8, "stop", "must be after start (0 s), got 0");
}

TEST(SceneFileLoads, UnknownKeyIsNamed) {
  expectLoadError(kBallForce + "wind = 2\n", 3, 8, "wind", "unknown field");
}

TEST(SceneFileLoads, WrongTypesAreNamed) {
  expectLoadError("body = \"ball\"\nforce = [1, 0]\n", 2, 9, "force",
                  "expected an array of 3 numbers [x, y, z]");
  expectLoadError("body = \"ball\"\nforce = \"up\"\n", 2, 9, "force",
                  "expected an array of 3 numbers [x, y, z]");
  expectLoadError("body = \"ball\"\ntorque = [0, \"a\", 0]\n", 2, 14, "torque",
                  "expected a number, got a string");
  expectLoadError("body = 1\nforce = [1, 0, 0]\n", 1, 8, "body",
                  "expected the name of a dynamic body (a string), got an integer");
  expectLoadError(kBallForce + "start = \"now\"\n", 3, 9, "start",
                  "expected a number, got a string");
}

// [[changes]]: each entry is the finger's whole settings from its time on, over the ones before.
TEST(SceneFileChanges, EachChangeHoldsTheFingersSettingsFromItsTimeOn) {
  const SessionDesc s = parseSceneText(
      kMinimal + "[[changes]]\nt = 0.1\nfinger = \"left\"\nn_sgo = 0\n"
                 "[[changes]]\nt = 0.15\nfinger = \"left\"\nr_max = 0.005\ntau_a = 45\n",
      "scene.toml", "", std::vector<std::string>{"changes.1.t=0.12"});
  ASSERT_EQ(s.scene.changes.size(), 2u);
  const sim::PatchSettings& before = s.scene.fingers[0].patch;
  const sim::PatchChange& a = s.scene.changes[0];
  EXPECT_EQ(a.time, 0.1);
  EXPECT_EQ(a.finger, 0);
  EXPECT_EQ(a.patch.n_sgo, 0);
  EXPECT_EQ(a.patch.r_max, before.r_max) << "what the change does not name stays";
  const sim::PatchChange& b = s.scene.changes[1];
  EXPECT_EQ(b.time, 0.12) << "--set reaches a change by its index";
  EXPECT_EQ(b.patch.n_sgo, 0) << "carried over from the change before";
  EXPECT_EQ(b.patch.r_max, 0.005);
  EXPECT_NEAR(b.patch.tau_a, 45.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_EQ(s.scene.fingers[0].patch.n_sgo, 8) << "the finger starts with its own settings";
  sim::World world(s.scene);  // the World accepts what the reader accepted
}

TEST(SceneFileChanges, BadEntriesAreNamed) {
  expectEntryError("changes", "t = 0.1\nfinger = \"thumb\"\nn_sgo = 0\n", 2, 10, "finger",
                   "no finger called 'thumb' (one of left)");
  expectEntryError("changes", "t = 0.1\nn_sgo = 0\n", 0, 1, "finger", "missing (the name of a finger)");
  expectEntryError("changes", "finger = \"left\"\nn_sgo = 0\n", 0, 1, "t", "missing");
  expectEntryError("changes", "t = -1\nfinger = \"left\"\nn_sgo = 0\n", 1, 5, "t", "-1");
  expectEntryError("changes", "t = 0.1\nfinger = \"left\"\n", 2, 10, "finger",
                   "the change names no setting: give one or more of n_sgo, r_max");
  expectEntryError("changes", "t = 0.1\nfinger = \"left\"\nn_sgo = 2\n", 3, 9, "n_sgo",
                   "must be 0 (god-object) or 3..64");
  expectEntryError("changes", "t = 0.1\nfinger = \"left\"\nproxy_mass = 1\n", 3, 14, "proxy_mass",
                   "cannot change during a run; a change may give n_sgo, r_max");
  expectEntryError("changes", "t = 0.1\nfinger = \"left\"\nn_sgo = 0\nspeed = 1\n", 4, 9, "speed", "unknown field");
  expectEntryError("changes", "t = 0.1\nfinger = \"left\"\nn_sgoo = 0\n", 3, 10, "n_sgoo", "unknown field");
  const InputError e = errorOf(kMinimal + "[[changes]]\nt = 0.1\nfinger = \"left\"\nn_sgo = 0\n"
                                          "[[changes]]\nt = 0.05\nfinger = \"left\"\nn_sgo = 8\n");
  EXPECT_EQ(e.field(), "changes.1.t");
  EXPECT_NE(std::string(e.what()).find("changes must be in time order: 0.05 s comes after 0.1 s"),
            std::string::npos) << e.what();
}

TEST(SceneFileLoads, ForceOrTorqueIsRequired) {
  expectLoadError("body = \"ball\"\nstart = 0.1\n", 0, 1, "force",
                  "give force = [x, y, z] (N), torque");
}

TEST(SceneFileLoads, SetOverridesALoadByIndex) {
  const std::string text = withLoad("body = \"ball\"\ntorque = [0, 0.01, 0]\n");
  const std::vector<std::string> o = {"loads.0.torque=[0,0.05,0]", "loads.0.start=0.1",
                                      "loads.0.ramp=0.02", "loads.0.stop=0.15",
                                      "loads.0.force=[0, 0, 2]"};
  const SessionDesc s = parseSceneText(text, "scene.toml", "", o);
  ASSERT_EQ(s.scene.loads.size(), 1u);
  EXPECT_EQ(s.scene.loads[0].torque, sim::Vec3(0, 0.05, 0));
  EXPECT_EQ(s.scene.loads[0].force, sim::Vec3(0, 0, 2));
  EXPECT_EQ(s.scene.loads[0].start, 0.1);
  EXPECT_EQ(s.scene.loads[0].ramp, 0.02);
  EXPECT_EQ(s.scene.loads[0].stop, 0.15);
  // A scene without loads gets one from a whole array.
  const std::vector<std::string> whole = {"loads=[{ body = \"ball\", torque = [0, 0.05, 0] }]"};
  const SessionDesc added = parseSceneText(kMinimal, "scene.toml", "", whole);
  ASSERT_EQ(added.scene.loads.size(), 1u);
  EXPECT_EQ(added.scene.loads[0].torque, sim::Vec3(0, 0.05, 0));
}

TEST(SceneFileLoads, BadSetOfALoadIsNamed) {
  const std::string text = withLoad("body = \"ball\"\ntorque = [0, 0.01, 0]\n");
  const InputError a = errorOf(text, {"loads.1.torque=[0,0.05,0]"});
  EXPECT_EQ(a.field(), "loads.1");
  EXPECT_NE(std::string(a.what()).find("no element 1 (the array has 1)"), std::string::npos)
      << a.what();
  const InputError b = errorOf(text, {"loads.first.torque=[0,0.05,0]"});
  EXPECT_EQ(b.field(), "loads.first");
  EXPECT_NE(std::string(b.what()).find("expected an element index"), std::string::npos) << b.what();
  const InputError c = errorOf(text, {"loads.0.torque=[0,0.05]"});
  EXPECT_EQ(c.file(), "--set loads.0.torque=[0,0.05]");
  EXPECT_EQ(c.field(), "loads.0.torque");
  EXPECT_NE(std::string(c.what()).find("expected an array of 3 numbers"), std::string::npos)
      << c.what();
  const InputError d = errorOf(text, {"loads.0.ramp=-1"});
  EXPECT_EQ(d.field(), "loads.0.ramp");
  EXPECT_NE(std::string(d.what()).find("must be in [0, 1e+06], got -1"), std::string::npos)
      << d.what();
}

}  // namespace
}  // namespace gf::app
