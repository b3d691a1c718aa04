#pragma once
// CrossfadeConvolver: time-varying convolution through K impulse responses h_0 … h_{K−1} placed at key frames
// t_0 < t_1 < … < t_{K−1} (sample indices of the input, counted from its first frame = 0):
//     y[n] = Σ_k g_k(n)·(h_k ∗ x)[n],
// with hat-function gains: g_k(t_k) = 1, linear down to 0 at t_{k−1} and t_{k+1}; g_0 = 1 before t_0 and
// g_{K−1} = 1 after t_{K−1}. The gains sum to 1 at every n and are continuous, so the output moves from one
// IR's sound to the next without a click (the door's closing: one IR per opening).
//  * Outputs are crossfaded, not IR coefficients, and every convolver sees the whole input history it needs:
//    convolver k runs only on [t_{k−1} − L_k + 1, t_{k+1}) (L_k its IR length; both ends widened to the
//    block grid), started from silence, so the result is identical to running all K convolvers all the time
//    while only the ones whose span covers n cost anything (2 when key frames are further apart than the
//    IRs are long).
//  * Each IR k is multichannel as dsp::MultichannelConvolver takes it (irs[k][m] = channel m of IR k, all
//    the same length within IR k); all K have the same channel count, their lengths may differ. Channel
//    pairing with the input as in multichannel_convolver.h.
//  * Streaming: init() once, then process() any number of times with any frame counts (interleaved float,
//    zero latency, allocation-free); when the input is over, flush() feeds silence for tailFrames() frames to
//    get the rest of the output. A call with a multiple of blockSize() frames costs the least.
//  * Memory: K MultichannelConvolvers are built in init() (about 32·L_k bytes per IR channel each).
//  * Engines: CrossfadeConvolver runs uniformly partitioned convolvers (the offline door); the
//    NonUniformCrossfadeConvolver runs dsp::NonUniformMultichannelConvolver (non_uniform_convolver.h), whose
//    cost per block grows with the log of the IR's length: the real-time door (audio/playback.h).
// Thread-safety: one object is used by one thread at a time.
#include <vector>

#include "diffray/dsp/multichannel_convolver.h"

namespace diffray::dsp {

template <class Multichannel>
class BasicCrossfadeConvolver {
 public:
  /// `irs[k][m]`: channel m of IR k (K = irs.size() ≥ 1, every IR with the same channel count ≥ 1, each
  /// channel ≥ 1 finite sample); `key_frames[k]`: where IR k is heard alone (strictly increasing, K
  /// values; any sign). Blocks of `block_size` frames (1 … 2^20). Throws core::InputError for bad input.
  /// May be called again to start over.
  void init(int block_size, const std::vector<std::vector<std::vector<float>>>& irs, int input_channels,
            const std::vector<long>& key_frames);

  /// Convolves the next `frames` interleaved input frames (inputChannels() samples each) into `frames`
  /// interleaved output frames (outputChannels() samples each). `in` and `out` must not overlap.
  /// Allocation-free, lock-free, no I/O.
  void process(const float* in, float* out, long frames);

  /// process() with `frames` frames of silence as input: the output's tail once the input is over.
  /// Allocation-free.
  void flush(float* out, long frames);

  /// Frames of output still possibly non-zero if the input ended now (i.e. after the frames fed so far):
  /// max over k of min(L_k − 1, t_{k+1} − position()), at least 0. Feeding this many frames to flush()
  /// completes the output; everything after it is exactly zero.
  long tailFrames() const;

  /// Back to the state right after init(): position 0, no input history. Allocation-free.
  void reset();

  /// The gain g_k(n) of IR k at input frame n (the hat functions above).
  double gain(int k, long n) const;

  int inputChannels() const { return input_channels_; }
  int outputChannels() const { return output_channels_; }
  int blockSize() const { return block_; }
  int irCount() const { return static_cast<int>(convolvers_.size()); }
  const std::vector<long>& keyFrames() const { return key_frames_; }
  /// Frames fed so far (process() and flush()).
  long position() const { return position_; }
  /// Convolvers that have started and not yet stopped (the cost of the next frames).
  int activeConvolvers() const;

 private:
  /// Runs one chunk [position_, position_ + n) that lies inside one block of the grid.
  void processChunk(const float* in, float* out, long n);

  int block_ = 0;
  int input_channels_ = 0;
  int output_channels_ = 0;
  std::vector<Multichannel> convolvers_;  ///< one per IR
  std::vector<long> key_frames_;
  std::vector<long> ir_lengths_;   ///< L_k
  std::vector<long> start_;        ///< first frame convolver k is fed (on the block grid)
  std::vector<long> stop_;         ///< frame convolver k is no longer fed (on the block grid)
  std::vector<float> scratch_;     ///< one block of one convolver's output, interleaved
  std::vector<float> silence_;     ///< one block of input zeros, for flush()
  long position_ = 0;
};

using CrossfadeConvolver = BasicCrossfadeConvolver<MultichannelConvolver>;
using NonUniformCrossfadeConvolver = BasicCrossfadeConvolver<NonUniformMultichannelConvolver>;
extern template class BasicCrossfadeConvolver<MultichannelConvolver>;
extern template class BasicCrossfadeConvolver<NonUniformMultichannelConvolver>;

}  // namespace diffray::dsp
