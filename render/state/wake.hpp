// The render thread's realtime alarm: posted by every publish (haptic thread) and by finish(),
// slept on by the render thread until its next frame is due.
#pragma once

#include <cerrno>
#include <chrono>

#include <semaphore.h>
#include <time.h>

namespace gf::render {

// A semaphore's post is an atomic add and, when the thread sleeps, a futex wake: no lock the
// sleeping thread could hold, so the haptic thread never waits on the render thread.
class Wake {
 public:
  Wake() { sem_init(&sem_, 0, 0); }
  ~Wake() { sem_destroy(&sem_); }
  Wake(const Wake&) = delete;
  Wake& operator=(const Wake&) = delete;

  void post() { sem_post(&sem_); }

  // Sleeps until `t` or a post, then takes every post made meanwhile.
  void sleepUntil(std::chrono::steady_clock::time_point t) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
    const timespec at{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
    while (sem_clockwait(&sem_, CLOCK_MONOTONIC, &at) != 0) {  // steady_clock is CLOCK_MONOTONIC
      if (errno != EINTR) return;                               // ETIMEDOUT
    }
    while (sem_trywait(&sem_) == 0) {
    }
  }

 private:
  sem_t sem_;
};

}  // namespace gf::render
