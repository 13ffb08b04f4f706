// Sessions: what `godfinger run` writes (trace, summary, contacts, frames) and how scripted
// overlay input reaches the simulation.
#include "app/session/session.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <map>
#include <numbers>
#include <sstream>
#include <vector>

#include "app/runs/files.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/expectations.hpp"
#include "app/study/study_measure.hpp"
#include "render/frames/image.hpp"
#include "tests/app/run_helpers.hpp"
#include "tests/scratch.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

using gf::app::test::readFile;

// A long run's rows go to disk while it runs: many rings' worth arrive whole, in order and
// formatted as appendNumber formats them, the owner waiting for the writer when the ring is full
// rather than losing a row; the file appears (replacing the earlier one) only when it is closed.
TEST(RowFile, RowsOfManyRingsArriveInOrderAndReplaceTheFileOnlyAtClose) {
  const fs::path path = gf::test::scratchRoot() / "gf_rows.csv";
  {
    std::ofstream earlier(path);
    earlier << "earlier run\n";
  }
  std::string expected = "i,x\n";
  {
    RowFileOptions small;
    small.ring_rows = 1024;
    RowFile file(path.string(), {"i", "x"}, small);
    ASSERT_EQ(file.columns(), 2u);
    for (int i = 0; i < 100000; ++i) {  // about 100 rings of 1024 rows
      const double row[2] = {static_cast<double>(i), 1.0 / (i + 3)};
      file.push(row);
      expected += std::to_string(i) + ',';
      appendNumber(expected, row[1]);
      expected += '\n';
    }
    EXPECT_EQ(readFile(path), "earlier run\n");
    file.close();
  }
  EXPECT_EQ(readFile(path), expected);
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
}

// A run that throws part-way still leaves a valid file of the rows it reached.
TEST(RowFile, AnOwnerThatThrowsLeavesTheRowsItReached) {
  const fs::path path = gf::test::scratchRoot() / "gf_rows_thrown.csv";
  try {
    RowFile file(path.string(), {"t"});
    const double row = 0.0;
    file.push(&row);
    throw std::runtime_error("the run failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(readFile(path), "t\n0\n");
}

TEST(RowFile, AFileThatCannotBeCreatedIsNamed) {
  const std::string path = (gf::test::scratchRoot() / "gf_no_such_folder" / "trace.csv").string();
  try {
    RowFile file(path, {"t"});
    FAIL() << "opened " << path;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ".tmp: cannot create"), std::string::npos) << e.what();
  }
}

TEST(Session, SameSceneTwiceGivesByteIdenticalTrace) {
  SessionDesc s = loadSceneFile(resolveScenePath("fig7-side-pick"));
  s.scene.duration = 1.0;
  const fs::path a = gf::test::scratchRoot() / "gf_session_a", b = gf::test::scratchRoot() / "gf_session_b";
  runSession(s, {a.string(), false, false, false, "", ""});
  runSession(s, {b.string(), false, false, false, "", ""});
  const std::string ta = readFile(a / "trace.csv");
  EXPECT_GT(ta.size(), 1000u);
  EXPECT_EQ(ta, readFile(b / "trace.csv"));
  EXPECT_TRUE(fs::exists(a / "summary.json"));
  // With the aggregate solver too.
  s.scene.world.contact_solver = sim::ContactSolver::kAggregate;
  runSession(s, {a.string(), false, false, false, "", ""});
  runSession(s, {b.string(), false, false, false, "", ""});
  const std::string tc = readFile(a / "trace.csv");
  EXPECT_NE(tc, ta) << "the aggregate run is its own";
  EXPECT_EQ(tc, readFile(b / "trace.csv"));
  EXPECT_EQ(ta.substr(0, ta.find('\n')),
            "t,box.px,box.py,box.pz,box.qx,box.qy,box.qz,box.qw,left.fx,left.fy,left.fz,left.n_sgo,left.r,left.px,left.py,left.pz,left.dx,left.dy,left.dz,"
            "right.fx,right.fy,right.fz,right.n_sgo,right.r,right.px,right.py,right.pz,right.dx,right.dy,right.dz,box.vx,box.vy,box.vz,box.wx,box.wy,box.wz,"
            "left.sent_fx,left.sent_fy,left.sent_fz,left.port_energy,right.sent_fx,right.sent_fy,right.sent_fz,right.port_energy,"
            "left+right.overlap_mm2");
}

// Options writing into a fresh temporary folder `name`, without progress lines.
SessionOptions freshOutput(const std::string& name) {
  const fs::path out = gf::test::scratchRoot() / name;
  fs::remove_all(out);
  SessionOptions options;
  options.out_dir = out.string();
  options.progress = false;
  return options;
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Every key of `j`, at any depth.
void collectKeys(const nlohmann::json& j, std::vector<std::string>& keys) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) {
      keys.push_back(k);
      collectKeys(v, keys);
    }
  } else if (j.is_array()) {
    for (const auto& v : j) collectKeys(v, keys);
  }
}

// The press depth reaches contacts/*.json with the separation, in the world frame; the radius
// there is Eq. 1 of that press depth; every angle in every JSON file is in degrees.
TEST(Session, ContactsCarryPressDepthAndAnglesAreInDegrees) {
  const std::vector<std::string> overrides = {"duration=1.0", "record.contacts=[0.8]", "fingers.left.tau_a=45"};
  SessionOptions options = freshOutput("gf_session_contacts");
  options.close_ups = false;
  runSession(loadSceneFile(resolveScenePath("fig7-side-pick"), overrides), options);
  const fs::path out(options.out_dir);
  const nlohmann::json contacts = readJson(out / "contacts" / "t0.800.json");
  EXPECT_EQ(contacts["frame"], "world");
  ASSERT_EQ(contacts["fingers"].size(), 2u);
  for (const nlohmann::json& f : contacts["fingers"]) {
    ASSERT_EQ(f["contacts"].size(), 1u);
    const nlohmann::json& c = f["contacts"][0];
    const double press = c["press_depth_m"];
    EXPECT_GT(press, 0.004) << "the devices are 4 mm past the proxies' resting place and the box gives";
    EXPECT_LT(c["separation_m"].get<double>(), 0.0);
    EXPECT_NEAR(c["radius_m"].get<double>(), 0.01 * -std::expm1(-press / 0.004), 1e-12) << "Eq. 1";
    EXPECT_FALSE(c.contains("distance_m"));
  }
  const nlohmann::json summary = readJson(out / "summary.json");
  EXPECT_NEAR(summary["fingers"][0]["tau_a_deg"].get<double>(), 45.0, 1e-9);
  EXPECT_EQ(summary["counters"]["crossing_limit_stops"].get<long>(), 0) << "every walk within its budget";
  // Each SGO's load (and the true point's) is there, one per SGO; with the contact's tangential
  // forces they add up to the contact's force (within 1 %, as written with JSON's rounding).
  for (const nlohmann::json& f : contacts["fingers"]) {
    const nlohmann::json& c = f["contacts"][0];
    ASSERT_EQ(c["sgo_loads"].size(), c["sgos"].size());
    const auto v = [](const nlohmann::json& a) { return Eigen::Vector3d(a[0], a[1], a[2]); };
    const Eigen::Vector3d n = v(c["outward_normal"]);
    const auto force = [&](const nlohmann::json& l) { return Eigen::Vector3d(v(l["tangential_n"]) - l["normal_n"].get<double>() * n); };
    Eigen::Vector3d sum = force(c["point_load"]);
    for (const nlohmann::json& l : c["sgo_loads"]) sum += force(l);
    const Eigen::Vector3d total = v(c["force_n"]);
    EXPECT_GT(c["normal_force_n"].get<double>(), 1.0) << "the fingers squeeze the box";
    EXPECT_LT((sum - total).norm(), 0.01 * total.norm());
    EXPECT_NEAR(c["normal_force_n"].get<double>(), -total.dot(n), 1e-9 * total.norm());
  }
  std::vector<std::string> keys;
  collectKeys(contacts, keys);
  collectKeys(summary, keys);
  for (const std::string& k : keys) EXPECT_FALSE(k.ends_with("_rad")) << k;
}

// A 0.5 s offline session gives a frame at every 1/60 s (t = 0 included), close-ups beside
// the contact JSON, and the overlay's scripted clicks change the running simulation.
TEST(Session, WritesEveryFrameAndAppliesScriptedInput) {
  const std::vector<std::string> overrides = {"duration=0.6", "record.contacts=[0.4]", "render.width=320",
      "render.height=180",
      "render.actions=[{t = 0.3, widget = \"left/god_finger\", value = \"off\"}]"};
  SessionOptions options = freshOutput("gf_render_session");
  options.frames = true;
  runSession(loadSceneFile(resolveScenePath("overlay-demo"), overrides), options);
  const fs::path out(options.out_dir);
  int frames = 0;
  for (const auto& e : fs::directory_iterator(out / "frames")) frames += e.path().extension() == ".png";
  EXPECT_EQ(frames, 37);  // k / 60 s for k = 0..36
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400.json"));
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400-left.png"));
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400-right.png"));
  const render::Image frame = render::readPng((out / "frames" / "000036.png").string());
  EXPECT_EQ(frame.width, 320);
  EXPECT_EQ(frame.height, 180);
  const nlohmann::json summary = readJson(out / "summary.json");
  ASSERT_EQ(summary["overlay_changes"].size(), 1u);
  EXPECT_EQ(summary["overlay_changes"][0]["finger"], "left");
  EXPECT_EQ(summary["overlay_changes"][0]["n_sgo"], 0);
  // The click lands on the frame after the press: (ceil(0.3 * 60) + 2) / 60 s.
  EXPECT_NEAR(summary["overlay_changes"][0]["t"].get<double>(), 20.0 / 60.0, 1e-3);
}

// The files of a folder by name, with their bytes.
std::map<std::string, std::string> filesIn(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(folder)) files[e.path().filename().string()] = readFile(e.path());
  return files;
}

// A run's contact close-up (t = 0.8 s: frame 48; drawn once the frames are, as an offline run
// with frames does) leaves its frames the files of a run without close-ups, byte for byte. Drawn
// among the frames (realtime), a close-up draws its own shadow map, without the fingers, and
// leaves none behind: SamePicture.ACloseUpAmongFramesLeavesTheFrameOfItsInstantItsShadows.
TEST(Session, ACloseUpLeavesTheFrameOfItsInstantItsShadows) {
  std::map<std::string, std::string> frames[2];
  for (int run = 0; run < 2; ++run) {
    SessionOptions options = freshOutput("gf_session_close_up_" + std::to_string(run));
    options.frames = true;
    const std::vector<std::string> set = {"duration=1.0", "render.width=320", "render.height=180",
                                          run == 0 ? "record.contacts=[0.8]" : "record.contacts=[]"};
    runSession(loadSceneFile(resolveScenePath("fig8-pinch-oscillation"), set), options);
    const fs::path out(options.out_dir);
    frames[run] = filesIn(out / "frames");
    if (run == 0) {
      EXPECT_TRUE(fs::exists(out / "contacts" / "t0.800-left.png"));
    }
  }
  ASSERT_EQ(frames[0].size(), 61u);
  EXPECT_TRUE(frames[0] == frames[1]) << "a close-up changed the frame of its instant";
}

// A realtime run records how its deadlines were kept: the haptic thread's policy (normal when
// SCHED_FIFO is not asked for, as for a user without privileges), the spin, the late steps per
// second of the run, and the renderer lowered to nice 10 (any user may choose it). Wall-clock
// figures are only checked for being there, not for their values.
TEST(Session, RealtimeRunRecordsItsPrioritiesAndLateSteps) {
  SessionOptions options = freshOutput("gf_realtime_session");
  options.realtime = true;
  options.frames = true;
  options.fifo = false;
  options.spin_us = 100.0;
  const std::vector<std::string> overrides = {"duration=0.3", "render.width=160", "render.height=90"};
  runSession(loadSceneFile(resolveScenePath("fig7-side-pick"), overrides), options);
  const nlohmann::json summary = readJson(fs::path(options.out_dir) / "summary.json");
  const nlohmann::json& r = summary["realtime"];
  EXPECT_EQ(r["haptic_priority"], "normal");
  EXPECT_EQ(r["fifo_requested"], false);
  EXPECT_EQ(r["spin_us"], 100.0);
  ASSERT_EQ(r["late_per_second"].size(), 2u);  // seconds 0 and the part-second after
  EXPECT_EQ(r["late_per_second"][0].get<long>() + r["late_per_second"][1].get<long>(), r["late_steps"].get<long>());
  EXPECT_GE(r["max_lateness_us"].get<double>(), 0.0);
  EXPECT_EQ(summary["counters"]["steps"], 300);
  EXPECT_EQ(summary["render"]["priority"], "nice 10");
  // Published at every 1/60 s of simulated time (0 to 0.3 s); how many a nice-10 renderer
  // drew depends on the CPU it got (none on a machine busy with other work).
  EXPECT_EQ(summary["render"]["published"], 19);
  EXPECT_LE(summary["render"]["frames"].get<long>(), 19);
}

// The cells of one CSV line.
std::vector<std::string> cellsOf(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

// A free ball (no gravity, no finger) under a known force and torque: trace.csv's velocity
// columns read v = F t / m and w = tau t / I (I = 2/5 m r^2) at every row, to rounding.
TEST(Session, TraceHasTheVelocitiesOfALoadedBody) {
  const std::string text = R"(name = "loaded"
duration = 0.5
effects = []
[bodies.ball]
shape = "sphere"
radius = 0.04
mass = 0.5
position = [0, 1, 0]
[[loads]]
body = "ball"
force = [0.3, 0, -0.1]
torque = [0, 2e-3, 0]
)";
  SessionOptions options = freshOutput("gf_session_loaded");
  runSession(parseSceneText(text, "loaded.toml", ""), options);
  std::stringstream trace(readFile(fs::path(options.out_dir) / "trace.csv"));
  std::string line;
  std::getline(trace, line);
  EXPECT_EQ(line,
            "t,ball.px,ball.py,ball.pz,ball.qx,ball.qy,ball.qz,ball.qw,"
            "ball.vx,ball.vy,ball.vz,ball.wx,ball.wy,ball.wz");
  const double m = 0.5, inertia = 0.4 * m * 0.04 * 0.04;
  int rows = 0;
  for (; std::getline(trace, line); ++rows) {
    const std::vector<std::string> c = cellsOf(line);
    ASSERT_EQ(c.size(), 14u) << line;
    const double t = std::stod(c[0]);
    const double expected[6] = {0.3 * t / m, 0.0, -0.1 * t / m, 0.0, 2e-3 * t / inertia, 0.0};
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(std::stod(c[8 + k]), expected[k], 1e-12 * (1 + std::abs(expected[k]))) << line;
  }
  EXPECT_EQ(rows, 500);
}

// The Fig. 8 hold meets the scene's [expect]; with god-objects the cylinder swings over and the
// pads lose their SGOs, and each failed expectation comes back with its worst value and time.
TEST(Session, ExpectationsPassOnTheHoldAndFailWithGodObjects) {
  SessionDesc s = loadSceneFile(resolveScenePath("fig8-pinch-oscillation"));
  s.scene.duration = 4.0;
  std::vector<ExpectFailure> failed{{"placeholder", 0, 0, 0}};
  SessionOptions options = freshOutput("gf_session_expect");
  options.expect_failures = &failed;
  runSession(s, options);
  EXPECT_TRUE(failed.empty()) << failed.front().text();
  EXPECT_EQ(readJson(fs::path(options.out_dir) / "summary.json")["expectations"]["failed"], 0);

  for (sim::FingerDesc& f : s.scene.fingers) f.patch.n_sgo = 0;
  runSession(s, options);
  std::map<std::string, ExpectFailure> by_name;
  for (const ExpectFailure& f : failed) by_name[f.name] = f;
  ASSERT_TRUE(by_name.contains("bodies.cylinder.max_rotation_deg"));
  EXPECT_GT(by_name["bodies.cylinder.max_rotation_deg"].value, 90.0);
  EXPECT_GT(by_name["bodies.cylinder.max_rotation_deg"].time, 1.0);
  ASSERT_TRUE(by_name.contains("fingers.left.min_sgo"));
  EXPECT_EQ(by_name["fingers.left.min_sgo"].value, 0.0);
  const nlohmann::json summary = readJson(fs::path(options.out_dir) / "summary.json");
  EXPECT_EQ(summary["expectations"]["failed"], failed.size());
}

// rests_after: the pressed puck spun about the vertical by its torque still rests (a spin is not
// a tilt, and its centre stays put); pushed sideways instead, its speed fails the check.
TEST(Session, ARestingBodyMaySpinButNotTiltOrMove) {
  SessionDesc s = loadSceneFile(resolveScenePath("pressed-puck"));
  s.expect.bodies["puck"].rests_after = 0.5;
  std::vector<ExpectFailure> failed{{"placeholder", 0, 0, 0}};
  SessionOptions options = freshOutput("gf_session_rests");
  options.expect_failures = &failed;
  runSession(s, options);
  EXPECT_TRUE(failed.empty()) << failed.front().text();
  const nlohmann::json measures = readJson(fs::path(options.out_dir) / "summary.json")["measures"];
  EXPECT_LT(measures["bodies.puck.rests_after.tilt_rate"].get<double>(), 0.05);

  ASSERT_EQ(s.scene.loads.size(), 1u);
  s.scene.loads[0].torque = sim::Vec3::Zero();
  s.scene.loads[0].force = sim::Vec3(0.5, 0.0, 0.0);
  runSession(s, options);
  std::map<std::string, ExpectFailure> by_name;
  for (const ExpectFailure& f : failed) by_name[f.name] = f;
  ASSERT_TRUE(by_name.contains("bodies.puck.rests_after.speed"));
  EXPECT_GT(by_name["bodies.puck.rests_after.speed"].value, 1e-3);
  EXPECT_GT(by_name["bodies.puck.rests_after.speed"].time, 0.6);
}

// The holds' checks, against the run's own trace: max_drift is the puck's largest distance from
// where it was at `after`, max_tilt_deg how far the vertical turned since, and max_force_change
// the coupling force's largest change from its value at the window's start. The puck is pressed
// and then pushed sideways by 2 N from 0.6 s (the finger's friction holds it: the proxy gives
// way by about 2.5 mm); every row of the trace is a step.
TEST(Session, HoldChecksMeasureFromTheirStartAsTheTraceDoes) {
  SessionDesc s = loadSceneFile(resolveScenePath("pressed-puck"));
  s.scene.duration = 1.0;
  ASSERT_EQ(s.scene.loads.size(), 1u);
  s.scene.loads[0].torque = sim::Vec3::Zero();
  s.scene.loads[0].force = sim::Vec3(2.0, 0.0, 0.0);
  s.scene.loads[0].start = 0.6;
  BodyExpect& puck = s.expect.bodies["puck"];
  puck.after = 0.5;
  puck.max_drift = 1e-5;
  puck.max_tilt_deg = 0.01;
  const std::string finger = s.scene.fingers.at(0).name;
  FingerExpect& f = s.expect.fingers[finger];
  f.from = 0.5;
  f.to = 0.9;
  f.max_force_change = 0.01;
  SessionOptions options = freshOutput("gf_session_hold");
  std::vector<ExpectFailure> failed;
  options.expect_failures = &failed;
  runSession(s, options);
  std::map<std::string, ExpectFailure> by_name;
  for (const ExpectFailure& e : failed) by_name[e.name] = e;
  ASSERT_TRUE(by_name.contains("bodies.puck.max_drift"));
  ASSERT_TRUE(by_name.contains("fingers." + finger + ".max_force_change"));

  std::ifstream trace(fs::path(options.out_dir) / "trace.csv");
  std::string line;
  std::getline(trace, line);
  const std::vector<std::string> header = cellsOf(line);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t t_at = column("t"), p_at = column("puck.px"), q_at = column("puck.qx"), f_at = column(finger + ".fx");
  ASSERT_LT(f_at, header.size());
  double drift = 0.0, tilt = 0.0, change = 0.0;
  bool started = false, force_started = false;
  sim::Vec3 p0 = sim::Vec3::Zero(), f0 = sim::Vec3::Zero();
  Eigen::Quaterniond q0 = Eigen::Quaterniond::Identity();
  while (std::getline(trace, line)) {
    const std::vector<std::string> c = cellsOf(line);
    const double t = std::stod(c[t_at]);
    const sim::Vec3 p(std::stod(c[p_at]), std::stod(c[p_at + 1]), std::stod(c[p_at + 2]));
    const Eigen::Quaterniond q(std::stod(c[q_at + 3]), std::stod(c[q_at]), std::stod(c[q_at + 1]), std::stod(c[q_at + 2]));
    const sim::Vec3 force(std::stod(c[f_at]), std::stod(c[f_at + 1]), std::stod(c[f_at + 2]));
    if (t >= 0.5 - 1e-12) {
      if (!started) p0 = p, q0 = q, started = true;
      drift = std::max(drift, (p - p0).norm());
      const sim::Vec3 up = (q * q0.inverse()) * sim::Vec3::UnitY();
      tilt = std::max(tilt, std::atan2(std::hypot(up.x(), up.z()), up.y()) * 180.0 / std::numbers::pi);
    }
    if (t >= 0.5 - 1e-12 && t <= 0.9 + 1e-12) {
      if (!force_started) f0 = force, force_started = true;
      change = std::max(change, (force - f0).norm());
    }
  }
  // The trace prints 17 significant digits: the checker's values to within that rounding.
  EXPECT_NEAR(by_name["bodies.puck.max_drift"].value, drift, 1e-12);
  EXPECT_GT(drift, 1e-3) << "the push moved it";
  EXPECT_NEAR(by_name["fingers." + finger + ".max_force_change"].value, change, 1e-9);
  const double checked_tilt = by_name.contains("bodies.puck.max_tilt_deg") ? by_name["bodies.puck.max_tilt_deg"].value
                                                                           : readJson(fs::path(options.out_dir) / "summary.json")["measures"]["bodies.puck.max_tilt_deg"].get<double>();
  EXPECT_NEAR(checked_tilt, tilt, 1e-9);
}

// max_roll_ratio: pushed by the god-finger, the Fig. 5 ball slides (its roll ratio over the
// push stays under the scene's 0.2); pushed by a god-object it rolls, 1, and the check fails at
// the window's end. Both are the studies' roll_ratio measure of the run's trace, to the bit.
// The first 0.6 s of the push only, to keep the test short.
TEST(Session, TheFig5BallSlidesUnderAGodFingerAndRollsUnderAGodObject) {
  SessionDesc s = loadSceneFile(resolveScenePath("fig5-push-ball"));
  s.scene.duration = 1.2;
  BodyExpect& ball = s.expect.bodies.at("ball");
  ASSERT_EQ(ball.max_roll_ratio, 0.2);
  ASSERT_EQ(ball.roll_from, 0.6);
  ball.roll_to = 1.2;
  StudyMeasure study_measure;
  study_measure.name = "roll_ratio";
  study_measure.kind = MeasureKind::kRollRatio;
  study_measure.reference = ReferenceKind::kRollingPrediction;
  study_measure.body = "ball";
  study_measure.from = 0.6;
  study_measure.to = 1.2;
  std::vector<ExpectFailure> failed{{"placeholder", 0, 0, 0}};
  SessionOptions options = freshOutput("gf_session_roll");
  options.expect_failures = &failed;
  runSession(s, options);
  EXPECT_TRUE(failed.empty()) << failed.front().text();
  const double sliding = readJson(fs::path(options.out_dir) / "summary.json")["measures"]["bodies.ball.max_roll_ratio"];
  EXPECT_LT(sliding, 0.2);
  EXPECT_EQ(sliding, evaluateMeasure(study_measure, readRunOutputs(options.out_dir, s), nullptr).measure);

  s.scene.fingers.at(0).patch.n_sgo = 0;
  runSession(s, options);
  std::map<std::string, ExpectFailure> by_name;
  for (const ExpectFailure& f : failed) by_name[f.name] = f;
  ASSERT_TRUE(by_name.contains("bodies.ball.max_roll_ratio"));
  EXPECT_NEAR(by_name["bodies.ball.max_roll_ratio"].value, 1.0, 1e-3);
  EXPECT_NEAR(by_name["bodies.ball.max_roll_ratio"].time, 1.2, 1e-9);
  EXPECT_EQ(by_name["bodies.ball.max_roll_ratio"].value,
            evaluateMeasure(study_measure, readRunOutputs(options.out_dir, s), nullptr).measure);
}

}  // namespace
}  // namespace gf::app
