// SIGINT and SIGTERM during long commands: localize keeps the run so far (the trajectory,
// metrics.yaml with complete: false) and exits 130 / 143; perturb writes nothing and leaves
// the earlier files as they were. No sleeps decide anything: the tests wait for the
// progress line that shows the run under way, or feed the input through a FIFO.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "hostile_corpus.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::hostile {
namespace {

namespace fs = std::filesystem;

/// Starts pgmcl with `args` in `cwd`, stderr to `err`; returns its pid.
pid_t spawn(const std::vector<std::string>& args, const std::string& cwd, const std::string& err) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(cwd.c_str()) != 0) ::_exit(127);
    const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    std::vector<char*> argv;
    const std::string bin = PGMCL_BINARY_DIR "/pgmcl";
    argv.push_back(const_cast<char*>(bin.c_str()));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(bin.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

/// Waits until `file` contains `text` (a guard of 10 minutes against a hang, not a timing).
bool wait_for(const std::string& file, const std::string& text, pid_t pid) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  while (std::chrono::steady_clock::now() < give_up) {
    if (testkit::read_text(file).find(text) != std::string::npos) return true;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;  // ended early
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

int exit_code(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

void expect_no_temporaries(const fs::path& dir) {
  for (const auto& f : fs::recursive_directory_iterator(dir)) {
    EXPECT_EQ(f.path().filename().string().find(".pgmcl-"), std::string::npos) << f.path();
  }
}

/// A long localize (the whole log, 20000 particles without KLD), stopped by `sig` once the
/// first progress line shows it under way.
void interrupt_localize(int sig, bool with_truth, int expected_code) {
  const Base& b = base();
  testkit::TempDir dir("signal");
  // An earlier run's files, error.png among them, that the stopped run must replace as a set.
  testkit::write_text(dir.file("out/error.png"), "stale");
  testkit::write_text(dir.file("out/trajectory.tum"), "stale");
  std::vector<std::string> args = {"localize",
                                   "--map",
                                   b.map,
                                   "--log",
                                   b.raw,
                                   "--init",
                                   b.init(),
                                   "--set",
                                   "filter.kld.enabled=false",
                                   "--set",
                                   "filter.particles=20000",
                                   "--out",
                                   "out"};
  if (with_truth) {
    args.push_back("--truth");
    args.push_back(b.truth);
  }
  const std::string err = dir.file("stderr.txt");
  const pid_t pid = spawn(args, dir.path().string(), err);
  ASSERT_TRUE(wait_for(err, "(10%)", pid)) << testkit::read_text(err);
  ::kill(pid, sig);
  // "localize: 89/910 (10%) ...": the updates done when the signal was sent, at least.
  const std::string progress = testkit::read_text(err);
  const std::size_t pct = progress.find("(10%)");
  const std::size_t line = progress.rfind("localize: ", pct) + 10;
  const std::size_t done_before =
      std::stoul(progress.substr(line, progress.find('/', line) - line));
  EXPECT_EQ(exit_code(pid), expected_code) << testkit::read_text(err);
  const std::string log = testkit::read_text(err);
  EXPECT_NE(log.find("interrupted by"), std::string::npos) << log;
  EXPECT_NE(log.find("complete: false"), std::string::npos) << log;

  const io::Trajectory t = io::read_tum(dir.file("out/trajectory.tum"));
  EXPECT_GE(t.size(), done_before);  // the updates the progress line reported, at least
  EXPECT_GE(done_before, 80u);
  EXPECT_LT(t.size(), 900u);  // and not the whole log
  const std::string metrics = testkit::read_text(dir.file("out/metrics.yaml"));
  EXPECT_NE(metrics.find("complete: false"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("updates: "), std::string::npos);
  for (const char* f : {"config.yaml", "updates.csv", "overlay.png"}) {
    EXPECT_TRUE(fs::exists(dir.file(std::string("out/") + f))) << f;
  }
  // With truth, error.png is this run's picture; without, the stale one is gone.
  if (with_truth) {
    EXPECT_NE(testkit::read_text(dir.file("out/error.png")), "stale");
    EXPECT_NE(metrics.find("ate_rmse_m"), std::string::npos);
  } else {
    EXPECT_FALSE(fs::exists(dir.file("out/error.png")));
  }
  expect_no_temporaries(dir.path());
}

TEST(Signals, SigintDuringLocalizeWritesTheRunSoFarAndExits130) {
  interrupt_localize(SIGINT, true, 130);
}

TEST(Signals, SigtermDuringLocalizeWritesTheRunSoFarAndExits143) {
  interrupt_localize(SIGTERM, false, 143);
}

TEST(Signals, SigintDuringPerturbWritesNothingAndKeepsTheEarlierFiles) {
  const Base& b = base();
  testkit::TempDir dir("signal");
  testkit::write_text(dir.file("raw.log"), "earlier\n");
  testkit::write_text(dir.file("truth.tum"), "earlier\n");
  const std::string fifo = dir.file("in.log");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string err = dir.file("stderr.txt");
  const pid_t pid = spawn({"perturb", "--log", "in.log", "--odom-noise", "0.01,0,0.01,0", "--seed",
                           "1", "--out", "raw.log", "--truth-out", "truth.tum"},
                          dir.path().string(), err);
  // The command reads the log through the FIFO: half of it, the signal, then the rest.
  const std::string text = testkit::read_text(b.log);
  // Opened once pgmcl opens its end (non-blocking, so a pgmcl that failed early cannot
  // leave the test waiting).
  int fd = -1;
  while (fd < 0) {
    fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    int status = 0;
    ASSERT_FALSE(fd < 0 && ::waitpid(pid, &status, WNOHANG) == pid) << testkit::read_text(err);
    if (fd < 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  const std::size_t half = text.size() / 2;
  ASSERT_EQ(::write(fd, text.data(), half), static_cast<ssize_t>(half));
  ::kill(pid, SIGINT);
  // The rest may meet a reader that already stopped: a broken pipe is fine here.
  ::signal(SIGPIPE, SIG_IGN);
  (void)!::write(fd, text.data() + half, text.size() - half);
  ::close(fd);
  EXPECT_EQ(exit_code(pid), 130) << testkit::read_text(err);
  EXPECT_NE(testkit::read_text(err).find("interrupted by SIGINT"), std::string::npos);
  EXPECT_EQ(testkit::read_text(dir.file("raw.log")), "earlier\n");
  EXPECT_EQ(testkit::read_text(dir.file("truth.tum")), "earlier\n");
  expect_no_temporaries(dir.path());
}

}  // namespace
}  // namespace pgmcl::hostile
