// Ctrl-C (SIGINT) and SIGTERM for the commands that stop at a step boundary and finish their
// outputs (`run`, `live`).
#pragma once

#include <csignal>

#include <pthread.h>

namespace gf::app {

/// While alive, SIGINT and SIGTERM are blocked on this thread, so the threads it starts meanwhile
/// never take them (they stay with the thread that records them).
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t both;
    sigemptyset(&both);
    sigaddset(&both, SIGINT);
    sigaddset(&both, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &both, &old_);
  }
  ~SignalsBlocked() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t old_{};
};

/// While alive, SIGINT and SIGTERM record their signal (the first one) instead of ending the
/// process; each handler resets itself, so a second Ctrl-C ends the process at once. A signal the
/// process was started ignoring stays ignored. Blocking reads are not restarted after the signal
/// (a `live` session waiting on its input stops). One at a time.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

/// The signal recorded since the last InterruptScope began (SIGINT or SIGTERM), 0 if none.
/// Safe to poll from any thread.
int interruptSignal();

/// The shell's exit status for a run stopped by interruptSignal(): 128 + the signal (130, 143).
int interruptedStatus();

}  // namespace gf::app
