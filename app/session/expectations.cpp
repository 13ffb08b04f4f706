#include "app/session/expectations.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sim/scene/scene_desc.hpp"
#include "sim/world/world.hpp"

namespace gf::app {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr double kEnergyWindow = 1.0;  // s

bool finiteVec(const sim::Vec3& v) { return v.allFinite(); }

}  // namespace

std::string ExpectFailure::text() const {
  char b[256];
  std::snprintf(b, sizeof b, "expectation %s failed: %.6g (limit %.6g) at t = %.4f s", name.c_str(), value, limit, time);
  return b;
}

ExpectChecker::ExpectChecker(const ExpectDesc& expect, const sim::World& world) : expect_(expect) {
  const sim::SceneDesc& scene = world.desc();
  const auto add = [&](std::string name, double limit, bool at_most) {
    checks_.push_back({std::move(name), limit, at_most, at_most ? -HUGE_VAL : HUGE_VAL, 0.0, false});
    return static_cast<int>(checks_.size() - 1);
  };
  if (expect.finite) finite_ = add("finite", 0.0, true);  // value: 1 at a non-finite state
  if (expect.max_speed) any_speed_ = add("max_speed", *expect.max_speed, true);
  if (expect.max_angular_speed) any_angular_ = add("max_angular_speed", *expect.max_angular_speed, true);
  if (expect.energy_growth) energy_ = add("energy_growth", *expect.energy_growth, true);
  for (const auto& [name, e] : expect.bodies) {
    BodyState s;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      if (scene.bodies[b].name == name) s.body = static_cast<int>(b);
    }
    const std::string p = "bodies." + name + ".";
    if (e.max_speed) s.speed = add(p + "max_speed", *e.max_speed, true);
    if (e.max_angular_speed) s.angular = add(p + "max_angular_speed", *e.max_angular_speed, true);
    if (e.stays_above) s.above = add(p + "stays_above", *e.stays_above, false);
    if (e.max_rotation_deg) s.rotation = add(p + "max_rotation_deg", *e.max_rotation_deg, true);
    if (e.ends_above) s.ends = add(p + "ends_above", *e.ends_above, false);
    if (e.max_drift) s.drift = add(p + "max_drift", *e.max_drift, true);
    if (e.max_tilt_deg) s.tilt = add(p + "max_tilt_deg", *e.max_tilt_deg, true);
    if (e.rests_after) {
      s.rest_speed = add(p + "rests_after.speed", e.rest_speed, true);
      s.rest_tilt = add(p + "rests_after.tilt_rate", e.rest_tilt_rate, true);
      s.rests_after = *e.rests_after;
    }
    if (e.max_roll_ratio) {
      s.roll = add(p + "max_roll_ratio", *e.max_roll_ratio, true);
      s.roll_from = e.roll_from;
      s.roll_to = e.roll_to;
      s.roll_ratio = RollRatio(scene.bodies[static_cast<std::size_t>(s.body)].radius, sim::Vec3::UnitY());
    }
    s.after = e.after;
    bodies_.push_back(s);
  }
  // Every finger gets the scene-wide penetration and tunnelling checks; [expect.fingers.NAME]
  // adds its own.
  for (std::size_t f = 0; f < scene.fingers.size(); ++f) {
    const std::string& name = scene.fingers[f].name;
    const auto own = expect.fingers.find(name);
    const FingerExpect e = own != expect.fingers.end() ? own->second : FingerExpect{};
    FingerState s;
    s.finger = static_cast<int>(f);
    const std::string p = "fingers." + name + ".";
    if (e.min_sgo) s.sgo = add(p + "min_sgo", *e.min_sgo, false);
    if (e.max_force) s.force = add(p + "max_force", *e.max_force, true);
    if (e.max_force_change) s.force_change = add(p + "max_force_change", *e.max_force_change, true);
    if (const auto pen = e.max_penetration ? e.max_penetration : expect.max_penetration) {
      s.penetration = add(p + "max_penetration", *pen, true);
    }
    if (expect.no_tunnelling) s.tunnel = add(p + "no_tunnelling", 0.0, true);  // value: m behind the plane
    s.port = add(p + "port_energy", expect.min_port_energy, false);
    s.from = e.from;
    s.to = e.to;
    fingers_.push_back(s);
  }
  const std::size_t samples = static_cast<std::size_t>(scene.world.haptic_rate_hz * kEnergyWindow) + 2;
  quiet_.reserve(samples);
  for (int f = 0; f < static_cast<int>(scene.fingers.size()); ++f) last_device_.push_back(world.devicePosition(f));
}

void ExpectChecker::observe(Check& c, double value, double t) {
  const bool worse = !c.seen || (c.at_most ? value > c.worst : value < c.worst) || std::isnan(value);
  if (worse && !(std::isnan(c.worst) && c.seen)) {
    c.worst = value;
    c.time = t;
  }
  c.seen = true;
}

void ExpectChecker::afterStep(const sim::World& world) {
  const sim::SceneDesc& scene = world.desc();
  const double t = world.time();
  bool finite = true;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].mass <= 0.0) continue;
    const int i = static_cast<int>(b);
    const sim::Pose p = world.bodyPose(i);
    const sim::Vec3 v = world.bodyLinearVelocity(i), w = world.bodyAngularVelocity(i);
    finite = finite && finiteVec(p.position) && p.orientation.coeffs().allFinite() && finiteVec(v) && finiteVec(w);
    if (any_speed_ >= 0) observe(checks_[static_cast<std::size_t>(any_speed_)], v.norm(), t);
    if (any_angular_ >= 0) observe(checks_[static_cast<std::size_t>(any_angular_)], w.norm(), t);
  }
  for (int f = 0; f < static_cast<int>(scene.fingers.size()); ++f) {
    finite = finite && finiteVec(world.couplingForce(f)) && finiteVec(world.proxyPosition(f));
  }
  if (finite_ >= 0) {
    const bool rolled_back = world.counters().nan_recoveries > 0;
    observe(checks_[static_cast<std::size_t>(finite_)], finite && !rolled_back ? 0.0 : 1.0, t);
  }
  for (BodyState& s : bodies_) {
    if (s.body >= 0) checkBody(world, s, t);
  }
  for (FingerState& s : fingers_) {
    if (s.finger < 0) continue;
    if (s.force_change >= 0 && t >= s.from - 1e-12 && t <= s.to + 1e-12) {
      const sim::Vec3 force = world.couplingForce(s.finger);
      if (!s.have_force) s.start_force = force, s.have_force = true;
      observe(checks_[static_cast<std::size_t>(s.force_change)], (force - s.start_force).norm(), t);
    }
    if (s.sgo >= 0 && t >= s.from - 1e-12 && t <= s.to + 1e-12) {
      observe(checks_[static_cast<std::size_t>(s.sgo)], world.sgoCount(s.finger), t);
    }
    if (s.force >= 0) observe(checks_[static_cast<std::size_t>(s.force)], world.couplingForce(s.finger).norm(), t);
    observe(checks_[static_cast<std::size_t>(s.port)], world.portEnergy(s.finger), t);
    if (s.penetration >= 0) {
      sim::Touch touch;
      const double depth = world.deepestTouch(s.finger, touch) ? std::max(0.0, -touch.separation) : 0.0;
      observe(checks_[static_cast<std::size_t>(s.penetration)], depth, t);
    }
  }
  for (FingerState& s : fingers_) {
    if (s.tunnel >= 0) checkTunnelling(world, s, t);
  }
  if (energy_ >= 0) {
    // A quiet stretch: no device moved since the last step and no load acts.
    bool quiet = true;
    for (std::size_t f = 0; f < last_device_.size(); ++f) {
      const sim::Vec3 d = world.devicePosition(static_cast<int>(f));  // the sample this step ran with
      quiet = quiet && (d - last_device_[f]).norm() < 1e-12;
      last_device_[f] = d;
    }
    for (const sim::LoadDesc& l : scene.loads) quiet = quiet && sim::loadFactor(l, t) == 0.0;
    if (!quiet) {
      quiet_.clear();
      quiet_head_ = 0;
    } else {
      const double e = world.mechanicalEnergy();
      // quiet_ holds a rising run of minima over the last window (a monotonic queue).
      while (quiet_head_ < quiet_.size() && quiet_[quiet_head_].first < t - kEnergyWindow - 1e-12) ++quiet_head_;
      if (quiet_head_ < quiet_.size()) {
        observe(checks_[static_cast<std::size_t>(energy_)], e - quiet_[quiet_head_].second, t);
      }
      while (quiet_.size() > quiet_head_ && quiet_.back().second >= e) quiet_.pop_back();
      if (quiet_head_ > 0 && quiet_head_ * 2 >= quiet_.size()) {  // compact: the window stays bounded
        quiet_.erase(quiet_.begin(), quiet_.begin() + static_cast<std::ptrdiff_t>(quiet_head_));
        quiet_head_ = 0;
      }
      quiet_.emplace_back(t, e);
    }
  }
}

// [expect.bodies.NAME]'s limits at this step.
void ExpectChecker::checkBody(const sim::World& world, BodyState& s, double t) {
  const sim::Pose p = world.bodyPose(s.body);
  const sim::Vec3 v = world.bodyLinearVelocity(s.body), w = world.bodyAngularVelocity(s.body);
  if (s.speed >= 0) observe(checks_[static_cast<std::size_t>(s.speed)], v.norm(), t);
  if (s.angular >= 0) observe(checks_[static_cast<std::size_t>(s.angular)], w.norm(), t);
  if (s.above >= 0) observe(checks_[static_cast<std::size_t>(s.above)], p.position.y(), t);
  if ((s.rotation >= 0 || s.drift >= 0 || s.tilt >= 0) && t >= s.after - 1e-12) {
    if (!s.have_start) s.start = p.orientation, s.start_position = p.position, s.have_start = true;
    const Eigen::Quaterniond turn = p.orientation * s.start.inverse();
    if (s.rotation >= 0) observe(checks_[static_cast<std::size_t>(s.rotation)], Eigen::AngleAxisd(turn).angle() * kRadToDeg, t);
    if (s.drift >= 0) observe(checks_[static_cast<std::size_t>(s.drift)], (p.position - s.start_position).norm(), t);
    if (s.tilt >= 0) {
      // y is up: the angle between the vertical and where the turn since `after` takes it.
      const sim::Vec3 up = turn * sim::Vec3::UnitY();
      observe(checks_[static_cast<std::size_t>(s.tilt)], std::atan2(std::hypot(up.x(), up.z()), up.y()) * kRadToDeg, t);
    }
  }
  // The poses of the roll window, selected as a study selects trace rows (to 1e-9 s).
  if (s.roll >= 0 && t >= s.roll_from - 1e-9 && t <= s.roll_to + 1e-9) {
    s.roll_ratio.add(p.position, p.orientation);
    s.roll_last = t;
  }
  if (s.rest_speed >= 0 && t > s.rests_after + 1e-12) {
    observe(checks_[static_cast<std::size_t>(s.rest_speed)], v.norm(), t);
    // Tilt: turning about a horizontal axis (y is up); a spin about the vertical is not a tilt.
    observe(checks_[static_cast<std::size_t>(s.rest_tilt)], std::hypot(w.x(), w.z()), t);
  }
}

// The proxy's centre behind the plane of the contact it pressed (m; negative in front): while
// it presses, when the contact ends, and when the contact's normal turns over (a proxy through
// a thin body meets its far face).
void ExpectChecker::checkTunnelling(const sim::World& world, FingerState& s, double t) {
  Check& c = checks_[static_cast<std::size_t>(s.tunnel)];
  const sim::Vec3 proxy = world.proxyPosition(s.finger);
  const auto behindPressedPlane = [&] {
    const sim::Pose pose = world.bodyPose(s.pressed_body);
    return (pose.toWorld(s.plane_point) - proxy).dot(pose.orientation * s.plane_normal);
  };
  sim::Touch touch;
  const bool pressing = world.deepestTouch(s.finger, touch) && touch.separation <= 0.0;
  if (s.pressed_body >= 0 && (!pressing || touch.body != s.pressed_body)) {
    observe(c, behindPressedPlane(), t);  // the contact ended: which side did the proxy leave by?
    s.pressed_body = -1;
  }
  if (!pressing) return;
  const sim::Pose pose = world.bodyPose(touch.body);
  const sim::Vec3 normal = pose.orientation.inverse() * touch.normal;
  if (s.pressed_body == touch.body && normal.dot(s.plane_normal) < 0.0) observe(c, behindPressedPlane(), t);
  s.pressed_body = touch.body;
  s.plane_point = pose.orientation.inverse() * (touch.point - pose.position);
  s.plane_normal = normal;
  observe(c, (touch.point - proxy).dot(touch.normal), t);
}

std::vector<ExpectFailure> ExpectChecker::finish(const sim::World& world, bool at_scene_end) {
  for (const BodyState& s : bodies_) {
    if (!at_scene_end) break;
    if (s.body >= 0 && s.ends >= 0) observe(checks_[static_cast<std::size_t>(s.ends)], world.bodyPose(s.body).position.y(), world.time());
    // A run that ended before its roll window holds two poses leaves it unchecked; NaN (a ball
    // that did not go 1 % of its radius) fails.
    if (s.roll >= 0 && s.roll_ratio.samples() >= 2) {
      observe(checks_[static_cast<std::size_t>(s.roll)], s.roll_ratio.value(), s.roll_last);
    }
  }
  std::vector<ExpectFailure> out;
  for (const Check& c : checks_) {
    if (!c.seen) continue;
    const bool ok = c.at_most ? c.worst <= c.limit : c.worst >= c.limit;
    if (!ok || std::isnan(c.worst)) out.push_back({c.name, c.worst, c.limit, c.time});
  }
  return out;
}

nlohmann::json ExpectChecker::json() const {
  nlohmann::json out = nlohmann::json::array();
  for (const Check& c : checks_) {
    const bool ok = !c.seen || (c.at_most ? c.worst <= c.limit : c.worst >= c.limit);
    out.push_back({{"name", c.name},
                   {"limit", c.limit},
                   {"kind", c.at_most ? "at_most" : "at_least"},
                   {"worst", c.seen && std::isfinite(c.worst) ? nlohmann::json(c.worst) : nlohmann::json(nullptr)},
                   {"time_s", c.time},
                   {"checked", c.seen},
                   {"passed", ok && !std::isnan(c.worst)}});
  }
  return out;
}

}  // namespace gf::app
