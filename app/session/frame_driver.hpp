// The haptic side of rendering: takes a frame at every 1/fps of simulated time and hands it to
// the render thread, and applies the settings the overlay's widgets change.
#pragma once

#include <functional>
#include <vector>

#include "render/render_thread.hpp"
#include "sim/loop/haptic_loop.hpp"
#include "sim/world/world.hpp"

namespace gf::app {

/// A settings change made through the overlay, as applied to the simulation.
struct AppliedChange {
  double time = 0.0;  ///< s: applied from the step after this time
  sim::SettingsCommand command;
};

/// Haptic thread only. Offline, the frame at k/fps is interpolated between the two steps around
/// it, so frames fall on exact times whatever the haptic rate; frames that carry scripted input
/// wait for the overlay's answer so the change lands on the same step in every run. Realtime,
/// the latest state is published at each frame time and never waits.
class FrameDriver {
 public:
  FrameDriver(render::RenderThread& renderer, double fps, bool realtime,
              const std::vector<view::WidgetAction>& actions, const sim::LiveTimings* live);
  /// Frame 0, before the first step.
  void start(sim::World& world);
  /// After every step of `dt` seconds. Realtime, `input`: the step took input from a viewer (a
  /// move posted from the browser view): its state is published now and the render thread woken
  /// to draw it, not at the next frame time, so the move is in the next frame drawn and sent.
  void afterStep(sim::World& world, double dt, bool input = false);
  /// Realtime: called on each published state after the World's snapshot, to add what the
  /// World does not know (the browser view's move numbers, ServedRun::markMoves). Haptic
  /// thread; must not block.
  void setMarks(std::function<void(sim::Snapshot&)> marks) { marks_ = std::move(marks); }
  long frames() const { return next_frame_; }
  const std::vector<AppliedChange>& changes() const { return changes_; }

 private:
  double frameTime(long k) const { return static_cast<double>(k) / fps_; }
  void apply(sim::World& world, const std::vector<sim::SettingsCommand>& commands);
  void publishLatest(const sim::World& world, bool input = false);
  bool isSyncFrame(long k) const;

  render::RenderThread& renderer_;
  double fps_;
  bool realtime_;
  std::vector<long> sync_first_frames_;  // first frame of each scripted action
  const sim::LiveTimings* live_;
  long next_frame_ = 0;
  sim::Snapshot before_, after_, frame_;
  std::vector<AppliedChange> changes_;
  std::function<void(sim::Snapshot&)> marks_;
};

}  // namespace gf::app
