#pragma once
// Shared by the libFuzzer harnesses: the readers under test take a file name, so each input is written to
// one file in this process's own temporary folder (named with the process id, removed at exit) first.
// A harness accepts core::InputError (bad input refused in one line, what the readers promise) and lets
// every other exception, crash or sanitizer report through as a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace diffray::fuzz {

/// Writes `data` to NAME in the harness's temporary folder and returns the file's path.
inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
  struct Folder {
    std::filesystem::path path = std::filesystem::temp_directory_path() /
                                 ("diffray_fuzz_" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() { std::filesystem::remove_all(path); }
  };
  static const Folder folder;
  const std::string file = (folder.path / name).string();
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                static_cast<std::streamsize>(size));
  return file;
}

}  // namespace diffray::fuzz
