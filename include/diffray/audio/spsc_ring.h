#pragma once
// SpscFrameRing: a lock-free single-producer / single-consumer ring of interleaved float frames, the hand-off
// between a reader thread and an audio callback. Capacity is a power of two of frames, fixed at
// construction (the only allocation). push() is called by one producer thread, pop() by one consumer
// thread; neither locks, blocks or allocates: each moves what fits and returns how many frames it moved.
// The positions are monotonic frame counters in std::atomic<size_t> (lock-free on every platform diffray
// builds for); the producer publishes with release and the consumer reads with acquire, so frames written
// before a push() are visible to the pop() that sees them.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <vector>

namespace diffray::audio {

class SpscFrameRing {
 public:
  /// Room for at least `min_frames` frames of `channels` samples (rounded up to a power of two).
  SpscFrameRing(long min_frames, int channels) : channels_(static_cast<size_t>(channels)) {
    size_t frames = 1;
    while (frames < static_cast<size_t>(std::max(1L, min_frames))) frames *= 2;
    mask_ = frames - 1;
    data_.assign(frames * channels_, 0.0f);
  }

  long capacity() const { return static_cast<long>(mask_ + 1); }
  int channels() const { return static_cast<int>(channels_); }
  /// Frames ready to pop (exact for the consumer, a lower bound for anyone else).
  long available() const {
    return static_cast<long>(write_.load(std::memory_order_acquire) - read_.load(std::memory_order_acquire));
  }

  /// Producer: copies up to `frames` frames in; returns how many fitted.
  long push(const float* in, long frames) {
    const size_t w = write_.load(std::memory_order_relaxed);
    const size_t r = read_.load(std::memory_order_acquire);
    const size_t n = std::min(static_cast<size_t>(frames), mask_ + 1 - (w - r));
    for (size_t i = 0; i < n; ++i)
      std::copy(in + i * channels_, in + (i + 1) * channels_, data_.begin() + static_cast<long>(((w + i) & mask_) * channels_));
    write_.store(w + n, std::memory_order_release);
    return static_cast<long>(n);
  }

  /// Consumer: copies up to `frames` frames out; returns how many there were.
  long pop(float* out, long frames) {
    const size_t r = read_.load(std::memory_order_relaxed);
    const size_t w = write_.load(std::memory_order_acquire);
    const size_t n = std::min(static_cast<size_t>(frames), w - r);
    for (size_t i = 0; i < n; ++i) {
      const float* src = data_.data() + ((r + i) & mask_) * channels_;
      std::copy(src, src + channels_, out + i * channels_);
    }
    read_.store(r + n, std::memory_order_release);
    return static_cast<long>(n);
  }

 private:
  size_t channels_;
  size_t mask_ = 0;
  std::vector<float> data_;
  alignas(64) std::atomic<size_t> write_{0};  ///< frames ever pushed (written by the producer only)
  alignas(64) std::atomic<size_t> read_{0};   ///< frames ever popped (written by the consumer only)
};

}  // namespace diffray::audio
