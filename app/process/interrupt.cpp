#include "app/process/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace gf::app {
namespace {

std::atomic<int> g_signal{0};

// The first signal is kept: SIGTERM then Ctrl-C still ends with SIGTERM's status.
extern "C" void onInterrupt(int signal) {
  int none = 0;
  g_signal.compare_exchange_strong(none, signal, std::memory_order_relaxed);
}

struct sigaction g_old_int {}, g_old_term {};

}  // namespace

InterruptScope::InterruptScope() {
  g_signal.store(0);
  struct sigaction a {};
  a.sa_handler = onInterrupt;
  a.sa_flags = SA_RESETHAND;  // no SA_RESTART: a read waiting for input returns
  sigemptyset(&a.sa_mask);
  // A signal the process was started ignoring (a background job, nohup) stays ignored.
  sigaction(SIGINT, nullptr, &g_old_int);
  sigaction(SIGTERM, nullptr, &g_old_term);
  if (g_old_int.sa_handler != SIG_IGN) sigaction(SIGINT, &a, nullptr);
  if (g_old_term.sa_handler != SIG_IGN) sigaction(SIGTERM, &a, nullptr);
}

InterruptScope::~InterruptScope() {
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
}

int interruptSignal() { return g_signal.load(std::memory_order_relaxed); }

int interruptedStatus() {
  const int s = interruptSignal();
  return 128 + (s != 0 ? s : SIGINT);
}

}  // namespace gf::app
