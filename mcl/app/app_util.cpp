#include "app_util.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "cli_errors.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::app {

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

io::Trajectory load_truth(const std::string& path) {
  if (!io::is_carmen_path(path)) return io::read_tum(path);
  return io::log_truth(read_log(path, {}, false), path);
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

std::string format_g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

/// "in [0, 1)", ">= 0", "a whole number >= 1".
std::string describe_rule(const ValueRule& r) {
  const std::string kind = r.integer ? "a whole number " : "";
  if (std::isinf(r.hi)) return kind + (r.lo_open ? "> " : ">= ") + format_g(r.lo);
  if (std::isinf(r.lo)) return kind + (r.hi_open ? "< " : "<= ") + format_g(r.hi);
  return kind + "in " + (r.lo_open ? "(" : "[") + format_g(r.lo) + ", " + format_g(r.hi) +
         (r.hi_open ? ")" : "]");
}

}  // namespace

std::vector<double> parse_checked_list(std::string_view text, std::string_view option,
                                       std::initializer_list<ValueRule> rules,
                                       std::size_t required) {
  std::string form;
  std::size_t k = 0;
  for (const ValueRule& r : rules) {
    if (k == required && k > 0) form += "[";
    if (k > 0) form += ",";
    form += r.name;
    ++k;
  }
  if (required < rules.size()) form += "]";
  // parse_number_list takes the allowed counts as an initializer_list: required .. size,
  // which covers every use (at most three numbers, at most two of them optional).
  if (rules.size() > 3 || required == 0 || required > rules.size()) {
    throw std::logic_error("parse_checked_list: unsupported rule list");
  }
  const std::size_t n = rules.size();
  const std::vector<double> v =
      io::parse_number_list(text, option, {required, std::min(required + 1, n), n}, form);
  auto rule = rules.begin();
  for (const double x : v) {
    const ValueRule& r = *rule++;
    const bool below = r.lo_open ? !(x > r.lo) : !(x >= r.lo);
    const bool above = r.hi_open ? !(x < r.hi) : !(x <= r.hi);
    if (below || above || (r.integer && x != std::floor(x))) {
      throw io::UsageError(std::string(option) + ": " + std::string(r.name) + " must be " +
                           describe_rule(r) + ", got " + format_g(x) + " (in '" +
                           std::string(text) + "')");
    }
  }
  return v;
}

DeprecatedName::DeprecatedName(CLI::App& sub, CLI::Option* current, const std::string& old_name,
                               std::string& target)
    : old_name_(old_name), new_name_(current->get_name()) {
  CLI::Option* old = sub.add_option(old_name, target, "Deprecated name of " + new_name_)
                         ->group("Deprecated")
                         ->excludes(current);
  old_ = old;
}

const std::string& DeprecatedName::used() const noexcept {
  return old_ != nullptr && old_->count() > 0 ? old_name_ : new_name_;
}

void DeprecatedName::note_if_used() const {
  if (old_ != nullptr && old_->count() > 0) {
    std::fprintf(stderr, "pgmcl: warning: %s is deprecated, use %s\n", old_name_.c_str(),
                 new_name_.c_str());
  }
}

CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
  const std::string rule =
      "a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, rule](std::string& text) -> std::string {
        std::uint64_t v = 0;
        const char* first = text.data();
        const char* last = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(first, last, v);
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits || ec != std::errc() || ptr != last) {
          return "must be " + rule + ", got '" + text + "'";
        }
        return v >= lo && v <= hi ? std::string() : "must be " + rule + ", got " + text;
      },
      rule, "WHOLE_NUMBER");
}

CLI::Option* add_seed_option(CLI::App& sub, std::uint64_t& seed, const std::string& help) {
  return sub.add_option("--seed", seed, help)->check(whole_number());
}

std::string threads_warning(int threads) {
  const unsigned cores = std::thread::hardware_concurrency();
  if (cores == 0 || threads <= static_cast<int>(cores)) return "";
  return "threads = " + std::to_string(threads) + " is more than the " + std::to_string(cores) +
         " cores of this machine; the threads take turns (slower, same result)";
}

CLI::Validator positive() {
  return number_check([](double v) { return v > 0.0; }, "> 0", "POSITIVE");
}

CLI::Validator non_negative() {
  return number_check([](double v) { return v >= 0.0; }, ">= 0", "NONNEGATIVE");
}

std::string map_image_path(const std::string& map_yaml) {
  const std::filesystem::path image(maps::read_map_yaml(map_yaml).image);
  return image.is_relative() ? (std::filesystem::path(map_yaml).parent_path() / image).string()
                             : image.string();
}

io::CarmenLog read_log(const std::string& path, const io::CarmenReadOptions& opt, bool strict,
                       std::vector<std::string>* warnings) {
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
    if (warnings != nullptr) {
      std::string w = path + ": dropped " + std::to_string(r.malformed) + " malformed line(s)";
      if (!r.malformed_lines.empty()) {
        const io::LineIssue& i = r.malformed_lines.front();
        w += ", the first on line " + std::to_string(i.line) + ": " + i.field + ": " + i.message;
      }
      warnings->push_back(std::move(w));
    }
    const std::size_t listed = std::min(kListed, r.malformed_lines.size());
    for (std::size_t k = 0; k < listed; ++k) {
      const io::LineIssue& i = r.malformed_lines[k];
      std::fprintf(stderr, "  %s:%zu: %s: %s\n", path.c_str(), i.line, i.field.c_str(),
                   i.message.c_str());
    }
    if (r.malformed > listed) std::fprintf(stderr, "  ... %zu more\n", r.malformed - listed);
  }
  if (r.derived_front_mount) {
    const Pose2& m = *r.derived_front_mount;
    std::fprintf(stderr,
                 "pgmcl: note: %s: no PARAM robot_frontlaser_offset; the FLASER laser poses put "
                 "the laser at (%.3f m, %.3f m, %.2f deg) from the odometry pose on every scan, "
                 "so that is its mounting\n",
                 path.c_str(), m.x, m.y, m.theta * 180.0 / 3.141592653589793);
  }
  return log;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw io::IoError(path + ": cannot create file (" + std::strerror(errno) + ")");
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool flushed = std::fflush(f) == 0;
  const std::string why = std::strerror(errno);
  const bool closed = std::fclose(f) == 0;
  if (!written || !flushed || !closed) throw io::IoError(path + ": write failed (" + why + ")");
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
