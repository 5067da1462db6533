#include "pgmcl/io/values.hpp"

#include <charconv>
#include <cmath>

namespace pgmcl::io {
namespace {

std::string quoted(std::string_view s) {
  return "'" + std::string(s) + "'";
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string format_number(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  char buf[400];
  // Shortest round trip, in positional notation where that stays short ("0.0005", not
  // "5e-04"), else in scientific notation with a mantissa dot ("1.0e-09": YAML 1.1 readers
  // such as PyYAML take "1e-09" for a string).
  const double a = std::abs(v);
  const bool fixed = a == 0.0 || (a >= 1e-6 && a < 1e15);
  const auto res = std::to_chars(buf, buf + sizeof buf, v,
                                 fixed ? std::chars_format::fixed : std::chars_format::scientific);
  std::string s(buf, res.ptr);
  const std::size_t e = s.find('e');
  if (s.find('.') == std::string::npos) s.insert(e == std::string::npos ? s.size() : e, ".0");
  return s;
}

double parse_number(std::string_view text, std::string_view option) {
  const std::string_view t = trim(text);
  double v = 0.0;
  const char* first = t.data();
  const char* last = t.data() + t.size();
  if (!t.empty() && *first == '+') ++first;  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (t.empty() || ec != std::errc() || ptr != last || !std::isfinite(v)) {
    throw UsageError(std::string(option) + ": expected a number, got " + quoted(text));
  }
  return v;
}

std::vector<double> parse_number_list(std::string_view text, std::string_view option,
                                      std::initializer_list<std::size_t> counts,
                                      std::string_view form) {
  std::vector<double> out;
  std::string_view rest = text;
  auto fail = [&](const std::string& why) -> void {
    throw UsageError(std::string(option) + ": expected " + std::string(form) + ", got " +
                     quoted(text) + " (" + why + ")");
  };
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    try {
      out.push_back(parse_number(item, option));
    } catch (const UsageError&) {
      fail("item " + std::to_string(out.size() + 1) + " is not a number: " + quoted(item));
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  bool ok = false;
  for (const std::size_t c : counts) ok = ok || out.size() == c;
  if (!ok) fail(std::to_string(out.size()) + " values");
  return out;
}

std::pair<std::string, std::string> parse_key_value(std::string_view text,
                                                    std::string_view option) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos || trim(text.substr(0, eq)).empty()) {
    throw UsageError(std::string(option) + ": expected key=value, got " + quoted(text));
  }
  return {std::string(trim(text.substr(0, eq))), std::string(trim(text.substr(eq + 1)))};
}

}  // namespace pgmcl::io
