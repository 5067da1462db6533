#pragma once
/// A command's output files, all or nothing.
///
/// Every output is registered before any work starts (add): its folder is created and a
/// temporary file is made beside the target (".pgmcl-<pid>-<k>.<name>", so the extension
/// still picks the format), which proves the folder writable and is what the command
/// writes. commit() renames them all into place, with SIGINT / SIGTERM held back, and
/// removes the targets the run did not produce (drop), so no stale file of an earlier run
/// (error.png) survives beside the new set. Until commit the earlier files are untouched;
/// a failure or an interruption removes the temporaries (destructor).
///
/// Inputs are registered too (input): an output that is an input, or two outputs that are
/// one file, is a usage error naming both options, before anything is written.
///
/// An existing target that is not a regular file (/dev/null, /dev/stdout, a FIFO) is written
/// in place: a device cannot be replaced by a rename.

#include <string>
#include <vector>

namespace pgmcl::app {

class OutputFiles {
 public:
  OutputFiles() = default;
  ~OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  /// Registers `target`, given by `option` ("--out"); returns the path to write it at.
  /// Throws UsageError for a target that is a folder or the same file as an input or an
  /// earlier output, IoError when its folder cannot be created or written.
  std::string add(const std::string& target, const std::string& option);

  /// Registers an input the outputs must not overwrite (an empty path is ignored).
  void input(const std::string& path, const std::string& option);

  /// `target` is not produced by this run: its temporary file goes, and commit removes an
  /// earlier file of that name.
  void drop(const std::string& target);

  /// Renames every written output into place and removes the dropped ones. Throws IoError
  /// if a rename fails (the files renamed before it stay renamed), and Interrupted (nothing
  /// renamed) once SIGINT / SIGTERM arrived, unless keep_when_interrupted() was called.
  void commit();

  /// The outputs of a stopped run are still worth keeping (localize: the run so far).
  void keep_when_interrupted() noexcept { keep_when_interrupted_ = true; }

  [[nodiscard]] bool committed() const noexcept { return committed_; }

 private:
  struct Entry {
    std::string target;
    std::string option;
    std::string temp;  ///< empty: written in place (not a regular file)
    int slot = -1;     ///< interrupt.hpp registry
    bool dropped = false;
  };
  struct Input {
    std::string path;
    std::string option;
  };
  [[nodiscard]] Entry* find(const std::string& target);
  void remove_temps() noexcept;

  std::vector<Entry> outputs_;
  std::vector<Input> inputs_;
  bool committed_ = false;
  bool keep_when_interrupted_ = false;
};

/// True when `a` and `b` name the same file: the same inode when both exist (hard and
/// symbolic links included), else the same normalised absolute path.
[[nodiscard]] bool same_file(const std::string& a, const std::string& b);

}  // namespace pgmcl::app
