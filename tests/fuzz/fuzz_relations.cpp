// libFuzzer target: the SLAM-benchmark relations reader (pgmcl::io::parse_relations) and
// the relative-pose metric (Kuemmerle et al. 2009) on an estimate built from the input.
// Oracles: only FormatError escapes (relations.hpp); relations hold finite numbers;
// matched + degenerate + unmatched == relations; per-relation errors finite and >= 0;
// read_relations on the same bytes in a file fails at the same line and field, or not.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_util.hpp"
#include "pgmcl/eval/relations_error.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/relations.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace pgmcl;
  const auto parsed = fuzz::accepted<io::FormatError>(
      [&] { return io::parse_relations(fuzz::as_text(data, size), "fuzz.relations"); });
  if (!parsed) return 0;
  const std::vector<io::Relation>& rel = *parsed;
  {
    const std::string path = fuzz::write_scratch("fuzz.relations", fuzz::as_text(data, size));
    std::string file;
    try {
      file = fuzz::outcome<io::FormatError>([&] { return io::read_relations(path); });
      if (file == "ok" && io::read_relations(path).size() != rel.size())
        fuzz::fail("read_relations(file) and parse_relations(text) disagree on the count");
    } catch (const std::exception& e) {
      fuzz::undocumented(e);
    }
    if (file != "ok") fuzz::fail("read_relations(file) failed where parse_relations did not", file);
  }
  io::Trajectory est;
  for (const io::Relation& r : rel) {
    if (!std::isfinite(r.t1) || !std::isfinite(r.t2) || !std::isfinite(r.delta.x) ||
        !std::isfinite(r.delta.y) || !std::isfinite(r.delta.theta))
      fuzz::fail("relation with a non-finite number");
    est.push_back({r.t1, Pose2{}});
    est.push_back({r.t2, Pose2{}.compose(r.delta)});
  }
  try {
    const io::RelationResult res = io::evaluate_relations(est, rel);
    if (res.relations != rel.size() ||
        res.matched + res.degenerate + res.unmatched != res.relations)
      fuzz::fail("relation counts do not add up");
    if (res.errors.size() != res.matched) fuzz::fail("errors.size() != matched");
    for (const io::RelationError& e : res.errors) {
      if (!std::isfinite(e.translation) || !std::isfinite(e.rotation) || e.translation < 0 ||
          e.rotation < 0)
        fuzz::fail("relation error not a finite non-negative number");
    }
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }
  return 0;
}
