// The paper's experiments as bundled scenes: each shows the effect the paper reports, measured
// on the god-object (n_SGO = 0) and the god-finger (the scene's n_SGO) with the same devices,
// with each contact solver (world.contact_solver: points, aggregate).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/sim/test_context.hpp"

namespace gf::test_support {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// The contact solver of the running test ("points" or "aggregate").
std::string current_solver = "points";

class PaperScenes : public testing::TestWithParam<const char*> {
 protected:
  void SetUp() override { current_solver = GetParam(); }
};

const std::string& solver() { return current_solver; }

// Runs bundled scene `name` with every finger at n_sgo for `duration` (0: the scene's) under
// the test's contact solver, calling observe(world) after each step.
template <class Observer>
void runScene(const std::string& name, int n_sgo, double duration, Observer&& observe) {
  TestContext ctx(name, n_sgo, {"world.contact_solver=" + solver()});
  ctx.simulate(duration > 0.0 ? duration : ctx.scene().duration, observe);
}

int bodyIndex(const sim::World& w, const std::string& name) { return indexOf(w.desc().bodies, name); }

// Fig. 5: roll ratio = rotation angle x radius / distance travelled.
double rollRatio(int n_sgo) {
  double angle = 0.0, travelled = 0.0, start_x = 0.0;
  Eigen::Quaterniond last = Eigen::Quaterniond::Identity();
  bool first = true;
  runScene("fig5-push-ball", n_sgo, 0.0, [&](const sim::World& w) {
    const int b = bodyIndex(w, "ball");
    const sim::Pose p = w.bodyPose(b);
    if (first) start_x = p.position.x(), last = p.orientation, first = false;
    angle += Eigen::AngleAxisd(p.orientation * last.inverse()).angle();  // accumulated rotation
    last = p.orientation;
    travelled = p.position.x() - start_x;
  });
  const double ratio = angle * 0.03 / travelled;
  std::printf("fig5 %s n_sgo=%d: rolled %.3f rad, travelled %.4f m, roll ratio %.3f\n", solver().c_str(), n_sgo, angle,
              travelled, ratio);
  EXPECT_GT(travelled, 0.03) << "the finger pushed the ball along";
  return ratio;
}

TEST_P(PaperScenes, Fig5GodFingerCutsRollingAtLeastInHalf) {
  const double go = rollRatio(0), gf = rollRatio(8);
  EXPECT_NEAR(go, 1.0, 0.2) << "god-object: the ball rolls";
  EXPECT_LT(gf, 0.5 * go) << "god-finger: the ball slides";
}

// Height gained by `body` at the end, and its largest tilt (deg).
struct Lift {
  double height = 0.0, tilt = 0.0, final_tilt = 0.0;
};

Lift lift(const std::string& scene, const std::string& body, int n_sgo) {
  Lift l;
  double y0 = NAN;
  runScene(scene, n_sgo, 0.0, [&](const sim::World& w) {
    const sim::Pose p = w.bodyPose(bodyIndex(w, body));
    if (std::isnan(y0)) y0 = p.position.y();
    l.height = p.position.y() - y0;
    l.final_tilt = Eigen::AngleAxisd(p.orientation).angle() * kRadToDeg;
    l.tilt = std::max(l.tilt, l.final_tilt);
  });
  std::printf("%s %s n_sgo=%d: %s lifted %.4f m, largest tilt %.2f deg\n", scene.c_str(), solver().c_str(), n_sgo,
              body.c_str(), l.height, l.tilt);
  return l;
}

TEST_P(PaperScenes, Fig6OneFingerLiftsWithGodFingerNotGodObject) {
  const Lift go = lift("fig6-lift-one-finger", "tile", 0), gf = lift("fig6-lift-one-finger", "tile", 8);
  EXPECT_GT(go.final_tilt, 30.0) << "god-object: the tile tips off the single point";
  EXPECT_GT(gf.height, 0.035) << "god-finger: lifted 4 cm and held";
  EXPECT_LT(gf.tilt, 10.0);
}

TEST_P(PaperScenes, Fig7TwoFingersLiftThenOneCarriesOn) {
  const Lift gf = lift("fig7-lift-two-fingers", "tile", 8);
  EXPECT_GT(gf.height, 0.025) << "still held 3 cm up after the left finger let go";
  EXPECT_LT(gf.tilt, 10.0);
}

TEST_P(PaperScenes, Fig7SidePickLiftsTheBox) {
  const Lift gf = lift("fig7-side-pick", "box", 8);
  EXPECT_GT(gf.height, 0.045);
  EXPECT_LT(gf.tilt, 5.0);
}

// Fig. 8: swing about the pinch axis after the lift, and the spread of the y force on the
// centre of mass over the last 5 s.
struct Fig8 {
  double swing = 0.0, force_sd = 0.0;
};

Fig8 fig8(int n_sgo) {
  Fig8 r;
  double sum = 0.0, sum2 = 0.0, vy = 0.0;
  long n = 0;
  const double duration = 25.0, dt = 0.001;
  runScene("fig8-pinch-oscillation", n_sgo, duration, [&](const sim::World& w) {
    const int b = bodyIndex(w, "cylinder");
    const Eigen::AngleAxisd aa(w.bodyPose(b).orientation);
    if (w.time() > 1.0) r.swing = std::max(r.swing, std::abs(aa.angle() * aa.axis().x()) * kRadToDeg);
    const double v = w.bodyLinearVelocity(b).y();
    const double fy = 0.15 * ((v - vy) / dt + 9.81);
    vy = v;
    if (w.time() > duration - 5.0) sum += fy, sum2 += fy * fy, ++n;
  });
  r.force_sd = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  std::printf("fig8 %s n_sgo=%d: swing %.3f deg, y force sd over the last 5 s %.4g N\n", solver().c_str(), n_sgo, r.swing,
              r.force_sd);
  return r;
}

TEST_P(PaperScenes, Fig8GodFingerStopsTheSwingAndTheForceOscillation) {
  const Fig8 go = fig8(0), gf = fig8(8);
  EXPECT_GT(go.swing, 20.0);
  EXPECT_LT(gf.swing, 2.0);
  EXPECT_LT(gf.force_sd * 5.0, go.force_sd);
}

TEST_P(PaperScenes, ConcaveMeshIsTouchedAndMoved) {
  double moved = 0.0;
  long sgo_steps = 0;
  sim::Vec3 start = sim::Vec3::Constant(NAN);
  runScene("concave-mesh", 8, 0.0, [&](const sim::World& w) {
    const sim::Vec3 p = w.bodyPose(bodyIndex(w, "bunny")).position;
    if (!start.allFinite()) start = p;
    moved = (p - start).norm();
    if (w.sgoCount(0) > 0) ++sgo_steps;
    ASSERT_TRUE(p.allFinite());
  });
  std::printf("concave-mesh: bunny moved %.4f m, %ld steps with SGOs\n", moved, sgo_steps);
  EXPECT_GT(sgo_steps, 500) << "the finger's contact area lies on the bunny";
  EXPECT_GT(moved, 0.01) << "the finger moved the bunny";
}

INSTANTIATE_TEST_SUITE_P(Solvers, PaperScenes, testing::Values("points", "aggregate"),
                         [](const testing::TestParamInfo<const char*>& i) { return std::string(i.param); });

}  // namespace
}  // namespace gf::test_support
