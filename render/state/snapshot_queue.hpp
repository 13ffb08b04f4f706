// The realtime frames' ordered handoff from the haptic thread to the render thread (frames
// written to files, no viewer).
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

#include "render/state/one_writer.hpp"
#include "sim/assert.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

// First in, first out: the writer fills the free slot (back()) and publishes it; the reader
// takes the oldest state published (update()) and reads it (front()) until its next update().
// Neither side ever waits: when every slot but the reader's is published, back() is null and
// the writer's state is dropped. One writer thread and one reader thread (asserted for the
// writer). A slot's vectors keep their capacity, so a slot allocates only while it grows.
class SnapshotQueue {
 public:
  // `slots` ≥ 2: the reader's and at least one the writer may fill.
  explicit SnapshotQueue(std::size_t slots) : slots_(slots) { GF_ASSERT(slots >= 2); }

  sim::Snapshot* back() {
    writer_.check();
    const std::size_t w = write_.load(std::memory_order_relaxed);
    // The reader holds slot (read_ - 1) while it draws; the writer stays off it.
    if (w + 1 - read_.load(std::memory_order_acquire) >= slots_.size()) return nullptr;
    return &slots_[w % slots_.size()];
  }
  void publish() {
    writer_.check();
    write_.store(write_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  // States published and not taken yet; the reader's.
  std::size_t waiting() const {
    return write_.load(std::memory_order_acquire) - read_.load(std::memory_order_relaxed);
  }
  bool update() {
    const std::size_t r = read_.load(std::memory_order_relaxed);
    if (r == write_.load(std::memory_order_acquire)) return false;
    front_ = r % slots_.size();
    read_.store(r + 1, std::memory_order_release);
    return true;
  }
  const sim::Snapshot& front() const { return slots_[front_]; }

 private:
  std::vector<sim::Snapshot> slots_;
  std::size_t front_ = 0;
  std::atomic<std::size_t> write_{0}, read_{0};
  OneWriter writer_;
};

}  // namespace gf::render
