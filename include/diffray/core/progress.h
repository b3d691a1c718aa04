#pragma once
// A progress bar on stderr, drawn only when stderr is a terminal (never in CI logs or pipes).
// add() is thread-safe and cheap; redraws are rate-limited to about 10 per second.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace diffray::core {

class Progress {
 public:
  Progress(std::string label, std::uint64_t total);
  ~Progress();
  void add(std::uint64_t done);
  void finish();

 private:
  void draw(std::uint64_t done);
  std::string label_;
  std::uint64_t total_;
  bool enabled_;
  std::atomic<std::uint64_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool finished_ = false;
};

}  // namespace diffray::core
