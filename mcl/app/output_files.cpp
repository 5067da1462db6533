#include "output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "interrupt.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::app {
namespace {

namespace fs = std::filesystem;

fs::path normalised(const std::string& p) {
  std::error_code ec;
  fs::path abs = fs::absolute(p, ec);
  if (ec) return fs::path(p).lexically_normal();
  fs::path canon = fs::weakly_canonical(abs, ec);
  return ec ? abs.lexically_normal() : canon;
}

/// The folder a file goes in, created if needed.
fs::path make_parent(const std::string& target, const std::string& option) {
  fs::path parent = fs::path(target).parent_path();
  if (parent.empty()) parent = ".";
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (!fs::is_directory(parent)) {
    throw io::IoError(option + ": cannot create the folder '" + parent.string() + "' for " +
                      target + (ec ? " (" + ec.message() + ")" : std::string(" (not a folder)")));
  }
  return parent;
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool eq = fs::equivalent(a, b, ec);
    if (!ec) return eq;
  }
  return normalised(a) == normalised(b);
}

OutputFiles::~OutputFiles() {
  if (!committed_) remove_temps();
}

OutputFiles::Entry* OutputFiles::find(const std::string& target) {
  for (Entry& e : outputs_) {
    if (e.target == target) return &e;
  }
  return nullptr;
}

void OutputFiles::input(const std::string& path, const std::string& option) {
  if (path.empty()) return;
  for (const Entry& e : outputs_) {
    if (same_file(e.target, path)) {
      throw io::UsageError(e.option + ": " + e.target + " is also the input " + option + " " +
                           path + "; refusing to overwrite an input (choose another output)");
    }
  }
  inputs_.push_back({path, option});
}

std::string OutputFiles::add(const std::string& target, const std::string& option) {
  if (target.empty()) throw io::UsageError(option + ": the output path is empty");
  for (const Input& in : inputs_) {
    if (same_file(target, in.path)) {
      throw io::UsageError(option + ": " + target + " is also the input " + in.option + " " +
                           in.path + "; refusing to overwrite an input (choose another output)");
    }
  }
  for (const Entry& e : outputs_) {
    if (same_file(target, e.target)) {
      throw io::UsageError(option + ": " + target + " is also the output " + e.option + " " +
                           e.target + "; two outputs cannot share one file");
    }
  }
  std::error_code ec;
  const fs::file_status st = fs::status(target, ec);
  if (fs::is_directory(st)) {
    throw io::UsageError(option + ": " + target + " is a folder, not a file name");
  }
  Entry e{target, option, "", -1, false};
  if (fs::exists(st) && !fs::is_regular_file(st)) {
    outputs_.push_back(e);  // a device or FIFO: written in place
    return target;
  }
  const fs::path parent = make_parent(target, option);
  static int counter = 0;
  const std::string name = fs::path(target).filename().string();
  e.temp = (parent /
            (".pgmcl-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "." + name))
               .string();
  const int fd = ::open(e.temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    throw io::IoError(option + ": cannot write in the folder '" + parent.string() + "' (" +
                      std::strerror(errno) + ")");
  }
  ::close(fd);
  e.slot = register_temp_file(e.temp);
  outputs_.push_back(e);
  return e.temp;
}

void OutputFiles::drop(const std::string& target) {
  Entry* e = find(target);
  if (e == nullptr) return;
  e->dropped = true;
  if (!e->temp.empty()) {
    std::remove(e->temp.c_str());
    unregister_temp_file(e->slot);
    e->temp.clear();
  }
}

void OutputFiles::commit() {
  const SignalBlock hold;
  if (!keep_when_interrupted_) check_interrupt();
  for (Entry& e : outputs_) {
    if (e.dropped) {
      std::error_code ec;
      if (fs::is_regular_file(e.target, ec)) fs::remove(e.target, ec);
      continue;
    }
    if (e.temp.empty()) continue;
    if (std::rename(e.temp.c_str(), e.target.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      throw io::IoError(e.option + ": cannot move the finished " + e.target + " into place (" +
                        why + ")");
    }
    unregister_temp_file(e.slot);
    e.temp.clear();
  }
  committed_ = true;
}

void OutputFiles::remove_temps() noexcept {
  for (Entry& e : outputs_) {
    if (e.temp.empty()) continue;
    std::remove(e.temp.c_str());
    unregister_temp_file(e.slot);
    e.temp.clear();
  }
}

}  // namespace pgmcl::app
