// Sessions: what `godfinger run` writes (trace, summary, contacts, frames) and how scripted
// overlay input reaches the simulation.
#include "app/session.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/scene_file.hpp"
#include "render/image.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Session, SameSceneTwiceGivesByteIdenticalTrace) {
  SessionDesc s = loadSceneFile(resolveScenePath("fig7-side-pick"));
  s.scene.duration = 1.0;
  const fs::path a = fs::temp_directory_path() / "gf_session_a", b = fs::temp_directory_path() / "gf_session_b";
  runSession(s, {a.string(), false, false, false, "", ""});
  runSession(s, {b.string(), false, false, false, "", ""});
  const std::string ta = readFile(a / "trace.csv");
  EXPECT_GT(ta.size(), 1000u);
  EXPECT_EQ(ta, readFile(b / "trace.csv"));
  EXPECT_TRUE(fs::exists(a / "summary.json"));
  EXPECT_EQ(ta.substr(0, ta.find('\n')),
            "t,box.px,box.py,box.pz,box.qx,box.qy,box.qz,box.qw,left.fx,left.fy,left.fz,left.n_sgo,"
            "right.fx,right.fy,right.fz,right.n_sgo");
}

// A 0.5 s offline session gives a frame at every 1/60 s (t = 0 included), close-ups beside
// the contact JSON, and the overlay's scripted clicks change the running simulation.
TEST(Session, WritesEveryFrameAndAppliesScriptedInput) {
  const std::vector<std::string> overrides = {"duration=0.6", "record.contacts=[0.4]", "render.width=320",
      "render.height=180",
      "render.actions=[{t = 0.3, widget = \"left/god_finger\", value = \"off\"}]"};
  SessionDesc s =
      loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/overlay-demo.toml", overrides);
  const fs::path out = fs::temp_directory_path() / "gf_render_session";
  fs::remove_all(out);
  SessionOptions options;
  options.out_dir = out.string();
  options.progress = false;
  options.frames = true;
  runSession(s, options);
  int frames = 0;
  for (const auto& e : fs::directory_iterator(out / "frames")) frames += e.path().extension() == ".png";
  EXPECT_EQ(frames, 37);  // k / 60 s for k = 0..36
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400.json"));
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400-left.png"));
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400-right.png"));
  const render::Image frame = render::readPng((out / "frames" / "000036.png").string());
  EXPECT_EQ(frame.width, 320);
  EXPECT_EQ(frame.height, 180);
  std::ifstream in(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  ASSERT_EQ(summary["overlay_changes"].size(), 1u);
  EXPECT_EQ(summary["overlay_changes"][0]["finger"], "left");
  EXPECT_EQ(summary["overlay_changes"][0]["n_sgo"], 0);
  // The click lands on the frame after the press: (ceil(0.3 * 60) + 2) / 60 s.
  EXPECT_NEAR(summary["overlay_changes"][0]["t"].get<double>(), 20.0 / 60.0, 1e-3);
}

}  // namespace
}  // namespace gf::app
