#include "diffray/dsp/multichannel_convolver.h"

#include <algorithm>
#include <string>

#include <tbb/parallel_for.h>

#include "diffray/core/error.h"

namespace diffray::dsp {

template <class Engine>
int BasicMultichannelConvolver<Engine>::outputChannels(int ir_channels, int input_channels) {
  if (ir_channels < 1 || input_channels < 1)
    throw core::InputError("convolver", "the impulse response and the input need at least one channel each");
  if (ir_channels == 1 || ir_channels == input_channels) return input_channels;
  if (input_channels == 1) return ir_channels;
  throw core::InputError("convolver", "cannot pair a " + std::to_string(ir_channels) + "-channel impulse response with a " +
                                          std::to_string(input_channels) +
                                          "-channel input (a mono IR, a mono input, or equal channel counts)");
}

template <class Engine>
void BasicMultichannelConvolver<Engine>::init(int block_size, const std::vector<std::vector<float>>& ir, int input_channels) {
  const int ir_channels = static_cast<int>(ir.size());
  const int outputs = outputChannels(ir_channels, input_channels);
  for (const auto& channel : ir)
    if (channel.size() != ir.front().size())
      throw core::InputError("convolver", "the impulse response's channels differ in length");
  convolvers_.clear();
  source_.clear();
  for (int o = 0; o < outputs; ++o) {
    convolvers_.push_back(std::make_unique<Engine>());
    convolvers_.back()->init(block_size, ir[static_cast<size_t>(ir_channels == 1 ? 0 : o)]);
    source_.push_back(input_channels == 1 ? 0 : o);
  }
  input_channels_ = input_channels;
  block_ = block_size;
  scratch_in_.assign(static_cast<size_t>(block_size), 0.0f);
  channel_scratch_.assign(convolvers_.size(), std::vector<float>(static_cast<size_t>(block_size), 0.0f));
}

// In-place convolution of the de-interleaved block: the engines allow in == out.
template <class Engine>
void BasicMultichannelConvolver<Engine>::processChannel(long o, const float* in, float* out, long frames, float* scratch) {
  const auto cin = static_cast<long>(input_channels_);
  const auto cout = static_cast<long>(convolvers_.size());
  const long c = source_[static_cast<size_t>(o)];
  Engine& conv = *convolvers_[static_cast<size_t>(o)];
  for (long start = 0; start < frames; start += block_) {
    const long count = std::min<long>(block_, frames - start);
    for (long f = 0; f < count; ++f) scratch[f] = in[(start + f) * cin + c];
    conv.process(scratch, scratch, count);
    for (long f = 0; f < count; ++f) out[(start + f) * cout + o] = scratch[f];
  }
}

template <class Engine>
void BasicMultichannelConvolver<Engine>::process(const float* in, float* out, long frames) {
  for (long o = 0; o < static_cast<long>(convolvers_.size()); ++o) processChannel(o, in, out, frames, scratch_in_.data());
}

template <class Engine>
void BasicMultichannelConvolver<Engine>::processParallel(const float* in, float* out, long frames) {
  tbb::parallel_for(0L, static_cast<long>(convolvers_.size()), [&](long o) {
    processChannel(o, in, out, frames, channel_scratch_[static_cast<size_t>(o)].data());
  });
}

template <class Engine>
void BasicMultichannelConvolver<Engine>::reset() {
  for (auto& c : convolvers_) c->reset();
}

template class BasicMultichannelConvolver<PartitionedConvolver>;
template class BasicMultichannelConvolver<NonUniformConvolver>;

}  // namespace diffray::dsp
