#include "hostile_corpus.hpp"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "pgmcl/io/line_io.hpp"
#include "pgmcl/io/tum.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::hostile {
namespace {

namespace fs = std::filesystem;

const std::string kPgmcl = PGMCL_BINARY_DIR "/pgmcl";

std::string quote(const std::string& s) {
  return "'" + s + "'";
}

/// The truth pose nearest `stamp`.
Pose2 truth_at(const io::Trajectory& t, double stamp) {
  const auto i = io::nearest_index(t, stamp, 1.0);
  if (!i) throw std::runtime_error("hostile base: no truth near the scan stamps");
  return t[*i].pose;
}

void make_base(const std::string& dir, Base& b) {
  const std::string corrected = PGMCL_SOURCE_DIR "/data/logs/intel-corrected.log.gz";
  const RunResult m =
      run_pgmcl("map --log " + quote(corrected) + " --resolution 0.05 --out map.yaml --quiet", dir);
  const RunResult p = run_pgmcl("perturb --log " + quote(corrected) +
                                    " --odom-noise 0.005,0.0005,0.005,0.0005 --seed 1 --out "
                                    "raw.log.gz --truth-out truth.tum --quiet",
                                dir);
  if (m.code != 0 || p.code != 0) {
    throw std::runtime_error("hostile base: pgmcl map / perturb failed:\n" + m.err + p.err);
  }
  // short.log: the header and messages up to the kShortScans-th laser scan.
  io::LineReader in(dir + "/raw.log.gz");
  std::ofstream out(dir + "/short.log");
  std::string_view line;
  int scans = 0;
  std::vector<double> stamps;
  while (scans < kShortScans && in.next(line)) {
    out << line << "\n";
    if (line.rfind("FLASER", 0) == 0) {
      ++scans;
      std::istringstream words{std::string(line)};
      std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
      stamps.push_back(std::stod(w[w.size() - 3]));
    }
  }
  out.close();
  const io::Trajectory truth = io::read_tum(dir + "/truth.tum");
  b.start = truth_at(truth, stamps.front());
  b.end = truth_at(truth, stamps.back());
  b.raw_end = truth.back().pose;
  const maps::OccupancyGrid g = maps::load_map(dir + "/map.yaml");
  bool found = false;
  for (int r = 0; r < g.height() && !found; ++r) {
    for (int c = 0; c < g.width() && !found; ++c) {
      found = g.occupied(c, r);
      if (found) g.cell_center_global(c, r, b.wall.x, b.wall.y);
    }
  }
  std::ofstream(dir + "/poses.txt")
      << std::hexfloat << b.start.x << " " << b.start.y << " " << b.start.theta << " " << b.end.x
      << " " << b.end.y << " " << b.end.theta << " " << b.wall.x << " " << b.wall.y << " "
      << b.raw_end.x << " " << b.raw_end.y << "\n";
}

Base load_or_make_base() {
  struct stat st {};
  if (::stat(kPgmcl.c_str(), &st) != 0) throw std::runtime_error("hostile base: no " + kPgmcl);
  const std::string dir = std::string(PGMCL_BINARY_DIR) + "/hostile-base-" +
                          std::to_string(static_cast<long long>(st.st_mtime));
  Base b;
  if (!fs::exists(dir + "/poses.txt")) {
    // Made in a private folder and renamed: tests run in parallel processes.
    const std::string tmp = dir + ".tmp-" + std::to_string(::getpid());
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    make_base(tmp, b);
    std::error_code ec;
    fs::rename(tmp, dir, ec);
    if (ec) fs::remove_all(tmp);  // another process won; use its copy
    // Bases of earlier builds of pgmcl are stale now.
    for (const auto& old : fs::directory_iterator(PGMCL_BINARY_DIR, ec)) {
      const std::string name = old.path().filename().string();
      if (name.rfind("hostile-base-", 0) == 0 && old.path().string() != dir &&
          name.find(".tmp-") == std::string::npos) {
        fs::remove_all(old.path(), ec);
      }
    }
  }
  std::ifstream in(dir + "/poses.txt");
  std::string w[10];
  for (auto& s : w) in >> s;
  const auto d = [](const std::string& s) { return std::strtod(s.c_str(), nullptr); };
  b.start = {d(w[0]), d(w[1]), d(w[2])};
  b.end = {d(w[3]), d(w[4]), d(w[5])};
  b.wall = {d(w[6]), d(w[7]), 0.0};
  b.raw_end = {d(w[8]), d(w[9]), 0.0};
  b.dir = dir;
  b.map = dir + "/map.yaml";
  b.image = dir + "/map.pgm";
  b.raw = dir + "/raw.log.gz";
  b.log = dir + "/short.log";
  b.truth = dir + "/truth.tum";
  return b;
}

}  // namespace

std::string pose_text(const Pose2& p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.6f,%.6f,%.6f", p.x, p.y, p.theta);
  return buf;
}

std::string Base::init() const {
  return pose_text(start);
}

const Base& base() {
  static const Base b = load_or_make_base();
  return b;
}

RunResult run_pgmcl(const std::string& args, const std::string& cwd) {
  static int n = 0;
  const std::string capture = fs::temp_directory_path().string() + "/pgmcl_hostile_" +
                              std::to_string(::getpid()) + "_" + std::to_string(n++);
  const std::string cmd = "cd " + quote(cwd) + " && " + quote(kPgmcl) + " " + args + " > " +
                          quote(capture + ".out") + " 2> " + quote(capture + ".err");
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = testkit::read_text(capture + ".out");
  r.err = testkit::read_text(capture + ".err");
  std::remove((capture + ".out").c_str());
  std::remove((capture + ".err").c_str());
  return r;
}

std::string Env::write(const std::string& name, const std::string& text) const {
  testkit::write_text(path(name), text);
  return path(name);
}

std::string Env::write_gz(const std::string& name, const std::string& text) const {
  fs::create_directories(fs::path(path(name)).parent_path());
  io::LineWriter w(path(name));
  std::string_view rest = text;
  while (!rest.empty()) {
    const std::size_t nl = rest.find('\n');
    w.write_line(rest.substr(0, nl));
    rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
  }
  w.close();
  return path(name);
}

std::vector<std::string> Env::log_lines() const {
  std::vector<std::string> lines;
  std::ifstream in(b.log);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::vector<std::string> Env::raw_lines() const {
  std::vector<std::string> lines;
  io::LineReader in(b.raw);
  for (std::string_view l; in.next(l);) lines.emplace_back(l);
  return lines;
}

std::string Env::map_yaml(const std::string& name, const std::string& keys) const {
  return write(name, "image: " + b.image + "\n" + keys);
}

std::string Env::localize(const std::string& extra, const std::string& log,
                          const std::string& map) const {
  // The base start unless the case gives its own (or asks for a global start).
  const bool own_start =
      extra.find("--init") != std::string::npos || extra.find("--global") != std::string::npos;
  const bool own_out = extra.find("--out") != std::string::npos;
  return "localize --map " + quote(map.empty() ? b.map : map) + " --log " +
         quote(log.empty() ? b.log : log) + (own_start ? "" : " --init " + b.init()) + " --quiet" +
         (own_out ? "" : " --out out") + " " + extra;
}

Case error_case(std::string name, int code, MakeArgs make, std::vector<std::string> stderr_has,
                CheckRun check) {
  return {std::move(name), Expect::kError,        code,
          std::move(make), std::move(stderr_has), std::move(check)};
}

Case warning_case(std::string name, MakeArgs make, std::vector<std::string> stderr_has,
                  CheckRun check) {
  return {std::move(name), Expect::kWarning,      0,
          std::move(make), std::move(stderr_has), std::move(check)};
}

Case accepted_case(std::string name, MakeArgs make, CheckRun check) {
  return {std::move(name), Expect::kAccepted, 0, std::move(make), {}, std::move(check)};
}

Case bad_setting(std::string name, const std::string& assignment,
                 std::vector<std::string> stderr_has) {
  return error_case(std::move(name), 1, localize_with("--set " + assignment),
                    std::move(stderr_has));
}

MakeArgs localize_with(std::string extra, std::string log, std::string map) {
  return [extra = std::move(extra), log = std::move(log), map = std::move(map)](const Env& e) {
    return e.localize(extra, log, map);
  };
}

MakeArgs localize_with_config(std::string yaml) {
  return [yaml = std::move(yaml)](const Env& e) {
    e.write("cfg.yaml", yaml);
    return e.localize("--config cfg.yaml");
  };
}

MakeArgs localize_on_map_yaml(std::string yaml) {
  return [yaml = std::move(yaml)](const Env& e) {
    e.write("m.yaml", yaml);
    return e.localize("", "", "m.yaml");
  };
}

MakeArgs perturb_base_map(std::string options) {
  return [options = std::move(options)](const Env& e) {
    return "perturb-map --map " + e.b.map + " " + options;
  };
}

MakeArgs map_base_log(std::string options) {
  return [options = std::move(options)](const Env& e) {
    return "map --log " + e.b.log + " " + options;
  };
}

std::string repeat(const std::string& line, std::size_t bytes) {
  std::string s;
  s.reserve(bytes + line.size());
  while (s.size() < bytes) s += line;
  return s;
}

std::vector<std::string> restamp(const std::vector<std::string>& lines,
                                 const std::function<double(double)>& f, bool odom, bool scans) {
  std::vector<std::string> out;
  for (const std::string& l : lines) {
    const bool is_odom = l.rfind("ODOM", 0) == 0;
    const bool is_scan = l.rfind("FLASER", 0) == 0;
    if (!((is_odom && odom) || (is_scan && scans))) {
      out.push_back(l);
      continue;
    }
    std::istringstream words(l);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), {}};
    const double t = f(std::stod(w[w.size() - 3]));
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6f", t);
    w[w.size() - 3] = buf;
    w[w.size() - 1] = buf;
    std::string joined;
    for (const std::string& s : w) joined += (joined.empty() ? "" : " ") + s;
    out.push_back(joined);
  }
  return out;
}

std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

}  // namespace pgmcl::hostile
