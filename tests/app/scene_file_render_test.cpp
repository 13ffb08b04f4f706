// Scene files' [render] table: its names, their defaults, and a clear error (file, line, field)
// for each bad value.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "app/scene/scene_file.hpp"
#include "tests/app/scene_text.hpp"

namespace gf::app {
namespace {

// The line of the first field of a [render] table appended to the minimal scene.
int renderLine() {
  return static_cast<int>(std::count(kMinimal.begin(), kMinimal.end(), '\n')) + 2;
}

TEST(SceneFile, AntialiasingIsOneOfThreeNames) {
  EXPECT_EQ(parseSceneText(kMinimal, "scene.toml", "").view.antialiasing, view::Antialiasing::kFxaa);
  const std::string text = kMinimal + "[render]\nantialiasing = \"msaa\"\nmsaa_samples = 8\n";
  const SessionDesc s = parseSceneText(text, "scene.toml", "");
  EXPECT_EQ(s.view.antialiasing, view::Antialiasing::kMsaa);
  EXPECT_EQ(s.view.msaa_samples, 8);
  const InputError e = errorOf(kMinimal + "[render]\nantialiasing = \"smaa\"\n");
  EXPECT_EQ(e.line(), renderLine()) << e.what();
  EXPECT_EQ(e.field(), "render.antialiasing");
  EXPECT_NE(std::string(e.what()).find("expected \"fxaa\", \"msaa\" or \"none\""), std::string::npos) << e.what();
}

// Bodies are striped and proxies are spheres unless the table says otherwise; --set reaches
// both names.
TEST(SceneFile, BodyPatternAndProxyLookHaveDefaultsAndNames) {
  const SessionDesc plain = parseSceneText(kMinimal, "scene.toml", "");
  EXPECT_EQ(plain.view.body_pattern, view::BodyPattern::kStripes);
  EXPECT_EQ(plain.view.proxy, view::ProxyLook::kSphere);
  const SessionDesc s = parseSceneText(kMinimal + "[render]\nbody_pattern = \"none\"\nproxy = \"fingertip\"\n", "scene.toml", "");
  EXPECT_EQ(s.view.body_pattern, view::BodyPattern::kNone);
  EXPECT_EQ(s.view.proxy, view::ProxyLook::kFingertip);
  const std::vector<std::string> overrides = {"render.proxy=fingertip", "render.body_pattern=\"none\""};
  const SessionDesc set = parseSceneText(kMinimal, "scene.toml", "", overrides);
  EXPECT_EQ(set.view.body_pattern, view::BodyPattern::kNone);
  EXPECT_EQ(set.view.proxy, view::ProxyLook::kFingertip);
}

// A value that is not one of the names, or not a string, is named with its file, line and field
// and the names it may take.
TEST(SceneFile, BodyPatternAndProxyLookRefuseOtherValues) {
  struct Case {
    std::string text, field, reason;
  };
  const Case cases[] = {
      {"body_pattern = \"checker\"\n", "render.body_pattern", "unknown value 'checker' (one of stripes, none)"},
      {"body_pattern = true\n", "render.body_pattern", "expected a string"},
      {"proxy = \"hand\"\n", "render.proxy", "unknown value 'hand' (one of sphere, fingertip)"},
      {"proxy = 1\n", "render.proxy", "expected a string"},
  };
  for (const Case& c : cases) {
    const InputError e = errorOf(kMinimal + "[render]\n" + c.text);
    EXPECT_EQ(e.file(), "scene.toml");
    EXPECT_EQ(e.line(), renderLine()) << e.what();
    EXPECT_EQ(e.field(), c.field) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gf::app
