#pragma once
/// Progress reporting for long runs: a redrawn bar on a terminal, plain periodic lines
/// (every `percent_step` % or every `interval_s` seconds) when the output is a file or a
/// pipe, so logs stay readable.

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <string>
#include <string_view>

namespace pgmcl::app {

struct ProgressOptions {
  double percent_step = 10.0;  ///< plain mode: a line each time this many % have passed
  double interval_s = 10.0;    ///< plain mode: a line at least this often (seconds)
  double redraw_s = 0.1;       ///< terminal mode: minimum seconds between redraws
  int bar_width = 30;          ///< terminal mode: characters in the bar
};

class Progress {
 public:
  enum class Mode { kTerminal, kPlain, kSilent };

  /// `out` must outlive the Progress. `total` 0 means unknown (counts only).
  Progress(std::ostream& out, Mode mode, std::string label, std::size_t total,
           ProgressOptions options = {});
  /// A progress on std::cerr: terminal mode when stderr is a terminal, plain otherwise.
  [[nodiscard]] static Progress on_stderr(std::string label, std::size_t total, bool quiet = false,
                                          ProgressOptions options = {});

  /// Reports `done` items (monotone); `extra` is appended (e.g. "ATE 0.05 m").
  void update(std::size_t done, std::string_view extra = {});
  /// Final line (ends the bar with a newline in terminal mode). Idempotent.
  void finish(std::string_view summary = {});

 private:
  [[nodiscard]] double elapsed_s() const;
  [[nodiscard]] std::string status(std::size_t done, std::string_view extra) const;

  std::ostream* out_;
  Mode mode_;
  std::string label_;
  std::size_t total_;
  ProgressOptions options_;
  std::chrono::steady_clock::time_point start_;
  double last_emit_s_ = -1e9;
  double next_percent_ = 0.0;
  std::size_t done_ = 0;
  bool finished_ = false;
};

}  // namespace pgmcl::app
