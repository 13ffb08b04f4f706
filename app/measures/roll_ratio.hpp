// The roll ratio of a body along its path: how far it turned against how far it went, 1 for
// rolling without slipping and 0 for sliding. The studies' roll_ratio measure (from trace.csv)
// and [expect]'s max_roll_ratio (from the World, step by step) both take it here, so a scene's
// check and a study of it agree on the same samples.
#pragma once

#include "sim/math.hpp"

namespace gf::app {

/// A body's poses over a window, in time order: the angle it turned (the sum of the rotations
/// between successive poses, so turning back and forth adds up) times its radius, over the
/// distance its centre went across `axis` (first pose to last). Any thread; does not allocate.
class RollRatio {
 public:
  /// Least travel, as a share of the radius, for a roll ratio: a body that went less rests,
  /// and the ratio of its creep would mean nothing.
  static constexpr double kMinTravel = 0.01;

  /// `radius` of the body (m); `axis` (unit): the distance is taken across it (the vertical:
  /// along the ground).
  RollRatio(double radius, const sim::Vec3& axis) : radius_(radius), axis_(axis) {}
  /// The body's pose at the next sample; the orientation need not be normalised.
  void add(const sim::Vec3& position, const sim::Quat& orientation);
  int samples() const { return samples_; }
  double angle() const { return angle_; }  ///< rad turned
  double distance() const;                 ///< m travelled across the axis, first pose to last
  /// At least two poses, and the centre went at least kMinTravel of the radius.
  bool travelled() const;
  /// angle × radius / distance; NaN unless travelled().
  double value() const;

 private:
  double radius_;
  sim::Vec3 axis_;
  int samples_ = 0;
  double angle_ = 0.0;
  sim::Vec3 first_ = sim::Vec3::Zero(), last_ = sim::Vec3::Zero();
  sim::Quat last_orientation_ = sim::Quat::Identity();
};

}  // namespace gf::app
