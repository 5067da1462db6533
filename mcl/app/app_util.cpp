#include "app_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "pgmcl/io/cli_errors.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::app {

void not_available(std::string_view command, std::string_view why) {
  throw io::NotAvailableError(std::string(command) + ": not available yet (" + std::string(why) +
                              ")");
}

std::filesystem::path ensure_directory(const std::string& dir) {
  std::error_code ec;
  const std::filesystem::path p(dir);
  std::filesystem::create_directories(p, ec);
  if (ec || !std::filesystem::is_directory(p)) {
    throw io::IoError(dir + ": cannot create output directory" +
                      (ec ? " (" + ec.message() + ")" : std::string(" (not a directory)")));
  }
  return p;
}

void ensure_parent_directory(const std::string& file) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  if (!parent.empty()) ensure_directory(parent.string());
}

bool is_carmen_path(const std::string& path) {
  std::string p = path;
  if (p.size() > 3 && p.compare(p.size() - 3, 3, ".gz") == 0) p.resize(p.size() - 3);
  auto ends = [&p](const char* ext) {
    const std::string e(ext);
    return p.size() > e.size() && p.compare(p.size() - e.size(), e.size(), e) == 0;
  };
  return ends(".log") || ends(".clf");
}

io::Trajectory load_truth(const std::string& path) {
  if (!is_carmen_path(path)) return io::read_tum(path);
  const io::CarmenLog log = read_log(path, {}, false);
  for (const auto& s : log.scans) {
    if (s.has_poses) return io::scan_truth(log, s.message);
  }
  throw io::UsageError(path + ": no laser scans with poses to take as ground truth");
}

namespace {

CLI::Validator number_check(bool (*ok)(double), const char* rule, const char* name) {
  return CLI::Validator(
      [ok, rule](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v)) {
          return "expected a number, got '" + text + "'";
        }
        return ok(v) ? std::string() : "must be " + std::string(rule) + ", got " + text;
      },
      rule, name);
}

}  // namespace

CLI::Validator positive() {
  return number_check([](double v) { return v > 0.0; }, "> 0", "POSITIVE");
}

CLI::Validator non_negative() {
  return number_check([](double v) { return v >= 0.0; }, ">= 0", "NONNEGATIVE");
}

io::CarmenLog read_log(const std::string& path, const io::CarmenReadOptions& opt, bool strict) {
  io::CarmenReadOptions o = opt;
  o.strict = strict;
  io::CarmenLog log = io::read_carmen(path, o);
  const io::ParseReport& r = log.report;
  if (r.malformed > 0) {
    // Every dropped line by number (up to a screenful): a user fixing a log needs all of
    // them, not just the first.
    constexpr std::size_t kListed = 20;
    std::fprintf(stderr,
                 "pgmcl: warning: %s: dropped %zu malformed line(s) (use --strict to make this an "
                 "error):\n",
                 path.c_str(), r.malformed);
    const std::size_t listed = std::min(kListed, r.malformed_lines.size());
    for (std::size_t k = 0; k < listed; ++k) {
      const io::LineIssue& i = r.malformed_lines[k];
      std::fprintf(stderr, "  %s:%zu: %s: %s\n", path.c_str(), i.line, i.field.c_str(),
                   i.message.c_str());
    }
    if (r.malformed > listed) std::fprintf(stderr, "  ... %zu more\n", r.malformed - listed);
  }
  return log;
}

std::string format_seconds(double s) {
  char buf[64];
  if (s < 1.0) {
    std::snprintf(buf, sizeof buf, "%.2f ms", s * 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  }
  return buf;
}

}  // namespace pgmcl::app
