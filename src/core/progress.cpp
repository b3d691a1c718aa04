#include "diffray/core/progress.h"

#include <unistd.h>

#include <cstdio>
#include <memory>

namespace diffray::core {

Progress::Progress(std::string label, std::uint64_t total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) == 1) {
  start_ = last_draw_ = std::chrono::steady_clock::now();
}

Progress::~Progress() { finish(); }

void Progress::add(std::uint64_t done) {
  const std::uint64_t now_done = done_.fetch_add(done) + done;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  draw(now_done);
}

void Progress::draw(std::uint64_t done) {
  drawn_ = true;
  const double frac = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
  const int width = 30;
  const int filled = static_cast<int>(frac * width);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, '.');
  std::fprintf(stderr, "\r%s [%s] %5.1f%%  %.1fs elapsed, %.1fs left ", label_.c_str(), bar.c_str(),
               100.0 * frac, elapsed, eta);
  std::fflush(stderr);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!enabled_ || finished_) return;
  finished_ = true;
  if (!drawn_) return;  // done before the first redraw (100 ms): no bar to complete, no line left behind
  draw(done_.load());
  std::fprintf(stderr, "\n");
}

std::function<void(std::uint64_t)> progressOfUnknownSize(std::string label) {
  struct State {  // shared by every copy of the callback; the bar ends with the last copy
    std::string label;
    std::once_flag started;
    std::unique_ptr<Progress> bar;
  };
  auto state = std::make_shared<State>();
  state->label = std::move(label);
  return [state](std::uint64_t total) {
    std::call_once(state->started, [&] { state->bar = std::make_unique<Progress>(state->label, total); });
    state->bar->add(1);
  };
}

}  // namespace diffray::core
