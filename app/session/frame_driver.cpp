#include "app/session/frame_driver.hpp"

#include <cmath>

namespace gf::app {
namespace {

constexpr double kTimeEps = 1e-9;  // s: a step this close to a frame time is on it

}  // namespace

FrameDriver::FrameDriver(render::RenderThread& renderer, double fps, bool realtime,
                         const std::vector<view::WidgetAction>& actions, const sim::LiveTimings* live)
    : renderer_(renderer), fps_(fps), realtime_(realtime), live_(live) {
  for (const view::WidgetAction& a : actions) {
    sync_first_frames_.push_back(static_cast<long>(std::ceil(a.time * fps - kTimeEps)));
  }
}

bool FrameDriver::isSyncFrame(long k) const {
  for (long first : sync_first_frames_) {
    if (k >= first && k < first + view::kActionFrames) return true;
  }
  return false;
}

void FrameDriver::apply(sim::World& world, const std::vector<sim::SettingsCommand>& commands) {
  for (const sim::SettingsCommand& c : commands) {
    world.setPatchSettings(c.finger, c.patch);
    changes_.push_back({world.time(), c});
  }
}

// Realtime: the latest state, written straight into the render thread's free slot.
void FrameDriver::publishLatest(const sim::World& world, bool input) {
  renderer_.publishLatest(
      [&](sim::Snapshot& slot) {
        world.snapshot(slot);
        slot.timings = live_ ? live_->summary() : sim::HapticTimings{};
        if (marks_) marks_(slot);
      },
      input);
}

void FrameDriver::start(sim::World& world) {
  if (realtime_) {
    publishLatest(world);
  } else {
    world.snapshot(frame_);
    apply(world, renderer_.submitFrame(frame_, isSyncFrame(0)));
  }
  next_frame_ = 1;
}

void FrameDriver::afterStep(sim::World& world, double dt, bool input) {
  const double t = world.time();
  if (realtime_) {
    const bool frame_time = t + kTimeEps >= frameTime(next_frame_);
    if (!input && !frame_time) return;
    while (t + kTimeEps >= frameTime(next_frame_)) ++next_frame_;
    publishLatest(world, input);
    if (!frame_time) return;
    apply(world, renderer_.takeCommands());
    return;
  }
  // Keep the state before a step that will cross the next frame time.
  if (t + kTimeEps < frameTime(next_frame_)) {
    if (t + dt + kTimeEps >= frameTime(next_frame_)) world.snapshot(before_);
    return;
  }
  world.snapshot(after_);
  if (live_) after_.timings = live_->summary();
  while (t + kTimeEps >= frameTime(next_frame_)) {
    const double ft = frameTime(next_frame_);
    if (std::abs(t - ft) <= kTimeEps) {
      frame_ = after_;
      frame_.time = ft;
    } else {
      sim::interpolateSnapshot(before_, after_, ft, frame_);
    }
    apply(world, renderer_.submitFrame(frame_, isSyncFrame(next_frame_)));
    ++next_frame_;
  }
  if (t + dt + kTimeEps >= frameTime(next_frame_)) before_ = after_;
}

}  // namespace gf::app
