#pragma once
// NonUniformConvolver: one channel of non-uniformly partitioned convolution for real-time use, on the same
// contract as PartitionedConvolver (init / process / reset, zero latency, y[t] = Σ_k h[k]·x[t − k] up to
// rounding). It is built from PartitionedConvolvers, one per stage, in the spirit of FFTConvolver's
// TwoStageFFTConvolver (HiFi-LoFi/FFTConvolver):
//  * the head: block B (the audio block) over h[0, N₁), zero latency, run on every call;
//  * tail stage s = 1, 2, …: block N_s = B·8^s over h[N_s, N_{s+1}) (the last stage to the IR's end), while
//    N_s ≤ max(kMaxTailBlock, B); each tail stage is fed whole blocks of N_s samples and its output read
//    N_s samples late, which is exactly its segment's offset, so the sum stays exact and zero-latency.
// Scheduling (chosen for determinism; see impulse/README.md, "Real-time playback"): a tail stage's block is computed in
// the process() call that completes it (one PartitionedConvolver::process of N_s samples), not in a worker
// thread. The cost per call is the head's (two FFTs of 2B) plus, now and then, one tail block. To keep two
// tail blocks from landing in the same audio block, stage s starts with N_s/2 zeros already in its input
// (its block grid is shifted by half a block, and its read-out index by the same amount): with B-sized
// calls, stage s fires when t ≡ N_s/2 (mod N_s), so stages never fire in the same call.
// Real-time: process() and reset() allocate nothing, lock nothing and do no I/O; init() allocates and plans
// FFTs (under core::fftwPlannerMutex()). Samples are float in and out; each stage works in double.
// Thread-safety: one object is used by one thread at a time; distinct objects may run concurrently.
#include <memory>
#include <vector>

#include "diffray/dsp/partitioned_convolver.h"

namespace diffray::dsp {

class NonUniformConvolver {
 public:
  static constexpr int kGrowth = 8;               ///< N_{s+1} / N_s
  /// Largest tail block: bounds the cost of the call in which a tail block completes. With 2^13, a 3 s
  /// stereo IR at block 256 gets stages 256 and 2048; with 2^14 a third stage of 16384 cut the mean cost
  /// but tripled the worst call (tools/bench realtime).
  static constexpr long kMaxTailBlock = 1 << 13;

  NonUniformConvolver();
  ~NonUniformConvolver();
  NonUniformConvolver(const NonUniformConvolver&) = delete;
  NonUniformConvolver& operator=(const NonUniformConvolver&) = delete;

  /// Prepares convolution with `ir` (ir_length ≥ 1 finite samples) for calls of (ideally) `block_size`
  /// samples (1 … 2^20). Throws core::InputError for a bad size or a non-finite IR sample. May be called
  /// again; the state is cleared.
  void init(int block_size, const float* ir, long ir_length);
  void init(int block_size, const std::vector<float>& ir) { init(block_size, ir.data(), static_cast<long>(ir.size())); }

  /// Convolves the next `n` input samples into `n` output samples (any n; `in` and `out` may be the same
  /// buffer). Allocation-free, lock-free, no I/O. Before init() the output is silence.
  void process(const float* in, float* out, long n);

  /// Forgets the past (as if freshly initialised). Allocation-free.
  void reset();

  int blockSize() const { return head_.blockSize(); }
  long irLength() const { return ir_length_; }
  /// Number of stages, the head included (1 = plain uniform partitioning).
  int stages() const { return 1 + static_cast<int>(tails_.size()); }
  /// Block size of stage s (0 = head).
  long stageBlockSize(int s) const;

 private:
  struct TailStage;
  void runTail(TailStage& stage, float* out, long count);

  PartitionedConvolver head_;
  std::vector<std::unique_ptr<TailStage>> tails_;
  long ir_length_ = 0;
  long time_ = 0;  ///< samples processed since init() / reset()
};

}  // namespace diffray::dsp
