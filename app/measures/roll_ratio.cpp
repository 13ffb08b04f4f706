#include "app/measures/roll_ratio.hpp"

#include <cmath>

namespace gf::app {

void RollRatio::add(const sim::Vec3& position, const sim::Quat& orientation) {
  const sim::Quat q = orientation.normalized();
  if (samples_ == 0) first_ = position;
  else angle_ += Eigen::AngleAxisd(q * last_orientation_.inverse()).angle();
  last_ = position;
  last_orientation_ = q;
  ++samples_;
}

double RollRatio::distance() const {
  const sim::Vec3 d = last_ - first_;
  return (d - d.dot(axis_) * axis_).norm();
}

bool RollRatio::travelled() const { return samples_ >= 2 && distance() >= kMinTravel * radius_; }

double RollRatio::value() const { return travelled() ? angle_ * radius_ / distance() : NAN; }

}  // namespace gf::app
