#include "pgmcl/mcl/localizer_config.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "pgmcl/mcl/config_schema.hpp"

namespace pgmcl {
namespace config_schema {
namespace {

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string interval(const std::string& lo, const std::string& hi, bool lo_open, bool hi_open) {
  return std::string(lo_open ? "(" : "[") + lo + ", " + hi + (hi_open ? ")" : "]");
}

// Walks the schema and throws for the first field outside its allowed values.
class Validator {
 public:
  template <class Body>
  void section(const char* name, Body&& body) {
    path_.push_back(name);
    body();
    path_.pop_back();
  }
  void number(const Field& f, double v, const Bounds& b) const {
    if (!b.contains(v)) fail(f.name, "must be " + b.text() + " (got " + format_number(v) + ")");
  }
  template <class T>
  void integer(const Field& f, T v, const IntRange& r) const {
    if (std::cmp_less(v, r.lo) || std::cmp_greater(v, r.hi))
      fail(f.name, "must be " + r.text() + " (got " + std::to_string(v) + ")" +
                       r.memory(static_cast<std::uint64_t>(std::max<T>(v, T{0}))));
  }
  void flag(const Field&, bool) const {}
  template <class E, std::size_t N>
  void choice(const Field& f, E v, const std::array<EnumName<E>, N>& names) const {
    for (const auto& n : names)
      if (n.value == v) return;
    fail(f.name, "is not one of its named values");
  }
  void rule(const char* name, bool ok, const char* problem) const {
    if (!ok) fail(name, problem);
  }

 private:
  [[noreturn]] void fail(const char* name, std::string problem) const {
    std::string field;
    for (const char* p : path_) field += std::string(p) + ".";
    throw InvalidConfigField(field + name, std::move(problem));
  }
  std::vector<const char*> path_;
};

}  // namespace

std::string Bounds::text() const {
  const bool has_lo = lo != -kInf, has_hi = hi != kInf;
  if (has_lo && has_hi)
    return "in " + interval(format_number(lo), format_number(hi), lo_open, hi_open);
  if (has_lo) return std::string("finite and ") + (lo_open ? "> " : ">= ") + format_number(lo);
  if (has_hi) return std::string("finite and ") + (hi_open ? "< " : "<= ") + format_number(hi);
  return "finite";
}

std::string IntRange::text() const {
  if (hi == std::numeric_limits<std::uint64_t>::max()) return "an integer >= " + std::to_string(lo);
  return "an integer in " + interval(std::to_string(lo), std::to_string(hi), false, false);
}

std::string IntRange::memory(std::uint64_t v) const {
  if (unit_bytes <= 0.0 || v <= hi) return "";
  const double bytes = unit_bytes * static_cast<double>(v);
  char buf[128];
  std::snprintf(buf, sizeof buf, " (about %.0f bytes each: %.3g would take %.3g GB)", unit_bytes,
                static_cast<double>(v), bytes / 1e9);
  return buf;
}

}  // namespace config_schema

InvalidConfigField::InvalidConfigField(std::string field, std::string problem)
    : std::invalid_argument("LocalizerConfig: " + field + " " + problem),
      field_(std::move(field)),
      problem_(std::move(problem)) {}

void LocalizerConfig::validate() const {
  config_schema::Validator v;
  config_schema::describe_config(v, *this);
}

}  // namespace pgmcl
