#pragma once
// Shared helpers for the libFuzzer harnesses: a per-process scratch directory for APIs that
// read files, and the failure path for broken invariants (abort = a crash libFuzzer keeps).

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

namespace pgmcl::fuzz {

/// Reports a broken invariant and aborts, so libFuzzer saves the input as a crash.
[[noreturn]] inline void fail(const char* what, const std::string& detail = {}) {
  std::fprintf(stderr, "pgmcl fuzz invariant violated: %s %s\n", what, detail.c_str());
  std::abort();
}

/// An exception the API does not document escaped: report its type and message, abort.
[[noreturn]] inline void undocumented(const std::exception& e) {
  fail("undocumented exception escaped:", e.what());
}

/// A private directory under $TMPDIR, else /dev/shm (file I/O in memory: ~10x the
/// executions per second of a disk-backed /tmp), else /tmp. Removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    const char* env = std::getenv("TMPDIR");
    std::string base = env != nullptr && *env != '\0' ? env : "";
    if (base.empty()) base = access("/dev/shm", W_OK | X_OK) == 0 ? "/dev/shm" : "/tmp";
    std::string templ = base + "/pgmcl_fuzz_XXXXXX";
    if (mkdtemp(templ.data()) == nullptr) fail("mkdtemp failed", templ);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return std::filesystem::path(templ);
  }();
  return dir;
}

/// Writes `bytes` to scratch_dir()/name; false if the name cannot be created (too long...).
inline bool try_write_scratch(const std::string& name, std::string_view bytes) {
  std::ofstream out(scratch_dir() / name, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  return static_cast<bool>(out);
}

/// Writes `bytes` to scratch_dir()/name (a name the harness chose) and returns the path.
inline std::string write_scratch(const std::string& name, std::string_view bytes) {
  if (!try_write_scratch(name, bytes)) fail("cannot write scratch file", name);
  return (scratch_dir() / name).string();
}

/// Removes scratch_dir()/name when it goes out of scope.
class ScratchFile {
 public:
  explicit ScratchFile(std::string name) : name_(std::move(name)) {}
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(scratch_dir() / name_, ec);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

 private:
  std::string name_;
};

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace pgmcl::fuzz

namespace pgmcl::fuzz {

/// `parse()`'s value, or nullopt when it throws the documented exception E; any other
/// exception is a finding.
template <class E, class F>
auto accepted(F&& parse) -> std::optional<decltype(parse())> {
  try {
    return parse();
  } catch (const E&) {
    return std::nullopt;
  } catch (const std::exception& e) {
    undocumented(e);
  }
}

/// Runs `parse` (a callable returning a value or throwing) and returns its outcome as
/// "ok" or "<line>:<field>" of the FormatError-like exception E it threw.
template <class E, class F>
std::string outcome(F&& parse) {
  try {
    (void)parse();
    return "ok";
  } catch (const E& e) {
    return std::to_string(e.line()) + ":" + e.field();
  }
}

}  // namespace pgmcl::fuzz
