#pragma once
/// SIGINT and SIGTERM. The first one asks the running command to stop cleanly: long loops
/// poll check_interrupt() (or hand stop_flag() to pgmcl::replay), the command writes what it
/// promises for a stopped run (localize: the trajectory so far, `complete: false`) or nothing,
/// and exits 128 + signal (130, 143). A second one ends the process at once, after removing
/// the temporary files registered here, so an impatient user never finds a half-written file.

#include <atomic>
#include <csignal>
#include <stdexcept>
#include <string>

namespace pgmcl::app {

/// Installs the handlers (main does, once).
void install_interrupt_handlers();

/// Set by the first SIGINT / SIGTERM; pgmcl::replay::ReplayHooks::stop polls it.
[[nodiscard]] const std::atomic<bool>& stop_flag() noexcept;
[[nodiscard]] bool interrupted() noexcept;
/// The signal received (SIGINT, SIGTERM), 0 if none.
[[nodiscard]] int interrupt_signal() noexcept;
/// "SIGINT", "SIGTERM".
[[nodiscard]] const char* signal_name(int sig) noexcept;
/// 128 + the signal (130 for SIGINT, 143 for SIGTERM).
[[nodiscard]] int interrupted_exit_code() noexcept;
/// The command has dealt with the signal itself (localize: a complete run written before
/// the signal came stays exit 0); otherwise main turns a 0 after a signal into 130 / 143.
void mark_interrupt_handled() noexcept;
[[nodiscard]] bool interrupt_handled() noexcept;

/// A command stopped by a signal before it wrote anything; run_reporting_errors reports it
/// and exits 128 + signal.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int sig);
  [[nodiscard]] int signal() const noexcept { return sig_; }

 private:
  int sig_;
};

/// Throws Interrupted once a signal arrived.
void check_interrupt();

/// Temporary files the second signal removes before the process dies. Returns a slot for
/// unregister_temp_file (or -1 when the small fixed table is full: the file is then only
/// removed by its owner).
int register_temp_file(const std::string& path) noexcept;
void unregister_temp_file(int slot) noexcept;

/// Holds SIGINT and SIGTERM back while alive (the renames of OutputFiles::commit), so a
/// signal cannot land between two of them; a held signal is delivered on destruction.
class SignalBlock {
 public:
  SignalBlock() noexcept;
  ~SignalBlock();
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t old_{};
};

}  // namespace pgmcl::app
