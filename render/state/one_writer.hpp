// The haptic thread's claim on a realtime handoff (TripleBuffer, SnapshotQueue): one thread
// writes, and it is the first that calls.
#pragma once

#include <thread>

#include "sim/assert.hpp"

namespace gf::render {

class OneWriter {
 public:
  // Asserts that the calling thread is the writer; the first caller becomes it.
  void check() {
    if (id_ == std::thread::id()) id_ = std::this_thread::get_id();
    GF_ASSERT(id_ == std::this_thread::get_id() && "one thread (the haptic thread) publishes realtime snapshots");
  }

 private:
  std::thread::id id_;
};

}  // namespace gf::render
