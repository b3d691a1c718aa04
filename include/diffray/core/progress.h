#pragma once
// A progress bar on stderr, drawn only when stderr is a terminal (never in CI logs or pipes).
// add() is thread-safe and cheap; redraws are rate-limited to about 10 per second, and work finished
// before the first redraw (100 ms) leaves nothing on the terminal.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
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
  bool drawn_ = false;  ///< a redraw happened (under mutex_): work done in under 100 ms leaves no line
};

/// For work whose size is known only once it starts (a WBSDF table learns its row count from its
/// layout): returns a callback that draws a bar labelled `label`, created at the first call with that
/// call's `total`, advanced by one per call, and finished when the last copy of the callback is destroyed.
/// Thread-safe.
std::function<void(std::uint64_t total)> progressOfUnknownSize(std::string label);
/// Makes one such callback per piece of work from its label (progressOfUnknownSize is one): what library
/// code that runs several long steps takes, so that the caller decides whether bars are drawn.
using ProgressFactory = std::function<std::function<void(std::uint64_t total)>(const std::string& label)>;

}  // namespace diffray::core
