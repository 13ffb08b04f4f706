#include "app/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace gf::app {
namespace {

std::atomic<int> g_signal{0};

extern "C" void onInterrupt(int signal) { g_signal.store(signal, std::memory_order_relaxed); }

struct sigaction g_old_int {}, g_old_term {};

}  // namespace

InterruptScope::InterruptScope() {
  g_signal.store(0);
  struct sigaction a {};
  a.sa_handler = onInterrupt;
  a.sa_flags = SA_RESETHAND;  // no SA_RESTART: a read waiting for input returns
  sigemptyset(&a.sa_mask);
  sigaction(SIGINT, &a, &g_old_int);
  sigaction(SIGTERM, &a, &g_old_term);
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
