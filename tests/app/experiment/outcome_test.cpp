// A trial's outcome (app/experiment/outcome.hpp) against traces whose answer is known: when the
// goal began to hold, letting go, tilt limits, orientation goals and rolling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/experiment/outcome.hpp"

namespace gf::app {
namespace {

using sim::Vec3;

// A trace of a body "b" and a finger "f" pressing 2 N: `seconds` at 100 rows a second, the
// body's centre and orientation at each row's time from `pose`.
CsvTable bodyTrace(double seconds, const std::function<std::pair<Vec3, sim::Quat>(double)>& pose) {
  CsvTable c;
  c.names = {"t", "b.px", "b.py", "b.pz", "b.qx", "b.qy", "b.qz", "b.qw", "f.fx", "f.fy", "f.fz"};
  c.columns.resize(c.names.size());
  for (int i = 0; i <= static_cast<int>(std::lround(seconds * 100.0)); ++i) {
    const double t = i * 0.01;
    const auto [p, q] = pose(t);
    const std::vector<double> row = {t, p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w(), 0.0, 2.0, 0.0};
    for (std::size_t k = 0; k < row.size(); ++k) c.columns[k].push_back(row[k]);
  }
  return c;
}

// (The body's name comes in as a string: GCC 12 at -O3 warns, wrongly, of an overlapping copy
// when a one-letter literal is assigned to the goal's member here.)
TaskGoal zoneGoal(const std::string& body = std::string(1, 'b')) {
  TaskGoal g;
  g.body = body;
  g.has_zone = true;
  g.zone_min = Vec3(-0.01, 0.05, -0.01);
  g.zone_max = Vec3(0.01, 0.2, 0.01);
  g.hold = 0.5;
  return g;
}

// 4 s of an upright body, its centre at height y(t) (m).
CsvTable uprightTrace(const std::function<double(double)>& y) {
  return bodyTrace(4.0, [&](double t) { return std::pair(Vec3(0.0, y(t), 0.0), sim::Quat::Identity()); });
}

// Rises into the zone at 1.0 s, drops out at 1.3 s, back at 2.0 s and stays: the first stretch
// held long enough starts at 2.0 s.
TEST(ExperimentOutcome, CompletionIsTheStartOfTheFirstStretchHeldLongEnough) {
  const CsvTable trace = uprightTrace([](double time) {
    const bool in = (time >= 1.0 - 1e-9 && time < 1.3 - 1e-9) || time >= 2.0 - 1e-9;
    return in ? 0.08 : 0.02;
  });
  const TrialOutcome o = judgeTrace(zoneGoal(), {"f"}, trace);
  EXPECT_TRUE(o.success) << o.failure;
  EXPECT_NEAR(o.completion_s, 2.0, 1e-9);
  EXPECT_NEAR(o.peak_force_n, 2.0, 1e-12);
  EXPECT_EQ(o.end_distance_m, 0.0);
  TaskGoal longer = zoneGoal();
  longer.hold = 2.5;  // 2.0 s + 2.5 s is past the trace's 4 s
  const TrialOutcome late = judgeTrace(longer, {"f"}, trace);
  EXPECT_FALSE(late.success);
  EXPECT_EQ(late.failure, "not reached in 4 s");
}

// With `released`, the goal holds only once no finger holds the body: a finger pressing 2 N until
// 2.5 s delays the completion from 1.0 s (in the zone) to 2.5 s.
TEST(ExperimentOutcome, AReleasedGoalWaitsForTheFingersToLetGo) {
  CsvTable trace = uprightTrace([](double time) { return time >= 1.0 - 1e-9 ? 0.08 : 0.02; });
  const auto column = [&](const std::string& name) -> std::vector<double>& {
    return trace.columns[static_cast<std::size_t>(std::find(trace.names.begin(), trace.names.end(), name) - trace.names.begin())];
  };
  const std::vector<double>& t = column("t");
  std::vector<double>& fy = column("f.fy");
  for (std::size_t i = 0; i < fy.size(); ++i) fy[i] = t[i] < 2.5 - 1e-9 ? 2.0 : 0.1;  // then a free proxy's inertia
  TaskGoal g = zoneGoal();
  EXPECT_NEAR(judgeTrace(g, {"f"}, trace).completion_s, 1.0, 1e-9) << "held or not";
  g.released = true;
  const TrialOutcome o = judgeTrace(g, {"f"}, trace);
  EXPECT_TRUE(o.success) << o.failure;
  EXPECT_NEAR(o.completion_s, 2.5, 1e-9);
}

// A body that tips 30 degrees about a horizontal axis on the way breaks a 20-degree limit; a spin
// about the vertical is no tilt; an orientation goal holds within its tolerance.
TEST(ExperimentOutcome, TiltLimitsAndOrientationGoals) {
  const auto angle = [](double t) { return std::min(1.0, t) * 30.0 * M_PI / 180.0; };
  const auto tipped = [&](double t) { return sim::Quat(Eigen::AngleAxisd(angle(t), Vec3::UnitX())); };
  const auto spun = [&](double t) { return sim::Quat(Eigen::AngleAxisd(angle(t) * 1.5, Vec3::UnitY())); };  // to 45 degrees
  const auto spunInZone = [&](double t) { return std::pair(Vec3(0.0, 0.1, 0.0), spun(t)); };
  TaskGoal g = zoneGoal();
  g.max_tilt_deg = 20.0;
  // under the zone: tipping decides
  const TrialOutcome fell = judgeTrace(g, {"f"}, bodyTrace(3.0, [&](double t) { return std::pair(Vec3(0.0, 0.02, 0.0), tipped(t)); }));
  EXPECT_FALSE(fell.success);
  EXPECT_EQ(fell.failure.rfind("tilted 20.", 0), 0u) << fell.failure;
  const TrialOutcome turned = judgeTrace(g, {"f"}, bodyTrace(3.0, spunInZone));
  EXPECT_NEAR(turned.max_tilt_deg, 0.0, 1e-6);
  TaskGoal dock;
  dock.body = "b";
  dock.orientation = sim::Quat(Eigen::AngleAxisd(45.0 * M_PI / 180.0, Vec3::UnitY()));
  dock.orientation_tolerance_deg = 5.0;
  dock.hold = 0.5;
  const TrialOutcome docked = judgeTrace(dock, {"f"}, bodyTrace(3.0, spunInZone));
  EXPECT_TRUE(docked.success) << docked.failure;
  // 40 degrees is within 5 of 45 from t = 40/45 s on (the spin reaches 45 degrees at 1 s).
  EXPECT_NEAR(docked.completion_s, 0.89, 0.0051);
}

// A ball of radius 3 cm going 10 cm: turned 10/3 rad it rolled (ratio 1), not turned it slid.
TEST(ExperimentOutcome, RollingBreaksARollLimitAndSlidingDoesNot) {
  const auto x = [](double t) { return 0.1 * std::min(1.0, t / 2.0); };
  const auto rolled = [&](double t) { return std::pair(Vec3(x(t), 0.03, 0.0), sim::Quat(Eigen::AngleAxisd(-x(t) / 0.03, Vec3::UnitZ()))); };
  const auto slid = [&](double t) { return std::pair(Vec3(x(t), 0.03, 0.0), sim::Quat::Identity()); };
  TaskGoal g;
  g.body = "b";
  g.has_zone = true;
  g.zone_min = Vec3(0.09, 0.0, -0.01);
  g.zone_max = Vec3(0.11, 0.05, 0.01);
  g.hold = 0.5;
  g.max_roll_ratio = 0.5;
  g.roll_radius = 0.03;
  const TrialOutcome r = judgeTrace(g, {"f"}, bodyTrace(3.0, rolled));
  EXPECT_FALSE(r.success);
  EXPECT_NEAR(r.roll_ratio, 1.0, 1e-6);
  EXPECT_EQ(r.failure.rfind("rolled", 0), 0u) << r.failure;
  const TrialOutcome s = judgeTrace(g, {"f"}, bodyTrace(3.0, slid));
  EXPECT_TRUE(s.success) << s.failure;
  EXPECT_NEAR(s.roll_ratio, 0.0, 1e-9);
}

}  // namespace
}  // namespace gf::app
