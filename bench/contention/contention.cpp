/// Sharing the CPU (issue 16.5): Localizer::update with 1 thread, 2 threads (the default
/// adaptive_threads: one thread while the team is slower) and a fixed team of 2
/// (adaptive_threads off), on a quiet machine and with one core kept busy by another process
/// (a busy loop, free to migrate or pinned to one CPU). Prints mean, median and p95 update
/// times per case, the share of updates that ran on two threads, and the ratio to one
/// thread; writes contention.csv.
///
/// The world is the issue's: a 25 M-cell map (a 250 m synthetic office at 5 cm), 2000
/// particles, every beam of a 1081-beam UTM-30LX-like scan, the engine's defaults otherwise
/// (isotropic table, competing hypotheses on) with KLD, gating and selective resampling off
/// so that every update does the same work. The robot drives a small circle in one room.
/// Cases are interleaved (rounds of every case) so that drift of the machine spreads over
/// all of them. Take the lock and a quiet machine: flock /tmp/pgmcl-cpu.lock ...
///
/// Flags: --updates=N per case and round (200), --rounds=R (3), --particles=N (2000),
/// --size=M map side in metres (250), --pin-cpu=C CPU of the pinned busy loop (0),
/// --cases=quiet,busy,pinned, --out=DIR (writes DIR/contention.csv).

#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "../bench_common.hpp"
#include "pgmcl/mcl/localizer.hpp"

namespace pb = pgmcl::bench;

namespace {

struct Options {
  int updates = 200;
  int rounds = 3;
  std::size_t particles = 2000;
  double size = 250.0;
  int pin_cpu = 0;
  std::vector<std::string> cases = {"quiet", "busy", "pinned"};
  std::string out;
};

/// A child process that spins until killed; pinned to `cpu` when >= 0.
class BusyLoop {
 public:
  explicit BusyLoop(int cpu) {
    pid_ = fork();
    if (pid_ == 0) {
      if (cpu >= 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        CPU_SET(cpu, &set);
        (void)sched_setaffinity(0, sizeof set, &set);
      }
      volatile unsigned long x = 0;
      for (;;) x = x + 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // let it settle
  }
  ~BusyLoop() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  BusyLoop(const BusyLoop&) = delete;
  BusyLoop& operator=(const BusyLoop&) = delete;

 private:
  pid_t pid_ = -1;
};

struct World {
  pgmcl::maps::OccupancyGrid grid;
  std::shared_ptr<const pgmcl::maps::LikelihoodField> field;
  std::vector<std::uint32_t> free_cells;
  std::vector<pgmcl::Pose2> poses;
  std::vector<pgmcl::LaserScan> scans;
};

World make_world(const Options& o) {
  World w;
  pb::OfficeSpec spec;
  spec.width_m = spec.height_m = o.size;
  w.grid = pb::make_office(spec);
  w.field = pb::make_table(w.grid, pgmcl::maps::TableKind::kIsotropic);
  w.free_cells = pgmcl::free_cell_indices(w.grid);
  const pgmcl::sims::RayCaster caster(w.grid);
  pb::circle_drive(caster, pb::room_centre(spec, 3, 3), 32, w.poses, w.scans);
  return w;
}

struct Mode {
  const char* name;
  int threads;
  bool adaptive;
};
constexpr Mode kModes[] = {{"1", 1, true}, {"2", 2, true}, {"2 fixed", 2, false}};

struct Times {
  std::vector<double> ms;
  std::size_t team = 0;  // updates that ran on two threads
};

/// Update times (ms) of `n` updates in `mode`, after 10 untimed ones.
void run_case(const World& w, const Options& o, const Mode& mode, Times& out) {
  pgmcl::LocalizerConfig cfg;
  cfg.filter.particles = cfg.filter.global_particles = o.particles;
  cfg.filter.kld.enabled = false;
  cfg.filter.resample_threshold = 1.0;
  cfg.gating.enabled = false;
  cfg.likelihood.selection.mode = pgmcl::BeamSelectionMode::kAll;
  cfg.threads = mode.threads;
  cfg.adaptive_threads = mode.adaptive;
  pgmcl::Localizer loc(w.field, w.free_cells, cfg);
  loc.set_pose(w.poses[0], Eigen::Vector3d(0.01, 0.01, 0.003).asDiagonal());
  double stamp = 0.0;
  for (int i = 0; i < o.updates + 10; ++i) {
    const std::size_t k = static_cast<std::size_t>(i) % w.poses.size();
    const auto t0 = std::chrono::steady_clock::now();
    const pgmcl::UpdateResult r = loc.update(w.poses[k], w.scans[k], stamp);
    const double dt =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (i >= 10) {
      out.ms.push_back(dt);
      out.team += r.threads == 2 ? 1 : 0;
    }
    stamp += 0.1;
  }
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double pos = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(pos);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&](const char* key) -> const char* {
      const std::string k = std::string("--") + key + "=";
      return a.rfind(k, 0) == 0 ? argv[i] + k.size() : nullptr;
    };
    if (const char* v = value("updates")) {
      o.updates = std::stoi(v);
    } else if (const char* v = value("rounds")) {
      o.rounds = std::stoi(v);
    } else if (const char* v = value("particles")) {
      o.particles = std::stoul(v);
    } else if (const char* v = value("size")) {
      o.size = std::stod(v);
    } else if (const char* v = value("pin-cpu")) {
      o.pin_cpu = std::stoi(v);
    } else if (const char* v = value("cases")) {
      o.cases = pb::split_list(v);
    } else if (const char* v = value("out")) {
      o.out = v;
    } else {
      std::fprintf(stderr, "pgmcl_contention: unknown flag %s (see the file header)\n", argv[i]);
      return false;
    }
  }
  return o.updates > 0 && o.rounds > 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) return 2;
  std::printf("building the %.0f m office (%.1f M cells) ...\n", o.size,
              o.size * o.size / (0.05 * 0.05) * 1e-6);
  const World w = make_world(o);
  std::printf("%zu particles, %zu beams, %d updates x %d rounds per case, %u CPUs\n", o.particles,
              w.scans[0].size(), o.updates, o.rounds, std::thread::hardware_concurrency());
  std::map<std::string, Times> times;  // "case/mode" -> update times
  for (int round = 0; round < o.rounds; ++round) {
    for (const std::string& c : o.cases) {
      std::unique_ptr<BusyLoop> busy;
      if (c == "busy") busy = std::make_unique<BusyLoop>(-1);
      if (c == "pinned") busy = std::make_unique<BusyLoop>(o.pin_cpu);
      for (const Mode& m : kModes) run_case(w, o, m, times[c + "/" + m.name]);
    }
  }
  std::printf("\n%-8s %-8s %9s %9s %9s %8s   %s\n", "case", "threads", "mean ms", "p50 ms",
              "p95 ms", "on 2", "/ 1 thread (mean, p95)");
  std::string csv = "case,threads,mean_ms,p50_ms,p95_ms,share_on_two,ratio_mean,ratio_p95\n";
  for (const std::string& c : o.cases) {
    const Times& one = times[c + "/1"];
    for (const Mode& m : kModes) {
      const Times& t = times[c + "/" + m.name];
      const double share = static_cast<double>(t.team) / static_cast<double>(t.ms.size());
      const double rm = mean(t.ms) / mean(one.ms);
      const double rp = percentile(t.ms, 0.95) / percentile(one.ms, 0.95);
      std::printf("%-8s %-8s %9.3f %9.3f %9.3f %7.0f%%   %.2f, %.2f\n", c.c_str(), m.name,
                  mean(t.ms), percentile(t.ms, 0.5), percentile(t.ms, 0.95), 100.0 * share, rm, rp);
      char line[200];
      std::snprintf(line, sizeof line, "%s,%s,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f\n", c.c_str(), m.name,
                    mean(t.ms), percentile(t.ms, 0.5), percentile(t.ms, 0.95), share, rm, rp);
      csv += line;
    }
  }
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    std::ofstream(std::filesystem::path(o.out) / "contention.csv") << csv;
  }
  return 0;
}
