#include "fields.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "pgmcl/io/errors.hpp"

namespace pgmcl::io::detail {

void split_fields(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < n && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
}

std::optional<double> parse_double(std::string_view token) noexcept {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return v;
}

std::optional<long long> parse_integer(std::string_view token) noexcept {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  long long v = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return v;
}

namespace {
template <typename T, typename... Fmt>
void append_impl(std::string& out, T v, Fmt... fmt) {
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v, fmt...);
  // 64 bytes hold any shortest double and the fixed range append_fixed allows.
  if (ec != std::errc()) throw std::logic_error("pgmcl::io: number formatting overflow");
  out.append(buf, ptr);
}
}  // namespace

void append_number(std::string& out, double v) {
  append_impl(out, v);
}
void append_number(std::string& out, float v) {
  append_impl(out, v);
}
void append_fixed(std::string& out, double v) {
  // Logs do hold stamps like 1.65576e-153 (intel); those stay in scientific notation.
  const double a = std::abs(v);
  if (!std::isfinite(v) || (a != 0.0 && (a < 1e-6 || a >= 1e15))) {
    append_impl(out, v);
    return;
  }
  append_impl(out, v, std::chars_format::fixed);
}

std::string indexed_name(std::string_view name, std::size_t index) {
  std::string s(name);
  s += '[';
  s += std::to_string(index);
  s += ']';
  return s;
}

std::string_view FieldCursor::take(std::string_view name, std::size_t index, bool indexed) {
  if (pos_ >= tokens_.size()) {
    throw FieldError{indexed ? indexed_name(name, index) : std::string(name),
                     "missing (the line ends after " + std::to_string(tokens_.size()) + " fields)"};
  }
  return tokens_[pos_++];
}

double FieldCursor::finite(std::string_view name) {
  const std::string_view tok = take(name, 0, false);
  const auto v = parse_double(tok);
  if (!v) throw FieldError{std::string(name), "not a number: '" + std::string(tok) + "'"};
  if (!std::isfinite(*v))
    throw FieldError{std::string(name), "not finite: '" + std::string(tok) + "'"};
  return *v;
}

double FieldCursor::number(std::string_view name, std::size_t index) {
  const std::string_view tok = take(name, index, true);
  const auto v = parse_double(tok);
  if (!v) throw FieldError{indexed_name(name, index), "not a number: '" + std::string(tok) + "'"};
  return *v;
}

std::size_t FieldCursor::count(std::string_view name, std::size_t max) {
  const std::string_view tok = take(name, 0, false);
  const auto v = parse_integer(tok);
  if (!v) throw FieldError{std::string(name), "not an integer: '" + std::string(tok) + "'"};
  if (*v < 0 || static_cast<unsigned long long>(*v) > max) {
    throw FieldError{std::string(name),
                     "count " + std::string(tok) + " outside [0, " + std::to_string(max) + "]"};
  }
  return static_cast<std::size_t>(*v);
}

int FieldCursor::integer(std::string_view name) {
  const std::string_view tok = take(name, 0, false);
  const auto v = parse_integer(tok);
  if (!v || *v < -2147483647LL || *v > 2147483647LL) {
    throw FieldError{std::string(name), "not an integer: '" + std::string(tok) + "'"};
  }
  return static_cast<int>(*v);
}

std::string_view FieldCursor::text(std::string_view name) {
  return take(name, 0, false);
}

void FieldCursor::expect_end(std::string_view last_field) const {
  if (pos_ < tokens_.size()) {
    throw FieldError{std::string(last_field), std::to_string(tokens_.size() - pos_) +
                                                  " unexpected field(s) after it, from '" +
                                                  std::string(tokens_[pos_]) + "'"};
  }
}

void parse_fixed_numbers(std::span<const std::string_view> tokens,
                         std::span<const std::string_view> names, std::span<double> out,
                         const std::string& source, std::size_t line) {
  const std::string expected = "expected " + std::to_string(names.size()) + " fields, found " +
                               std::to_string(tokens.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string field(names[i]);
    if (i >= tokens.size()) throw FormatError(source, line, field, "missing (" + expected + ")");
    const auto v = parse_double(tokens[i]);
    if (!v)
      throw FormatError(source, line, field, "not a number: '" + std::string(tokens[i]) + "'");
    if (!std::isfinite(*v)) {
      throw FormatError(source, line, field, "not finite: '" + std::string(tokens[i]) + "'");
    }
    out[i] = *v;
  }
  if (tokens.size() > names.size()) {
    throw FormatError(source, line, std::string(names.back()), expected);
  }
}

}  // namespace pgmcl::io::detail
