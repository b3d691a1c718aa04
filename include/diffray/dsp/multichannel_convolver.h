#pragma once
// MultichannelConvolver: interleaved multichannel convolution built from one single-channel engine per
// output channel (same contract: init / process / reset, zero latency, nothing allocated in process()).
// The engine is a template parameter: MultichannelConvolver uses PartitionedConvolver (uniform partitions,
// for offline work), NonUniformMultichannelConvolver uses NonUniformConvolver (real-time playback). Both are
// instantiated in multichannel_convolver.cpp; an Engine offers init(int, const std::vector<float>&),
// process(const float*, float*, long), reset() and irLength().
// How an M-channel impulse response meets a C-channel input (outputChannels()):
//  * M = 1: the one IR is applied to every input channel (C outputs);
//  * M = C: channel-wise, IR channel c on input channel c (C outputs; stereo IR on stereo input);
//  * C = 1: the mono input through every IR channel (M outputs; e.g. a binaural or B-format IR);
//  * any other pairing is refused (core::InputError).
// Thread-safety: one object is used by one thread at a time (processParallel() fans out internally).
#include <memory>
#include <vector>

#include "diffray/dsp/non_uniform_convolver.h"
#include "diffray/dsp/partitioned_convolver.h"

namespace diffray::dsp {

template <class Engine>
class BasicMultichannelConvolver {
 public:
  /// Output channel count for an `ir_channels`-channel IR on an `input_channels`-channel input; throws
  /// core::InputError for a pairing the rules above do not cover.
  static int outputChannels(int ir_channels, int input_channels);

  /// `ir[m]` is IR channel m (all the same length ≥ 1). Blocks of `block_size` frames (see
  /// PartitionedConvolver). Throws core::InputError for an unsupported pairing or a bad IR.
  void init(int block_size, const std::vector<std::vector<float>>& ir, int input_channels);

  /// Convolves `frames` interleaved input frames (inputChannels() samples each) into `frames` interleaved
  /// output frames (outputChannels() samples each). `in` and `out` must not overlap. Allocation-free.
  void process(const float* in, float* out, long frames);

  /// Offline: the same result as process() (bit for bit), with the output channels convolved concurrently
  /// on TBB's thread pool (all cores unless a core::ThreadLimit is alive). Task scheduling may allocate
  /// and block: not for a real-time callback. Call it with many blocks at once (e.g. 8·block frames) so
  /// the threads' start-up is paid rarely.
  void processParallel(const float* in, float* out, long frames);

  void reset();

  int inputChannels() const { return input_channels_; }
  int outputChannels() const { return static_cast<int>(convolvers_.size()); }
  long irLength() const { return convolvers_.empty() ? 0 : convolvers_.front()->irLength(); }

 private:
  int input_channels_ = 0;
  int block_ = 0;
  std::vector<std::unique_ptr<Engine>> convolvers_;  ///< one per output channel
  std::vector<int> source_;               ///< input channel feeding output channel o
  std::vector<float> scratch_in_;         ///< one block of one channel, de-interleaved (process())
  std::vector<std::vector<float>> channel_scratch_;  ///< processParallel: one block per output channel

  /// Output channel o for frames [0, frames) through `scratch` (one block of room).
  void processChannel(long o, const float* in, float* out, long frames, float* scratch);
};

using MultichannelConvolver = BasicMultichannelConvolver<PartitionedConvolver>;
using NonUniformMultichannelConvolver = BasicMultichannelConvolver<NonUniformConvolver>;
extern template class BasicMultichannelConvolver<PartitionedConvolver>;
extern template class BasicMultichannelConvolver<NonUniformConvolver>;

}  // namespace diffray::dsp
