#pragma once
// Shared by the tests: a fresh temporary directory (emptied if a crashed run left one), removed with
// everything in it at scope exit, so an early return or a failed assertion leaves nothing behind.
#include <unistd.h>

#include <filesystem>
#include <iterator>
#include <string>

namespace diffray::test {

struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag)
      : path(std::filesystem::temp_directory_path() / ("diffray_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path / name).string(); }
  int entries() const {
    return static_cast<int>(
        std::distance(std::filesystem::directory_iterator(path), std::filesystem::directory_iterator()));
  }
};

}  // namespace diffray::test
