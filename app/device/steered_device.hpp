// A finger's device that the browser view (or a `move` posted to it) steers while a realtime
// session runs: the scene's track until the first move, then straight lines to each target;
// its orientation stays the track's (for a `web` device its tilt) whatever the moves.
// The server thread posts targets; the haptic thread samples without blocking or allocating.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include "sim/scene/device.hpp"

namespace gf::app {

class SteeredDevice final : public sim::DeviceSource {
 public:
  /// `track`: the scene's device track (kept by reference: it outlives the run). `web`: the
  /// finger's device is the page's pointer (`[fingers.NAME.device] web = true`).
  SteeredDevice(const sim::DeviceTrack& track, bool web) : track_(track), web_(web) {}

  /// From the next step on, moves the device from where it is straight to `target` (m) over
  /// `seconds` (0: at once). `number`: the move's number in the run (ServedRun numbers every
  /// device's moves in one increasing sequence; 0 for none), reported through moveMarks. Any
  /// thread but the haptic one.
  void moveTo(const sim::Vec3& target, double seconds, long number = 0);

  sim::DeviceSample sample(double t) override;
  /// The browser's pointer renders no force: the force the World sends is the force told.
  sim::Vec3 feedback(double, const sim::DeviceFeedback& f) override { return f.force; }

  bool web() const { return web_; }
  /// Moves taken by the haptic thread so far. Any thread.
  long moves() const { return moves_.load(std::memory_order_relaxed); }
  /// Moves whose device reached its target so far (a move of 0 s at once). Any thread.
  long arrivals() const { return arrivals_.load(std::memory_order_relaxed); }
  /// The number of the newest move taken (0: none; a move posted over one not yet taken
  /// replaces it, and both count as taken with it), whether the device has reached its target,
  /// and the number of the first move it has not reached since it last did: a move replaced
  /// before its device got there counts as reached with the move that replaced it. Haptic
  /// thread (they change there).
  long takenNumber() const { return taken_number_; }
  bool arrived() const { return arrived_; }
  long unreachedFrom() const { return unreached_from_; }
  /// The number of the first move posted and not yet taken (0: none). Any thread.
  long firstPending() const { return first_pending_.load(std::memory_order_acquire); }

 private:
  const sim::DeviceTrack& track_;
  const bool web_;
  // Posted by the server, taken by the haptic thread (try_lock: it never waits).
  std::mutex mutex_;
  std::atomic<bool> posted_{false};
  sim::Vec3 posted_target_ = sim::Vec3::Zero();
  double posted_seconds_ = 0.0;
  long posted_number_ = 0;
  std::atomic<long> first_pending_{0};  // the first move posted since the last one taken (0: none)
  // Haptic thread only.
  bool steered_ = false;
  sim::Vec3 from_ = sim::Vec3::Zero(), to_ = sim::Vec3::Zero(), last_ = sim::Vec3::Zero();
  double t0_ = 0.0, t1_ = 0.0;
  bool arrived_ = true;
  long taken_number_ = 0, unreached_from_ = 0;
  std::atomic<long> moves_{0}, arrivals_{0};
};

/// What a state shows of the numbered moves (sim::Snapshot's moves_taken and moves_arrived):
/// the newest move that, with every earlier one, the loop has taken (below the first move still
/// posted to any device), and the newest that, with every earlier one, its device has reached
/// (below, too, the first move not reached of any device on its way,
/// SteeredDevice::unreachedFrom). Haptic thread.
struct MoveMarks {
  long taken = 0, arrived = 0;
};
MoveMarks moveMarks(const std::vector<std::unique_ptr<SteeredDevice>>& devices);

}  // namespace gf::app
