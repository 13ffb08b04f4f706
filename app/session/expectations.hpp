// Expectations a scene file carries ([expect]): invariants the session checks after every step
// of a run and at its end, from the World's public state (never inside World::step). A failed
// expectation is printed, written into summary.json, and makes `godfinger run` exit 3.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/expect_desc.hpp"
#include "app/measures/roll_ratio.hpp"
#include "sim/mesh/mesh.hpp"

namespace gf::sim {
class World;
struct SceneDesc;
}  // namespace gf::sim

namespace gf::app {

/// One expectation that did not hold: the worst value, where and when.
struct ExpectFailure {
  std::string name;   ///< "bodies.box.max_speed"
  double value = 0.0, limit = 0.0, time = 0.0;
  std::string text() const;
};

/// Follows a run step by step. Allocates only in its constructor and on a failure's first
/// occurrence.
class ExpectChecker {
 public:
  ExpectChecker(const ExpectDesc& expect, const sim::World& world);
  /// After every step (haptic thread).
  void afterStep(const sim::World& world);
  /// After the last step: the failures, worst value of each. `at_scene_end` false: the run was
  /// cut short of the scene's duration (run --max-duration), so the limits taken at the end
  /// (ends_above, max_roll_ratio) are left unchecked; the others hold over the time run.
  std::vector<ExpectFailure> finish(const sim::World& world, bool at_scene_end = true);
  /// The expectations checked and the worst value each reached, for summary.json.
  nlohmann::json json() const;

 private:
  struct Check {
    std::string name;
    double limit = 0.0;
    bool at_most = true;  ///< value must stay <= limit (else >= limit)
    double worst = 0.0;
    double time = 0.0;
    bool seen = false;
  };
  void observe(Check& c, double value, double t);
  ExpectDesc expect_;
  std::vector<Check> checks_;
  // Per body and finger: indices into checks_ (-1: not checked) and what the checks need.
  struct BodyState {
    int body = -1;
    int speed = -1, angular = -1, above = -1, rotation = -1, ends = -1, drift = -1, tilt = -1;
    int rest_speed = -1, rest_tilt = -1;  // rests_after: speed and tilt rate after rests_after
    double after = 0.0, rests_after = 0.0;
    bool have_start = false;
    Eigen::Quaterniond start = Eigen::Quaterniond::Identity();
    sim::Vec3 start_position = sim::Vec3::Zero();
    int roll = -1;  // max_roll_ratio: taken at the end over the poses of roll_window
    double roll_from = 0.0, roll_to = 0.0, roll_last = 0.0;
    RollRatio roll_ratio{0.0, sim::Vec3::UnitY()};
  };
  struct FingerState {
    int finger = -1;
    int sgo = -1, force = -1, penetration = -1, tunnel = -1, port = -1, force_change = -1;
    double from = 0.0, to = 0.0;
    bool have_force = false;  // max_force_change: the force at the window's start
    sim::Vec3 start_force = sim::Vec3::Zero();
    // The plane of the contact it last pressed, in that body's frame (no_tunnelling).
    int pressed_body = -1;
    sim::Vec3 plane_point = sim::Vec3::Zero(), plane_normal = sim::Vec3::UnitY();
  };
  void checkTunnelling(const sim::World& world, FingerState& s, double t);
  void checkBody(const sim::World& world, BodyState& s, double t);
  std::vector<BodyState> bodies_;
  std::vector<FingerState> fingers_;
  int finite_ = -1, any_speed_ = -1, any_angular_ = -1, energy_ = -1;
  // Energy growth: (time, energy) minima of the current quiet stretch's last window, rising from
  // quiet_head_ (a monotonic queue), so the rise is the energy minus the front.
  std::vector<std::pair<double, double>> quiet_;
  std::size_t quiet_head_ = 0;
  std::vector<sim::Vec3> last_device_;
};

}  // namespace gf::app
