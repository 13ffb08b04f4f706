#include "app/device/steered_device.hpp"

#include <algorithm>
#include <limits>

namespace gf::app {

void SteeredDevice::moveTo(const sim::Vec3& target, double seconds, long number) {
  std::lock_guard lock(mutex_);
  posted_target_ = target;
  posted_seconds_ = seconds;
  if (!posted_.load(std::memory_order_relaxed)) first_pending_.store(number, std::memory_order_release);
  posted_number_ = number;
  posted_.store(true, std::memory_order_release);
}

sim::DeviceSample SteeredDevice::sample(double t) {
  if (posted_.load(std::memory_order_acquire)) {
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (lock.owns_lock()) {  // otherwise taken at the next step
      from_ = steered_ ? last_ : track_.sample(t).position;
      to_ = posted_target_;
      t0_ = t;
      t1_ = t + posted_seconds_;
      steered_ = true;
      if (arrived_) unreached_from_ = first_pending_.load(std::memory_order_relaxed);  // else the move cut short stays unreached
      first_pending_.store(0, std::memory_order_release);
      arrived_ = false;
      taken_number_ = posted_number_;
      posted_.store(false, std::memory_order_relaxed);
      moves_.fetch_add(1, std::memory_order_relaxed);
    }
  }
  if (!steered_) {
    const sim::DeviceSample s = track_.sample(t);
    last_ = s.position;
    return s;
  }
  sim::DeviceSample s;
  s.orientation = track_.sample(t).orientation;  // the page moves the position only
  if (t >= t1_) {
    s.position = to_;
    if (!arrived_) {
      arrived_ = true;
      arrivals_.fetch_add(1, std::memory_order_relaxed);
    }
  } else {
    const double span = t1_ - t0_;
    s.position = from_ + (to_ - from_) * ((t - t0_) / span);
    s.velocity = (to_ - from_) / span;
  }
  last_ = s.position;
  return s;
}

MoveMarks moveMarks(const std::vector<std::unique_ptr<SteeredDevice>>& devices) {
  long taken = 0, all_taken = std::numeric_limits<long>::max(), reached = all_taken;
  for (const auto& d : devices) {
    taken = std::max(taken, d->takenNumber());
    if (const long pending = d->firstPending(); pending > 0) all_taken = std::min(all_taken, pending - 1);
    if (!d->arrived()) reached = std::min(reached, d->unreachedFrom() - 1);
  }
  taken = std::min(taken, all_taken);
  return {taken, std::min(taken, reached)};
}

}  // namespace gf::app
