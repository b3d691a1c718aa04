#include "diffray/dsp/non_uniform_convolver.h"

#include <algorithm>
#include <string>

#include "diffray/core/error.h"

namespace diffray::dsp {

// A tail stage convolves x with its segment g[k] = h[offset + k] in whole blocks of `block` samples. Its
// input is x' = (phase zeros, then x), so its output z'[τ] = (x * g)[τ − phase], and the stage's share of
// y[t] is (x * g)[t − offset] = z'[t − offset + phase]. After input sample t, z' is known up to the last
// complete block, i.e. up to index ≥ t + phase − block; reading index t − offset + phase is therefore in
// hand whenever offset ≥ block (here offset = block). The ring keeps z' indices [r − offset, r + block).
struct NonUniformConvolver::TailStage {
  PartitionedConvolver conv;
  long block = 0;
  long offset = 0;  ///< first IR sample of the segment
  long phase = 0;   ///< zeros the input starts with (block / 2: staggers the stages' heavy calls)
  std::vector<float> input;      ///< the current block of x', `fill` samples so far
  long fill = 0;
  std::vector<float> block_out;  ///< z' of the block just completed
  std::vector<float> ring;       ///< z'[i] at ring[i mod ring.size()]
  long blocks_done = 0;

  void reset() {
    conv.reset();
    std::fill(input.begin(), input.end(), 0.0f);
    std::fill(ring.begin(), ring.end(), 0.0f);
    fill = phase;
    blocks_done = 0;
  }
};

NonUniformConvolver::NonUniformConvolver() = default;
NonUniformConvolver::~NonUniformConvolver() = default;

void NonUniformConvolver::init(int block_size, const float* ir, long ir_length) {
  if (ir_length < 1 || ir == nullptr) throw core::InputError("convolver", "the impulse response is empty");
  tails_.clear();
  // Stage s ≥ 1 has block N_s = B·8^s and starts at IR sample N_s; the head covers [0, N_1).
  const long max_block = std::max<long>(kMaxTailBlock, block_size);
  std::vector<long> starts;
  for (long n = static_cast<long>(block_size) * kGrowth; block_size >= 1 && n <= max_block && n < ir_length;
       n *= kGrowth)
    starts.push_back(n);
  const long head_length = starts.empty() ? ir_length : starts.front();
  head_.init(block_size, ir, head_length);  // validates block_size and the head's samples
  for (size_t s = 0; s < starts.size(); ++s) {
    auto stage = std::make_unique<TailStage>();
    stage->block = starts[s];
    stage->offset = starts[s];
    stage->phase = stage->block / 2;
    const long end = s + 1 < starts.size() ? starts[s + 1] : ir_length;
    stage->conv.init(static_cast<int>(stage->block), ir + stage->offset, end - stage->offset);
    stage->input.assign(static_cast<size_t>(stage->block), 0.0f);
    stage->block_out.assign(static_cast<size_t>(stage->block), 0.0f);
    stage->ring.assign(static_cast<size_t>(stage->offset + stage->block), 0.0f);
    stage->reset();
    tails_.push_back(std::move(stage));
  }
  ir_length_ = ir_length;
  time_ = 0;
}

long NonUniformConvolver::stageBlockSize(int s) const {
  DIFFRAY_CHECK(s >= 0 && s < stages());
  return s == 0 ? head_.blockSize() : tails_[static_cast<size_t>(s - 1)]->block;
}

void NonUniformConvolver::reset() {
  head_.reset();
  for (auto& stage : tails_) stage->reset();
  time_ = 0;
}

void NonUniformConvolver::process(const float* in, float* out, long n) {
  long done = 0;
  while (done < n) {
    // A chunk never crosses a tail stage's block boundary.
    long count = n - done;
    for (const auto& stage : tails_) count = std::min(count, stage->block - stage->fill);
    // The input goes into the stages before the head writes `out`, which may be `in`.
    for (auto& stage : tails_) {
      std::copy(in + done, in + done + count, stage->input.begin() + stage->fill);
      stage->fill += count;
    }
    head_.process(in + done, out + done, count);
    for (auto& stage : tails_) runTail(*stage, out + done, count);
    time_ += count;
    done += count;
  }
}

// Adds the stage's share of y[time_ … time_ + count) to `out`, then computes the block just completed.
void NonUniformConvolver::runTail(TailStage& stage, float* out, long count) {
  const long size = static_cast<long>(stage.ring.size());
  long r = time_ - stage.offset + stage.phase;
  long i = 0;
  if (r < 0) {  // before the segment's first sample can arrive
    i = std::min(count, -r);
    r += i;
  }
  long at = r % size;
  for (; i < count; ++i) {
    out[i] += stage.ring[static_cast<size_t>(at)];
    if (++at == size) at = 0;
  }
  if (stage.fill < stage.block) return;
  stage.conv.process(stage.input.data(), stage.block_out.data(), stage.block);
  long w = (stage.blocks_done * stage.block) % size;
  for (long k = 0; k < stage.block; ++k) {
    stage.ring[static_cast<size_t>(w)] = stage.block_out[static_cast<size_t>(k)];
    if (++w == size) w = 0;
  }
  ++stage.blocks_done;
  stage.fill = 0;
}

}  // namespace diffray::dsp
