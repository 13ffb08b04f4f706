// Targets ([targets.NAME]): a body's ghost at a pose and a zone, read from scene files and
// --set, drawn in frames; an experiment's task goal drawn as its trials' target.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/compare/screenshots.hpp"
#include "app/experiment/experiment.hpp"
#include "app/experiment/outcome.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "render/frames/image.hpp"
#include "render/render_thread.hpp"
#include "tests/app/scene_text.hpp"

namespace gf::app {
namespace {

// [targets.NAME]: a body's ghost at a pose (where the body starts unless given, the pose as a
// body's: [x, y, z, w] or rotation in degrees) and a zone; every bad field named.
TEST(SceneFile, TargetsAreGhostsAndZonesWithBadFieldsNamed) {
  const SessionDesc s = parseSceneText(kMinimal + "[targets.turned]\nbody = \"ball\"\nrotation = [0, 90, 0]\n"
                                       "[targets.zone]\nzone = { min = [0.1, 0, -0.02], max = [0.14, 0.05, 0.02] }\n",
                                       "scene.toml", "");
  ASSERT_EQ(s.targets.size(), 2u);
  EXPECT_EQ(s.targets[0].name, "turned");
  EXPECT_EQ(s.targets[0].body, 1);
  EXPECT_FALSE(s.targets[0].has_zone);
  EXPECT_NEAR((s.targets[0].position - sim::Vec3(0, 0.03, 0)).norm(), 0.0, 1e-15);  // where the ball starts
  EXPECT_NEAR(s.targets[0].orientation.angularDistance(sim::Quat(Eigen::AngleAxisd(M_PI / 2, sim::Vec3::UnitY()))), 0.0, 1e-12);
  EXPECT_EQ(s.targets[1].body, -1);
  EXPECT_TRUE(s.targets[1].has_zone);
  EXPECT_EQ(s.targets[1].zone_min, sim::Vec3(0.1, 0, -0.02));
  EXPECT_EQ(s.targets[1].zone_max, sim::Vec3(0.14, 0.05, 0.02));
  // The same through --set, as an experiment draws its goal.
  const std::vector<std::string> overrides = {"targets.goal.body=\"ball\"", "targets.goal.orientation=[0, 0, 1, 1]"};
  const SessionDesc set = parseSceneText(kMinimal, "scene.toml", "", overrides);
  ASSERT_EQ(set.targets.size(), 1u);
  EXPECT_NEAR(set.targets[0].orientation.angularDistance(sim::Quat(Eigen::AngleAxisd(M_PI / 2, sim::Vec3::UnitZ()))), 0.0, 1e-12);

  struct Case {
    std::string text, field, reason;
  };
  const Case cases[] = {
      {"[targets.t]\nbody = \"cube\"\n", "targets.t.body", "no body 'cube'"},
      {"[targets.t]\nbody = \"ground\"\n", "targets.t.body", "is a plane"},
      {"[targets.t]\nposition = [0, 0, 0]\nzone = { min = [0, 0, 0], max = [1, 1, 1] }\n", "targets.t.position", "give the body"},
      {"[targets.t]\n", "targets.t.body", "missing"},
      {"[targets.t]\nzone = { min = [0, 0, 0], max = [1, 0, 1] }\n", "targets.t.zone.max", "every coordinate must exceed"},
      {"[targets.t]\nzone = { min = [0, 0, 0] }\n", "targets.t.zone.max", "missing"},
      {"[targets.t]\nbody = \"ball\"\norientation = [0, 0, 0, 0]\n", "targets.t.orientation", "zero length"},
      {"[targets.t]\nbody = \"ball\"\ncolour = [1, 0, 0]\n", "targets.t.colour", "unknown field"},
      {"[targets.\"a b\"]\nbody = \"ball\"\n", "targets.a b", "a name may hold only"},
  };
  for (const Case& c : cases) {
    const InputError e = errorOf(kMinimal + c.text);
    EXPECT_EQ(e.field(), c.field) << c.text;
    EXPECT_NE(e.reason().find(c.reason), std::string::npos) << c.text << ": " << e.reason();
    EXPECT_GT(e.line(), 0) << c.text;
  }
}

// Each task's goal is drawn in its trials' frames as the scene's target "goal": a zone's box
// (pinch-carry), the goal body's ghost turned to the goal orientation where it lies
// (turn-to-target), or both, the ghost in the zone's centre (stack). The frame at t = 0 with the
// target differs from the one without it, and what differs is green (the target's colour, over
// grey bodies, the yellow base and the light backdrop).
TEST(ExperimentTasks, EachGoalIsDrawnAsTheScenesTarget) {
  const std::string tasks = bundledExperimentDir() + "/tasks/";
  for (const std::string name : {"pinch-carry", "turn-to-target", "stack"}) {
    const TaskDesc task = loadTaskFile(tasks + name + ".toml");
    const std::vector<std::string> overrides = goalTargetOverrides(task.goal);
    const SessionDesc plain = loadSceneFile(task.scene), drawn = loadSceneFile(task.scene, overrides);
    ASSERT_EQ(drawn.targets.size(), 1u) << name;
    const view::Target& target = drawn.targets[0];
    EXPECT_EQ(target.name, "goal");
    EXPECT_EQ(target.has_zone, task.goal.has_zone) << name;
    if (task.goal.has_zone) {
      EXPECT_NEAR((target.zone_min - task.goal.zone_min).norm(), 0.0, 1e-15);
      EXPECT_NEAR((target.zone_max - task.goal.zone_max).norm(), 0.0, 1e-15);
    }
    if (!task.goal.orientation) {
      EXPECT_EQ(target.body, -1);
    } else {
      ASSERT_GE(target.body, 0);
      EXPECT_EQ(drawn.scene.bodies[static_cast<std::size_t>(target.body)].name, task.goal.body);
      EXPECT_NEAR(target.orientation.angularDistance(*task.goal.orientation), 0.0, 1e-12) << name;
      const sim::Vec3 at = task.goal.has_zone ? sim::Vec3(0.5 * (task.goal.zone_min + task.goal.zone_max))
                                              : drawn.scene.bodies[static_cast<std::size_t>(target.body)].position;
      EXPECT_NEAR((target.position - at).norm(), 0.0, 1e-15) << name;
    }
    render::FrameOutputSettings settings = frameSettings(drawn, {});
    settings.width = 480;
    settings.height = 270;
    render::FrameOutputSettings without = settings;
    without.scene.targets = nullptr;
    const sim::Snapshot snapshot = snapshotAt(plain, 0.0);
    const render::Image a = render::renderStill(drawn.scene, snapshot, without), b = render::renderStill(drawn.scene, snapshot, settings);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    int changed = 0, green = 0;
    for (std::size_t i = 0; i + 2 < a.rgb.size(); i += 3) {
      const int dr = int(b.rgb[i]) - int(a.rgb[i]), dg = int(b.rgb[i + 1]) - int(a.rgb[i + 1]), db = int(b.rgb[i + 2]) - int(a.rgb[i + 2]);
      if (std::abs(dr) + std::abs(dg) + std::abs(db) <= 6) continue;
      ++changed;
      green += 2 * dg > dr + db;  // towards green (g - (r + b) / 2 grew), whatever it was over, the yellow base too
    }
    const int pixels = settings.width * settings.height;
    EXPECT_GT(changed, pixels / 500) << name << ": the target is seen";
    EXPECT_GT(green, changed * 9 / 10) << name << ": " << green << " of " << changed << " changed pixels turned greener";
    if (const char* dir = std::getenv("GF_TARGET_FRAMES")) render::writePng(std::string(dir) + "/" + name + ".png", b);
  }
}

}  // namespace
}  // namespace gf::app
