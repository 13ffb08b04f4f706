// The realtime frames' handoff from the haptic thread to the render thread.
#pragma once

#include <atomic>

#include "render/state/one_writer.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

// Latest-value handoff: the writer fills `back`, then swaps it with `middle`; the reader swaps
// `middle` with `front` when it holds something new. Neither side ever waits. One writer
// thread and one reader thread (asserted for the writer).
class TripleBuffer {
 public:
  sim::Snapshot& back() {
    writer_.check();
    return slots_[back_];
  }
  void publish() {
    writer_.check();
    back_ = middle_.exchange(back_ | kFresh) & kIndex;
  }
  // Whether the writer published since the last update(); the reader's.
  bool fresh() const { return (middle_.load() & kFresh) != 0; }
  bool update() {
    if (!(middle_.load() & kFresh)) return false;
    front_ = middle_.exchange(front_) & kIndex;
    return true;
  }
  const sim::Snapshot& front() const { return slots_[front_]; }

 private:
  static constexpr int kFresh = 4, kIndex = 3;
  sim::Snapshot slots_[3];
  int back_ = 0, front_ = 1;
  std::atomic<int> middle_{2};
  OneWriter writer_;
};

}  // namespace gf::render
