#include "interrupt.hpp"

#include <pthread.h>
#include <unistd.h>

#include <array>
#include <cstring>

namespace pgmcl::app {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
std::atomic<bool> g_handled{false};

/// Fixed storage: the handler may only touch memory that needs no allocation or lock.
constexpr std::size_t kSlots = 64;
constexpr std::size_t kPathMax = 1024;
struct TempSlot {
  std::atomic<bool> used{false};
  char path[kPathMax] = {};
};
std::array<TempSlot, kSlots> g_temps;

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

extern "C" void on_signal(int sig) {
  if (!g_stop.exchange(true)) {
    g_signal.store(sig);
    return;
  }
  // Second signal: the user wants out now. unlink, signal and raise are async-signal-safe.
  for (TempSlot& s : g_temps) {
    if (s.used.load(std::memory_order_acquire)) ::unlink(s.path);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // reads and writes in progress carry on; loops poll the flag
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

const std::atomic<bool>& stop_flag() noexcept {
  return g_stop;
}

bool interrupted() noexcept {
  return g_stop.load(std::memory_order_relaxed);
}

int interrupt_signal() noexcept {
  return g_signal.load();
}

const char* signal_name(int sig) noexcept {
  switch (sig) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

int interrupted_exit_code() noexcept {
  const int sig = interrupt_signal();
  return 128 + (sig != 0 ? sig : SIGINT);
}

void mark_interrupt_handled() noexcept {
  g_handled.store(true);
}

bool interrupt_handled() noexcept {
  return g_handled.load();
}

Interrupted::Interrupted(int sig)
    : std::runtime_error(std::string("interrupted by ") + signal_name(sig) +
                         "; stopped before writing anything"),
      sig_(sig) {}

void check_interrupt() {
  if (interrupted()) throw Interrupted(interrupt_signal() != 0 ? interrupt_signal() : SIGINT);
}

int register_temp_file(const std::string& path) noexcept {
  if (path.size() >= kPathMax) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    TempSlot& s = g_temps[i];
    if (s.used.load(std::memory_order_acquire)) continue;
    std::memcpy(s.path, path.c_str(), path.size() + 1);
    s.used.store(true, std::memory_order_release);
    return static_cast<int>(i);
  }
  return -1;
}

void unregister_temp_file(int slot) noexcept {
  if (slot >= 0 && static_cast<std::size_t>(slot) < kSlots) {
    g_temps[static_cast<std::size_t>(slot)].used.store(false, std::memory_order_release);
  }
}

SignalBlock::SignalBlock() noexcept {
  sigset_t block;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &block, &old_);
}

SignalBlock::~SignalBlock() {
  pthread_sigmask(SIG_SETMASK, &old_, nullptr);
}

}  // namespace pgmcl::app
