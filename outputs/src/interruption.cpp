// interruption.cpp — the SIGINT / SIGTERM flag and its check (interruption.hpp).
#include "shadowref/outputs/interruption.hpp"

#include <atomic>
#include <csignal>
#include <cstring>
#include <string>

namespace shadowref::outputs {
namespace {

// Lock-free on every platform we build for, hence safe to store from a signal handler.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_signal(int sig) {
  int none = 0;
  if (!g_signal.compare_exchange_strong(none, sig)) {
    // The second signal: the default action, now (signal() and raise() are async-signal-safe).
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

std::string signal_name(int sig) {
  if (sig == SIGINT) return "SIGINT";
  if (sig == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(sig);
}

}  // namespace

std::string Interrupted::message() const {
  return "interrupted by " + signal_name(signal_) +
         ": stopped; what was being written is removed, finished results stay (a rerun resumes from the complete reference "
         "cache entries)";
}

void install_interrupt_handlers() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int interrupt_signal() { return g_signal.load(std::memory_order_relaxed); }

void throw_if_interrupted() {
  if (const int sig = interrupt_signal()) throw Interrupted(sig);
}

}  // namespace shadowref::outputs
