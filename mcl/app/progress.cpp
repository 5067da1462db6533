#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace pgmcl::app {

Progress::Progress(std::ostream& out, Mode mode, std::string label, std::size_t total,
                   ProgressOptions options)
    : out_(&out),
      mode_(mode),
      label_(std::move(label)),
      total_(total),
      options_(options),
      start_(std::chrono::steady_clock::now()),
      next_percent_(options.percent_step) {}

Progress Progress::on_stderr(std::string label, std::size_t total, bool quiet,
                             ProgressOptions options) {
  Mode mode = Mode::kPlain;
  if (quiet) {
    mode = Mode::kSilent;
  } else if (::isatty(STDERR_FILENO) != 0) {
    mode = Mode::kTerminal;
  }
  return Progress(std::cerr, mode, std::move(label), total, options);
}

double Progress::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string Progress::status(std::size_t done, std::string_view extra) const {
  std::string s = label_ + ": " + std::to_string(done);
  if (total_ > 0) {
    char pct[32];
    std::snprintf(pct, sizeof pct, " (%.0f%%)", 100.0 * static_cast<double>(done) / total_);
    s.append("/").append(std::to_string(total_)).append(pct);
  }
  char t[32];
  std::snprintf(t, sizeof t, " %.1f s", elapsed_s());
  s += t;
  if (!extra.empty()) {
    s += "  ";
    s += extra;
  }
  return s;
}

void Progress::update(std::size_t done, std::string_view extra) {
  if (finished_ || mode_ == Mode::kSilent) return;
  done_ = done;
  const double now = elapsed_s();
  if (mode_ == Mode::kTerminal) {
    if (now - last_emit_s_ < options_.redraw_s && done != total_) return;
    last_emit_s_ = now;
    std::string bar;
    if (total_ > 0) {
      const double frac = std::clamp(static_cast<double>(done) / total_, 0.0, 1.0);
      const int filled = static_cast<int>(std::lround(frac * options_.bar_width));
      bar.append("[").append(static_cast<std::size_t>(filled), '#');
      bar.append(static_cast<std::size_t>(options_.bar_width - filled), '-').append("] ");
    }
    // \r redraws in place; \x1b[K clears what a longer previous line left behind.
    *out_ << '\r' << bar << status(done, extra) << "\x1b[K" << std::flush;
    return;
  }
  const double percent = total_ > 0 ? 100.0 * static_cast<double>(done) / total_ : 0.0;
  const bool step_due = total_ > 0 && percent + 1e-9 >= next_percent_;
  const bool time_due = now - last_emit_s_ >= options_.interval_s && last_emit_s_ > -1e8;
  if (!step_due && !time_due) {
    if (last_emit_s_ < -1e8) last_emit_s_ = now;  // the interval counts from the first update
    return;
  }
  if (step_due) {
    while (next_percent_ <= percent + 1e-9) next_percent_ += options_.percent_step;
  }
  last_emit_s_ = now;
  *out_ << status(done, extra) << '\n' << std::flush;
}

void Progress::finish(std::string_view summary) {
  if (finished_) return;
  finished_ = true;
  if (mode_ == Mode::kSilent) return;
  if (mode_ == Mode::kTerminal) *out_ << '\r' << "\x1b[K";
  *out_ << label_ << ": done, " << done_;
  if (total_ > 0) *out_ << '/' << total_;
  *out_ << " in ";
  char t[32];
  std::snprintf(t, sizeof t, "%.1f s", elapsed_s());
  *out_ << t;
  if (!summary.empty()) *out_ << "  " << summary;
  *out_ << '\n' << std::flush;
}

}  // namespace pgmcl::app
