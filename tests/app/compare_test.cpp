// `godfinger compare`: the layout of its frames, the checks of its options, and a short
// comparison of the Fig. 5 push run end to end as a user runs it: one run per model, the
// composited frames and video, compare.json, and the physics the comparison exists to show (under
// a god-object the pushed ball rolls; under a god-finger it slides).
#include "app/compare/compare.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <tuple>

#include "app/commands/plot.hpp"
#include "app/compare/chart_quantity.hpp"
#include "app/scene/data_folder.hpp"
#include "app/runs/run_reader.hpp"
#include "app/scene/scene_file.hpp"
#include "render/frames/image.hpp"
#include "sim/scene/settings.hpp"
#include "tests/app/run_helpers.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using gf::app::test::exitStatus;
using gf::app::test::freshFolder;
using gf::app::test::kBin;
using gf::app::test::readFile;

TEST(Compare, PanelsKeepTheFrameAspectAndLeaveTheChartAThird) {
  for (int n = 1; n <= 4; ++n) {
    const render::CompareLayout l = render::compareLayout(1280, 720, n);
    ASSERT_EQ(l.panels.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(l.width, 1280) << n;
    EXPECT_NEAR(double(l.panel_height) / l.panel_width, 720.0 / 1280.0, 0.01) << n;
    EXPECT_GE(l.chart_height, 0.3 * l.height - 1) << n;
    EXPECT_EQ(l.chart_top + l.chart_height, l.height) << n;
    EXPECT_EQ(l.height % 2, 0) << n;
    for (int i = 0; i < n; ++i) {  // inside the frame, above the chart, apart
      EXPECT_GE(l.panels[i].x(), 0);
      EXPECT_LE(l.panels[i].x() + l.panel_width, l.width);
      EXPECT_LE(l.panels[i].y() + l.panel_height, l.chart_top);
      for (int j = 0; j < i; ++j) {
        const bool apart = l.panels[i].x() >= l.panels[j].x() + l.panel_width ||
                           l.panels[j].x() >= l.panels[i].x() + l.panel_width ||
                           l.panels[i].y() >= l.panels[j].y() + l.panel_height;
        EXPECT_TRUE(apart) << n << " models: panels " << j << " and " << i;
      }
    }
  }
  // Two models at 1280 x 720: two 640 x 360 panels over a 360-pixel chart.
  const render::CompareLayout two = render::compareLayout(1280, 720, 2);
  EXPECT_EQ(two.panel_width, 640);
  EXPECT_EQ(two.panel_height, 360);
  EXPECT_EQ(two.panels[0], Eigen::Vector2i(0, 0));
  EXPECT_EQ(two.height, 720);
}

// Three or four models: the same 640 x 360 panels as two, in a 2 x 2 grid (beside a third, the key
// to the marks in the empty cell) over a 360-pixel chart, a third of a 1280 x 1080 frame; a 640 x 360
// scene gives 320 x 180 panels over a chart of at least 220 pixels.
TEST(Compare, ThreeOrFourModelsGoInATwoByTwoGridOverAThirdOfTheFrame) {
  const render::CompareLayout three = render::compareLayout(1280, 720, 3);
  EXPECT_EQ(three.panel_width, 640);
  EXPECT_EQ(three.panel_height, 360);
  EXPECT_EQ(three.height, 1080);
  EXPECT_EQ(three.chart_top, 720);
  EXPECT_EQ(three.chart_height, 360);
  EXPECT_EQ(three.panels[0], Eigen::Vector2i(0, 0));
  EXPECT_EQ(three.panels[1], Eigen::Vector2i(640, 0));
  EXPECT_EQ(three.panels[2], Eigen::Vector2i(0, 360));
  EXPECT_EQ(three.key, Eigen::Vector2i(640, 360));
  const render::CompareLayout four = render::compareLayout(1280, 720, 4);
  EXPECT_EQ(four.panels[3], Eigen::Vector2i(640, 360));
  EXPECT_LT(four.key.x(), 0) << "no empty cell: no key";
  const render::CompareLayout small = render::compareLayout(640, 360, 4);
  EXPECT_EQ(small.panel_width, 320);
  EXPECT_EQ(small.panel_height, 180);
  EXPECT_EQ(small.chart_top, 360);
  EXPECT_EQ(small.height, 580);
}

// The tilt is the angle of the body's y axis (a cylinder's) from up: a cylinder swung a whole
// turn about the pinch axis is upright again (tilt 0; the angle turned keeps 360), one spun about
// its own axis does not tilt, one lying on its side reads 90.
TEST(Compare, TiltIsTheAxisFromUprightNotTheAngleTurned) {
  SessionDesc session = loadSceneFile(resolveScenePath("fig8-pinch-oscillation"), {});
  const Quantity tilt = chartQuantity(session, "", "");
  EXPECT_EQ(tilt.kind, Quantity::kTilt) << "a cylinder's default";
  EXPECT_EQ(quantityName(tilt), "tilt");
  const Quantity ball = chartQuantity(loadSceneFile(resolveScenePath("fig5-push-ball"), {}), "", "");
  EXPECT_EQ(ball.kind, Quantity::kRotation) << "a sphere's default";
  const sim::Quat start = sim::Quat::Identity();
  QuantityTrack track(tilt, start);
  Quantity turned_q = tilt;
  turned_q.kind = Quantity::kRotation;
  QuantityTrack turned(turned_q, start);
  EXPECT_NEAR(track.atStart(), 0.0, 1e-9);
  const double w = 2.0 * M_PI;  // rad/s about x: a whole turn in 1 s
  double at_end = NAN, turned_end = NAN, most = 0.0;
  for (int k = 1; k <= 1000; ++k) {
    const double t = k / 1000.0;
    const sim::Pose pose{sim::Vec3::Zero(), sim::Quat(Eigen::AngleAxisd(w * t, sim::Vec3::UnitX()))};
    at_end = track.next(t, pose, sim::Vec3::Zero(), sim::Vec3(w, 0.0, 0.0));
    turned_end = turned.next(t, pose, sim::Vec3::Zero(), sim::Vec3(w, 0.0, 0.0));
    most = std::max(most, at_end);
  }
  EXPECT_NEAR(at_end, 0.0, 1e-6);
  EXPECT_NEAR(turned_end, 360.0, 1e-6);
  EXPECT_NEAR(most, 180.0, 0.5);
  QuantityTrack spin(tilt, start);
  EXPECT_NEAR(spin.next(0.1, {sim::Vec3::Zero(), sim::Quat(Eigen::AngleAxisd(1.0, sim::Vec3::UnitY()))}, sim::Vec3::Zero(),
                        sim::Vec3::Zero()),
              0.0, 1e-9);
  QuantityTrack side(tilt, start);
  EXPECT_NEAR(side.next(0.1, {sim::Vec3::Zero(), sim::Quat(Eigen::AngleAxisd(M_PI / 2, sim::Vec3::UnitZ()))},
                        sim::Vec3::Zero(), sim::Vec3::Zero()),
              90.0, 1e-9);
}

TEST(Compare, BadOptionsAreErrorsNamingTheOptionBeforeAnyRun) {
  CompareOptions o;
  o.scene = "fig5-push-ball";
  o.godfinger = kBin;
  o.out = freshFolder("compare-bad-models").string();  // nothing may be written; if it were, here
  for (const std::vector<std::string>& models :
       {std::vector<std::string>{}, {"god_object", "point"}, {"god_finger", "god_finger"},
        {"god_object", "soft_finger", "god_finger", "god_object", "soft_finger"}}) {
    o.models = models;
    try {
      runCompare(o);
      ADD_FAILURE() << "accepted " << models.size() << " models";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--models"), std::string::npos) << e.what();
    }
  }
  // The chart's quantity is checked against the scene before any run, and nothing is written.
  const fs::path out = fs::path(o.out) / "never";
  o.out = out.string();
  o.models = {"god_object", "god_finger"};
  for (const auto& [chart, body, option] : {std::tuple{"rotation", "no_such_body", "--body"},
                                            std::tuple{"ball.qq", "", "--chart"},
                                            std::tuple{"index.fy", "ball", "--body"}}) {
    o.chart = chart;
    o.body = body;
    try {
      runCompare(o);
      ADD_FAILURE() << "accepted --chart " << chart << " --body " << body;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out)) << chart;
  }
}

// god_finger_3dof and god_finger_6dof are the god-finger with pad_model disc and oriented on
// every finger; the contact_model names stay one override each; the runs of a pad model carry
// its pad_model.
TEST(Compare, PadModelNamesAreAGodFingerWithItsPadModel) {
  EXPECT_EQ(compareModelOverrides({"left", "right"}, "god_finger_3dof"),
            (std::vector<std::string>{"fingers.left.contact_model=god_finger", "fingers.left.pad_model=disc",
                                      "fingers.right.contact_model=god_finger", "fingers.right.pad_model=disc"}));
  EXPECT_EQ(compareModelOverrides({"index"}, "god_finger_6dof"),
            (std::vector<std::string>{"fingers.index.contact_model=god_finger", "fingers.index.pad_model=oriented"}));
  EXPECT_EQ(compareModelOverrides({"index"}, "soft_finger"),
            (std::vector<std::string>{"fingers.index.contact_model=soft_finger"}));
  EXPECT_EQ(modelTitle("god_finger_3dof"), "god-finger 3-DOF");
  EXPECT_EQ(modelTitle("god_finger_6dof"), "god-finger 6-DOF");
  EXPECT_NE(modelColour("god_finger_6dof", 1), modelColour("god_finger_3dof", 0));
  // Every finger of each run gets its pad: the scene loads with the overrides, pad_model set.
  const std::string scene = resolveScenePath("orientation-track");
  for (const char* model : {"god_finger_3dof", "god_finger_6dof"}) {
    const SessionDesc s = loadSceneFile(scene, compareModelOverrides({"index"}, model));
    EXPECT_EQ(s.scene.fingers.at(0).patch.pad_model,
              std::string(model) == "god_finger_6dof" ? sim::PadModel::kOriented : sim::PadModel::kDisc)
        << model;
  }
}

TEST(Compare, AShortFig5ComparisonWritesFramesVideoAndMeasures) {
  const fs::path out = freshFolder("compare-fig5");
  const fs::path video = out / "fig5.mp4";
  // A frame an earlier, longer comparison left: the new sequence replaces it.
  fs::create_directories(out / "frames");
  std::ofstream(out / "frames" / "000200.png") << "stale";
  const int code = exitStatus(kBin + " compare fig5-push-ball --models god_object,god_finger --duration 1.2 --out " +
                              out.string() + " --frames --video " + video.string() + " --quiet 2> " +
                              (out / "stderr.txt").string());
  ASSERT_EQ(code, 0) << readFile(out / "stderr.txt");
  const nlohmann::json c = nlohmann::json::parse(readFile(out / "compare.json"));
  ASSERT_EQ(c["models"].size(), 2u);
  EXPECT_EQ(c["models"][0]["model"], "god_object");
  EXPECT_EQ(c["models"][1]["model"], "god_finger");
  // 1.2 s at 60 frames per second, from t = 0: 73 frames, each at the scene's frame size.
  EXPECT_EQ(c["frames"], 73);
  const render::Image last = render::readPng((out / "frames" / "000072.png").string());
  EXPECT_EQ(last.width, 1280);
  EXPECT_EQ(last.height, 720);
  EXPECT_FALSE(fs::exists(out / "frames" / "000073.png"));
  EXPECT_FALSE(fs::exists(out / "frames" / "000200.png"));
  EXPECT_GT(fs::file_size(video), 10000u);
  // Each run kept its summary and trace; its own frames were removed once composited.
  for (const char* m : {"god_object", "god_finger"}) {
    EXPECT_TRUE(fs::exists(out / m / "summary.json")) << m;
    EXPECT_TRUE(fs::exists(out / m / "trace.csv")) << m;
    EXPECT_FALSE(fs::exists(out / m / "frames")) << m;
  }
  // What the comparison shows: rolling without slipping turns a ball by its travel over its
  // radius; the god-object's ball rolls (within 5 % of that), the god-finger's slides (less
  // than a fifth of it).
  const double radius = 0.03;  // m, the scene's ball
  for (int i = 0; i < 2; ++i) {
    const std::string m = c["models"][i]["model"];
    const std::vector<std::vector<double>> x = readCsvColumns((out / m / "trace.csv").string(), {"ball.px"});
    const double rolled_deg = (x[0].back() - x[0].front()) / radius * 180.0 / M_PI;
    const double turned = c["models"][i]["chart"]["final"].get<double>();
    RecordProperty(m + "_rolled_deg", std::to_string(rolled_deg));
    RecordProperty(m + "_turned_deg", std::to_string(turned));
    ASSERT_GT(rolled_deg, 20.0) << m << ": the ball was pushed";
    if (i == 0) {
      EXPECT_NEAR(turned / rolled_deg, 1.0, 0.05) << m;
    } else {
      EXPECT_LT(turned / rolled_deg, 0.2) << m;
    }
  }
  EXPECT_GT(c["models"][0]["step_time_us"]["median"].get<double>(), 0.0);
}

}  // namespace
}  // namespace gf::app
