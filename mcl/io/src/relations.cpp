#include "pgmcl/io/relations.hpp"

#include <array>
#include <cmath>

#include "fields.hpp"
#include "pgmcl/io/line_io.hpp"

namespace pgmcl::io {
namespace {

constexpr std::array<std::string_view, 8> kFields = {"t1", "t2",   "x",     "y",
                                                     "z",  "roll", "pitch", "yaw"};

void parse_line(std::string_view line, std::size_t line_no, const std::string& source,
                std::vector<std::string_view>& tokens, std::vector<Relation>& out) {
  detail::split_fields(line, tokens);
  if (tokens.empty() || tokens.front().front() == '#') return;
  std::array<double, 8> v{};
  detail::parse_fixed_numbers(tokens, kFields, v, source, line_no);
  Relation r;
  r.t1 = v[0];
  r.t2 = v[1];
  r.delta = {v[2], v[3], wrap_angle(v[7])};
  r.z = v[4];
  r.roll = v[5];
  r.pitch = v[6];
  r.line = line_no;
  check_record_memory(out.size() + 1, sizeof(Relation), source, line_no);
  out.push_back(r);
}

}  // namespace

std::vector<Relation> read_relations(const std::string& path) {
  std::vector<Relation> out;
  std::vector<std::string_view> tokens;
  detail::for_each_file_line(
      path, [&](std::string_view line, std::size_t n) { parse_line(line, n, path, tokens, out); });
  return out;
}

std::vector<Relation> parse_relations(std::string_view text, const std::string& source) {
  std::vector<Relation> out;
  std::vector<std::string_view> tokens;
  detail::for_each_text_line(text, [&](std::string_view line, std::size_t n) {
    parse_line(line, n, source, tokens, out);
  });
  return out;
}

}  // namespace pgmcl::io
