#include "diffray/dsp/crossfade_convolver.h"

#include <algorithm>
#include <limits>
#include <string>

#include "diffray/core/error.h"

namespace diffray::dsp {

namespace {

constexpr long kNever = std::numeric_limits<long>::max();
constexpr long kAlways = std::numeric_limits<long>::min();

/// The largest multiple of `block` ≤ n, for negative n too.
long floorToGrid(long n, long block) {
  const long q = n / block;
  return (n % block != 0 && n < 0 ? q - 1 : q) * block;
}

/// The smallest multiple of `block` ≥ n.
long ceilToGrid(long n, long block) { return -floorToGrid(-n, block); }

}  // namespace

template <class Multichannel>
void BasicCrossfadeConvolver<Multichannel>::init(int block_size, const std::vector<std::vector<std::vector<float>>>& irs,
                                                int input_channels, const std::vector<long>& key_frames) {
  const std::string where = "crossfade convolver";
  if (irs.empty()) throw core::InputError(where, "needs at least one impulse response");
  if (key_frames.size() != irs.size())
    throw core::InputError(where, std::to_string(irs.size()) + " impulse responses but " +
                                      std::to_string(key_frames.size()) + " key frames");
  for (size_t k = 1; k < key_frames.size(); ++k)
    if (key_frames[k] <= key_frames[k - 1])
      throw core::InputError(where, "key frames must increase strictly, but key frame " + std::to_string(k) +
                                        " (" + std::to_string(key_frames[k]) + ") follows " +
                                        std::to_string(key_frames[k - 1]));
  for (size_t k = 0; k < irs.size(); ++k) {
    if (irs[k].size() != irs.front().size())
      throw core::InputError(where, "impulse response " + std::to_string(k) + " has " +
                                        std::to_string(irs[k].size()) + " channels, impulse response 0 has " +
                                        std::to_string(irs.front().size()));
  }
  const int K = static_cast<int>(irs.size());
  // One multichannel convolver per IR; it checks the block size, the channel pairing and the samples.
  std::vector<Multichannel> convolvers(irs.size());
  for (int k = 0; k < K; ++k) convolvers[static_cast<size_t>(k)].init(block_size, irs[static_cast<size_t>(k)], input_channels);
  convolvers_ = std::move(convolvers);
  block_ = block_size;
  input_channels_ = input_channels;
  output_channels_ = convolvers_.front().outputChannels();
  key_frames_ = key_frames;
  ir_lengths_.assign(irs.size(), 0);
  start_.assign(irs.size(), kAlways);
  stop_.assign(irs.size(), kNever);
  for (int k = 0; k < K; ++k) {
    const auto i = static_cast<size_t>(k);
    ir_lengths_[i] = convolvers_[i].irLength();
    // g_k is non-zero on (t_{k−1}, t_{k+1}): the output at t_{k−1} + 1 needs the input from
    // t_{k−1} + 1 − (L_k − 1) on, so the convolver starts (from silence) at or before t_{k−1} − L_k + 2.
    if (k > 0) start_[i] = floorToGrid(key_frames_[i - 1] - ir_lengths_[i] + 1, block_);
    if (k < K - 1) stop_[i] = ceilToGrid(key_frames_[i + 1], block_);
  }
  scratch_.assign(static_cast<size_t>(block_) * static_cast<size_t>(output_channels_), 0.0f);
  silence_.assign(static_cast<size_t>(block_) * static_cast<size_t>(input_channels_), 0.0f);
  position_ = 0;
}

template <class Multichannel>
double BasicCrossfadeConvolver<Multichannel>::gain(int k, long n) const {
  const int K = irCount();
  const auto i = static_cast<size_t>(k);
  if (n <= key_frames_[i]) {
    if (k == 0) return 1.0;
    const long prev = key_frames_[i - 1];
    return n <= prev ? 0.0 : static_cast<double>(n - prev) / static_cast<double>(key_frames_[i] - prev);
  }
  if (k == K - 1) return 1.0;
  const long next = key_frames_[i + 1];
  return n >= next ? 0.0 : static_cast<double>(next - n) / static_cast<double>(next - key_frames_[i]);
}

template <class Multichannel>
void BasicCrossfadeConvolver<Multichannel>::process(const float* in, float* out, long frames) {
  const auto cin = static_cast<long>(input_channels_), cout = static_cast<long>(output_channels_);
  for (long done = 0; done < frames;) {
    // Chunks never cross the block grid, so each lies wholly inside or outside every convolver's span.
    const long to_grid = block_ - (position_ - floorToGrid(position_, block_));
    const long n = std::min(frames - done, to_grid);
    processChunk(in + done * cin, out + done * cout, n);
    done += n;
  }
}

template <class Multichannel>
void BasicCrossfadeConvolver<Multichannel>::flush(float* out, long frames) {
  const auto cout = static_cast<long>(output_channels_);
  for (long done = 0; done < frames;) {
    const long to_grid = block_ - (position_ - floorToGrid(position_, block_));
    const long n = std::min(frames - done, to_grid);
    processChunk(silence_.data(), out + done * cout, n);
    done += n;
  }
}

template <class Multichannel>
void BasicCrossfadeConvolver<Multichannel>::processChunk(const float* in, float* out, long n) {
  const long cout = output_channels_;
  std::fill(out, out + n * cout, 0.0f);
  for (size_t k = 0; k < convolvers_.size(); ++k) {
    if (position_ < start_[k] || position_ >= stop_[k]) continue;
    convolvers_[k].process(in, scratch_.data(), n);
    for (long f = 0; f < n; ++f) {
      const auto g = static_cast<float>(gain(static_cast<int>(k), position_ + f));
      if (g == 0.0f) continue;
      for (long c = 0; c < cout; ++c) out[f * cout + c] += g * scratch_[static_cast<size_t>(f * cout + c)];
    }
  }
  position_ += n;
}

template <class Multichannel>
long BasicCrossfadeConvolver<Multichannel>::tailFrames() const {
  long tail = 0;
  const int K = irCount();
  for (int k = 0; k < K; ++k) {
    const auto i = static_cast<size_t>(k);
    long m = ir_lengths_[i] - 1;  // (h_k ∗ x)[n] = 0 from position_ + L_k − 1 on
    if (k < K - 1) m = std::min(m, key_frames_[i + 1] - position_);  // g_k = 0 from t_{k+1} on
    if (m <= 0) continue;
    if (k > 0 && position_ + m - 1 <= key_frames_[i - 1]) continue;  // g_k = 0 up to t_{k−1}
    tail = std::max(tail, m);
  }
  return tail;
}

template <class Multichannel>
void BasicCrossfadeConvolver<Multichannel>::reset() {
  for (auto& c : convolvers_) c.reset();
  position_ = 0;
}

template <class Multichannel>
int BasicCrossfadeConvolver<Multichannel>::activeConvolvers() const {
  int active = 0;
  for (size_t k = 0; k < convolvers_.size(); ++k) active += position_ >= start_[k] && position_ < stop_[k];
  return active;
}

template class BasicCrossfadeConvolver<MultichannelConvolver>;
template class BasicCrossfadeConvolver<NonUniformMultichannelConvolver>;

}  // namespace diffray::dsp
