#pragma once
/// How many threads the next update runs with, when LocalizerConfig::threads asks for a
/// team and adaptive_threads is on: the team, or one thread when recent updates say the
/// team does not help.
///
/// Why: on a robot the rest of the stack uses the cores too. When another process keeps a
/// core busy, a team of two is slower than one thread (libgomp's idle threads spin between
/// the update's parallel loops and take the core the serial parts need; the thread that
/// shares a core falls behind), and the wait policy that would avoid it can only be set
/// through the environment. So the engine measures: each measured update's wall time per
/// unit of work (particles x beams) is recorded for the thread count it ran with; the
/// cheaper count by the mean of its last few updates is used (the mean, not the median: a
/// team beside a busy core is slow by its tail, a few updates that wait out another
/// process's time slice). The other count is tried again after kProbeEvery updates, at
/// once while those tries keep winning, and after twice as many each time one loses (up
/// to kMaxProbeEvery): a change of load is followed within a few hundred updates, and a
/// load that stays costs few slow tries. A try of the team is costly exactly when it is
/// pointless (a team thread waits out another process's time slice), so it is skipped, as
/// if lost, while the run queue shows the other cores taken (`cores_taken`), and the first
/// update starts on one thread then too. The results do not depend on it: the blocks and
/// random streams are fixed, so any thread count gives the same bits.

#include <array>
#include <cstddef>
#include <cstdint>

namespace pgmcl {

/// Whether other runnable threads take all cores but the caller's, sampled now (Linux: the
/// run queue of /proc/loadavg against the cores this process may use; elsewhere false).
[[nodiscard]] bool cores_taken() noexcept;
/// The rule behind it: `loadavg` (the text of /proc/loadavg) counts at least `cores`
/// runnable entities. Unreadable text claims nothing (false).
[[nodiscard]] bool run_queue_full(const char* loadavg, int cores) noexcept;

class ThreadPolicy {
 public:
  /// Samples the machine's load before a try of the team: true = the other cores are taken.
  using LoadProbe = bool (*)() noexcept;

  static constexpr std::size_t kWindow = 5;             ///< samples per count (mean)
  static constexpr std::uint64_t kProbeEvery = 64;      ///< updates until the other count's try
  static constexpr std::uint64_t kMaxProbeEvery = 512;  ///< ... after tries that kept losing
  static constexpr std::uint64_t kWarmup = 2;           ///< updates before the first try

  /// `requested`: LocalizerConfig::threads (1 = always serial; 0 = OpenMP's default team);
  /// `probe`: consulted before the team is tried or first used (nullptr: never).
  explicit ThreadPolicy(int requested = 1, LoadProbe probe = nullptr) noexcept
      : team_(requested), probe_(probe) {}

  /// Threads for the next update: `requested` or 1.
  [[nodiscard]] int next() noexcept;
  /// The update that used `threads` (a value next() returned) took `ms` for `work` units
  /// (particles x beams scored); ignored unless both are positive and finite.
  void record(int threads, double ms, double work) noexcept;

  /// The count in use when no try is due (`requested` until the serial one proved faster).
  [[nodiscard]] int preferred() const noexcept { return team_preferred_ ? team_ : 1; }

 private:
  struct Samples {
    std::array<double, kWindow> v{};
    std::size_t n = 0, next = 0;
    void add(double x) noexcept;
    [[nodiscard]] double mean() const noexcept;
  };
  /// The other count's next try comes `interval` updates from now.
  void schedule_try(std::uint64_t interval) noexcept;

  int team_;
  LoadProbe probe_;
  bool team_preferred_ = true;
  bool retry_ = false;  // the last try beat the preferred count: try again next update
  std::uint64_t updates_ = 0;
  std::uint64_t interval_ = kProbeEvery;      // updates from one try to the next
  std::uint64_t next_try_ = kProbeEvery + 1;  // the update of the next try
  Samples serial_, team_samples_;
};

}  // namespace pgmcl
