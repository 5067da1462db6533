#include "app_util.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "cli_errors.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "pgmcl/mcl/config_schema.hpp"

namespace pgmcl::app {

io::Trajectory load_truth(const std::string& path) {
  const io::FileKind kind = io::detect_file_kind(path);
  const bool log = kind == io::FileKind::kCarmenLog ||
                   (kind != io::FileKind::kNumberTable && io::is_carmen_path(path));
  if (!log) return io::read_tum(path);
  try {
    return io::log_truth(read_log(path, {}, false), path);
  } catch (const io::UsageError& e) {
    throw std::runtime_error(e.what());  // bad input (exit 1), not a bad command line
  }
}

CLI::Validator file_kind(std::initializer_list<io::FileKind> accepted, std::string wanted) {
  return CLI::Validator(
      [kinds = std::vector<io::FileKind>(accepted), wanted](std::string& path) {
        return io::file_kind_problem(path, kinds, wanted);
      },
      "", "file kind");
}

CLI::Validator length_in(const std::string& unit) {
  return CLI::Validator(
      [unit](std::string& text) -> std::string {
        // The number, then an optional unit: "5", "5mm", "0.5 cm", "0.005m".
        std::size_t end = text.size();
        while (end > 0 && std::isalpha(static_cast<unsigned char>(text[end - 1]))) --end;
        const std::string suffix = text.substr(end);
        std::string number = text.substr(0, end);
        while (!number.empty() && number.back() == ' ') number.pop_back();
        double v = 0.0;
        const double per_m = unit == "mm" ? 1000.0 : 1.0;  // this unit's value of a metre
        const std::map<std::string, double> factors{
            {"", 1.0}, {"mm", per_m / 1000.0}, {"cm", per_m / 100.0}, {"m", per_m}};
        const auto f = factors.find(suffix);
        if (f == factors.end() || !CLI::detail::lexical_cast(number, v) || !std::isfinite(v)) {
          return "expected a length in " + unit + " or with a unit (5, 5mm, 0.5cm, 0.005m), got '" +
                 text + "'";
        }
        text = io::format_number(v * f->second);
        return {};
      },
      "", "length");
}

CLI::Validator map_file() {
  return file_kind({io::FileKind::kMapYaml, io::FileKind::kOtherYaml},
                   "a map YAML (map_server: image, resolution, origin)");
}
CLI::Validator log_file() {
  return file_kind({io::FileKind::kCarmenLog}, "a CARMEN log");
}
CLI::Validator trajectory_file(bool log_ok) {
  if (!log_ok) {
    return file_kind({io::FileKind::kNumberTable},
                     "a TUM trajectory (stamp x y z qx qy qz qw per line)");
  }
  return file_kind({io::FileKind::kNumberTable, io::FileKind::kCarmenLog},
                   "a TUM trajectory or a corrected CARMEN log");
}
CLI::Validator filter_file() {
  return file_kind({io::FileKind::kFilterYaml, io::FileKind::kOtherYaml},
                   "a filter configuration (configs/filters/)");
}
CLI::Validator experiment_file() {
  return file_kind({io::FileKind::kExperiment, io::FileKind::kOtherYaml},
                   "an experiment file (map + data + filter; configs/experiments/)");
}
CLI::Validator scenario_file() {
  return file_kind({io::FileKind::kScenario, io::FileKind::kOtherYaml},
                   "a scenario (configs/scenarios/)");
}
CLI::Validator relations_file() {
  return file_kind({io::FileKind::kNumberTable},
                   "a relations file (t1 t2 x y z roll pitch yaw per line)");
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

CLI::Option* add_input_file(CLI::App& sub, const std::string& name, std::string& path,
                            const std::string& help, const CLI::Validator& kind) {
  return sub.add_option(name, path, help)->check(CLI::ExistingFile)->check(kind);
}

CLI::Option* add_threads_option(CLI::App& sub, int& threads, const std::string& help) {
  return sub.add_option("--threads", threads, help)
      ->check(whole_number(0, config_schema::kMaxThreads));
}

FilterOptions add_filter_options(CLI::App& sub, std::string& config,
                                 std::vector<std::string>& sets) {
  FilterOptions added;
  added.config =
      add_input_file(sub, "--config", config, "Filter configuration YAML", filter_file());
  added.sets = sub.add_option("--set", sets, "Override a config key, e.g. filter.particles=2000")
                   ->take_all();
  return added;
}

CLI::Option* add_strict_flag(CLI::App& sub, bool& strict) {
  return sub.add_flag("--strict", strict, "Malformed log lines are errors, not warnings");
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
