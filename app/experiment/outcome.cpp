#include "app/experiment/outcome.hpp"

#include <algorithm>
#include <cstdio>
#include <numbers>

#include "app/measures/roll_ratio.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

using sim::Vec3;

constexpr double kDeg = 180.0 / std::numbers::pi;

double distanceFromZone(const TaskGoal& goal, const Vec3& p) {
  if (!goal.has_zone) return 0.0;
  const Vec3 outside = (goal.zone_min - p).cwiseMax(p - goal.zone_max).cwiseMax(0.0);
  return outside.norm();
}

}  // namespace

std::string shortText(double v, int digits) {
  if (!std::isfinite(v)) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

TrialOutcome judgeTrace(const TaskGoal& goal, const std::vector<std::string>& fingers, const CsvTable& trace) {
  TrialOutcome o;
  const std::string& b = goal.body;
  const std::vector<double>& t = trace.column("t");
  const auto& px = trace.column(b + ".px");
  const auto& py = trace.column(b + ".py");
  const auto& pz = trace.column(b + ".pz");
  const auto& qx = trace.column(b + ".qx");
  const auto& qy = trace.column(b + ".qy");
  const auto& qz = trace.column(b + ".qz");
  const auto& qw = trace.column(b + ".qw");
  o.peak_force_n = 0.0;
  std::vector<double> largest(t.size(), 0.0);  // per row, the largest finger's force
  for (const std::string& f : fingers) {
    const auto& fx = trace.column(f + ".fx");
    const auto& fy = trace.column(f + ".fy");
    const auto& fz = trace.column(f + ".fz");
    for (std::size_t i = 0; i < fx.size() && i < t.size(); ++i) largest[i] = std::max(largest[i], Vec3(fx[i], fy[i], fz[i]).norm());
  }
  for (const double f : largest) o.peak_force_n = std::max(o.peak_force_n, f);
  if (t.empty()) {
    o.ran = false;
    o.failure = "run failed (an empty trace)";
    return o;
  }
  const sim::Quat start = sim::Quat(qw[0], qx[0], qy[0], qz[0]).normalized();
  RollRatio roll(goal.roll_radius, Vec3::UnitY());
  o.max_tilt_deg = 0.0;
  double stretch = NAN;  // when the current stretch of the goal holding began
  std::size_t decided = t.size() - 1;
  std::string broken;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Vec3 p(px[i], py[i], pz[i]);
    const sim::Quat q = sim::Quat(qw[i], qx[i], qy[i], qz[i]).normalized();
    if (!p.allFinite() || !q.coeffs().allFinite()) {
      o.failure = "the body's pose is not finite at t = " + sim::numberText(t[i]) + " s";
      return o;
    }
    // Tilt: how far the turn since the start moves the vertical.
    const Vec3 up = (q * start.conjugate()) * Vec3::UnitY();
    o.max_tilt_deg = std::max(o.max_tilt_deg, std::acos(std::clamp(up.y(), -1.0, 1.0)) * kDeg);
    if (goal.max_roll_ratio) roll.add(p, q);
    if (broken.empty() && goal.max_tilt_deg && o.max_tilt_deg > *goal.max_tilt_deg) {
      broken = "tilted " + shortText(o.max_tilt_deg) + " deg (limit " + sim::numberText(*goal.max_tilt_deg) + ")";
    }
    o.end_distance_m = distanceFromZone(goal, p);
    o.end_angle_deg = goal.orientation ? q.angularDistance(*goal.orientation) * kDeg : 0.0;
    const bool holds = o.end_distance_m == 0.0 && (!goal.orientation || o.end_angle_deg <= goal.orientation_tolerance_deg) &&
                       (!goal.released || largest[i] < kReleasedForce);
    if (!holds) {
      stretch = NAN;
    } else if (std::isnan(stretch)) {
      stretch = t[i];
    }
    if (!broken.empty()) {
      decided = i;
      break;
    }
    if (!std::isnan(stretch) && t[i] - stretch >= goal.hold - 1e-9) {
      o.success = true;
      o.completion_s = stretch;
      decided = i;
      break;
    }
  }
  // The roll ratio is a whole path's (the angle turned over the distance gone): judged once, at
  // the decision, not on the first millimetres of a push.
  if (goal.max_roll_ratio && roll.travelled()) {
    o.roll_ratio = roll.value();
    if (broken.empty() && o.roll_ratio > *goal.max_roll_ratio) {
      o.success = false;
      o.completion_s = NAN;
      broken = "rolled: roll ratio " + shortText(o.roll_ratio) + " (limit " + sim::numberText(*goal.max_roll_ratio) + ")";
    }
  }
  if (!o.success) o.failure = broken.empty() ? "not reached in " + sim::numberText(t[decided]) + " s" : broken;
  return o;
}

TrialOutcome judgeTrial(const TaskGoal& goal, const std::vector<std::string>& fingers, const std::filesystem::path& dir,
                        int exit_code, double until_s) {
  TrialOutcome o;
  o.ran = false;
  if (exit_code != 0) {
    o.failure = "run failed (exit " + std::to_string(exit_code) + "; see " + (dir / "run.log").string() + ")";
    return o;
  }
  try {
    CsvTable trace = readTrace(dir);
    const std::vector<double>& t = trace.column("t");
    const auto after = std::find_if(t.begin(), t.end(), [&](double v) { return v > until_s + 1e-9; });
    const auto keep = static_cast<std::size_t>(after - t.begin());
    for (std::vector<double>& c : trace.columns) c.resize(std::min(c.size(), keep));
    return judgeTrace(goal, fingers, trace);
  } catch (const std::exception& e) {
    o.failure = std::string("run failed (") + e.what() + ")";
  }
  return o;
}

std::vector<std::string> goalTargetOverrides(const TaskGoal& goal) {
  const auto vec = [](const sim::Vec3& v) { return exactArray({v.x(), v.y(), v.z()}); };
  std::vector<std::string> out;
  if (goal.has_zone) out.push_back("targets.goal.zone={min=" + vec(goal.zone_min) + ", max=" + vec(goal.zone_max) + "}");
  if (!goal.orientation) return out;
  const sim::Quat& q = *goal.orientation;
  out.push_back("targets.goal.body=\"" + goal.body + "\"");
  out.push_back("targets.goal.orientation=" + exactArray({q.x(), q.y(), q.z(), q.w()}));
  if (goal.has_zone) out.push_back("targets.goal.position=" + vec(0.5 * (goal.zone_min + goal.zone_max)));
  return out;
}

}  // namespace gf::app
