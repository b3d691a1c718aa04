#pragma once
// Output files are written whole or not at all: content goes to a temporary file beside the target,
// which is renamed over the target only when complete. A failed write leaves no file behind.
#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "diffray/core/error.h"
#include "diffray/core/temp_files.h"

namespace diffray::core {

/// Calls `write(stream)` on a temporary file next to `path`, then renames it to `path`.
/// Throws InputError (naming `path`) if the file cannot be written; nothing is left behind then.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// A command's set of output files, replaced together. write() has each file written under a staging name
/// beside its target (stagingName: the extension kept, for writers that look at it), and commit() renames
/// them all over their targets once every one is written. If the command fails before commit() (an
/// exception unwinds this object), the staged files are removed and the targets are left as they were:
/// a failed rerun keeps the previous run's outputs, and a first run leaves nothing. Not thread-safe (one
/// thread calls its members; writeEach runs its writers on TBB's pool).
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();
  /// Calls write_file(staging path) for the target `path`; the file appears at `path` on commit(). An
  /// InputError from the writer is rethrown naming `path` where it named the staging file.
  template <class WriteFile>
  void write(const std::string& path, WriteFile&& write_file) {
    const std::string staging = stagingName(path, staged_.size());
    staged_.emplace_back(staging, path);
    registered_.emplace_back(staging);  // deleted if the program is interrupted before commit()
    try {
      write_file(staging);
    } catch (const InputError& e) {
      rethrowNaming(e, staging, path);
    }
  }
  /// write() for each of `paths` in order, the files written in parallel: write_file(i, staging path of
  /// paths[i]), each call alone with its file. If writers fail, one of their InputErrors is rethrown.
  template <class WriteFile>
  void writeEach(const std::vector<std::string>& paths, WriteFile&& write_file) {
    std::vector<std::string> staging;
    for (const std::string& path : paths) {
      staging.push_back(stagingName(path, staged_.size()));
      staged_.emplace_back(staging.back(), path);
      registered_.emplace_back(staging.back());
    }
    tbb::parallel_for(std::size_t{0}, paths.size(), [&](std::size_t i) {
      try {
        write_file(i, staging[i]);
      } catch (const InputError& e) {
        rethrowNaming(e, staging[i], paths[i]);
      }
    });
  }
  /// Renames every staged file over its target, in the order written. Throws InputError naming the target
  /// if a rename fails: the files renamed before it stay replaced (the set is then mixed), the rest are
  /// removed.
  void commit();
  /// The targets commit() put in place, in order.
  const std::vector<std::string>& committed() const { return committed_; }
  /// The staging name of output number `index` of this process for `path`: "dir/name.ext" →
  /// "dir/name.part<pid>-<index>.ext".
  static std::string stagingName(const std::string& path, std::size_t index);

 private:
  [[noreturn]] static void rethrowNaming(const InputError& e, const std::string& staging, const std::string& path);
  std::vector<std::pair<std::string, std::string>> staged_;  ///< (staging, target), not yet renamed
  std::vector<TempRegistration> registered_;                 ///< the staging names, for an interrupt
  std::vector<std::string> committed_;
};

}  // namespace diffray::core
