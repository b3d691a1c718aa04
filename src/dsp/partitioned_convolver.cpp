#include "diffray/dsp/partitioned_convolver.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>

#include "diffray/core/error.h"
#include "diffray/core/fftw_planner.h"

namespace diffray::dsp {

namespace {

constexpr int kMaxBlock = 1 << 20;
// Spectra held for IR and delay line together: 2^27 complex floats per array is 1 GiB, beyond any sane IR.
constexpr double kMaxSpectrumValues = static_cast<double>(1L << 27);

/// acc += a·b over n complex values (interleaved re, im), written on floats so the compiler vectorises it.
void multiplyAdd(const std::complex<float>* a, const std::complex<float>* b, std::complex<float>* acc, int n) {
  const float* __restrict pa = reinterpret_cast<const float*>(a);
  const float* __restrict pb = reinterpret_cast<const float*>(b);
  float* __restrict pc = reinterpret_cast<float*>(acc);
  for (int i = 0; i < n; ++i) {
    const float ar = pa[2 * i], ai = pa[2 * i + 1], br = pb[2 * i], bi = pb[2 * i + 1];
    pc[2 * i] += ar * br - ai * bi;
    pc[2 * i + 1] += ar * bi + ai * br;
  }
}

}  // namespace

PartitionedConvolver::~PartitionedConvolver() { release(); }

void PartitionedConvolver::release() {
  if (fft_real_ == nullptr) return;
  std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
  fftwf_destroy_plan(static_cast<fftwf_plan>(forward_plan_));
  fftwf_destroy_plan(static_cast<fftwf_plan>(inverse_plan_));
  fftwf_free(fft_real_);
  fftwf_free(fft_complex_);
  fft_real_ = nullptr;
  fft_complex_ = nullptr;
  forward_plan_ = inverse_plan_ = nullptr;
  block_ = 0;
  ir_length_ = 0;
  partitions_ = 0;
}

void PartitionedConvolver::init(int block_size, const float* ir, long ir_length) {
  if (block_size < 1 || block_size > kMaxBlock)
    throw core::InputError("convolver", "block size must lie between 1 and " + std::to_string(kMaxBlock) +
                                            ", got " + std::to_string(block_size));
  if (ir_length < 1 || ir == nullptr) throw core::InputError("convolver", "the impulse response is empty");
  for (long i = 0; i < ir_length; ++i)
    if (!std::isfinite(ir[i]))
      throw core::InputError("convolver", "impulse response sample " + std::to_string(i) + " is not finite");
  const long partitions = (ir_length + block_size - 1) / block_size;
  if (static_cast<double>(partitions) * (block_size + 1) > kMaxSpectrumValues)
    throw core::InputError("convolver", "impulse response of " + std::to_string(ir_length) +
                                            " samples is too long for blocks of " + std::to_string(block_size));
  release();
  block_ = block_size;
  ir_length_ = ir_length;
  partitions_ = static_cast<int>(partitions);
  bins_ = block_ + 1;
  const int n = 2 * block_;
  fft_real_ = fftwf_alloc_real(static_cast<size_t>(n));
  auto* spectrum = fftwf_alloc_complex(static_cast<size_t>(bins_));
  fft_complex_ = spectrum;
  DIFFRAY_CHECK(fft_real_ != nullptr && spectrum != nullptr);
  {
    std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
    // FFTW_ESTIMATE leaves the buffers alone while planning; the plans are reused for every execute.
    forward_plan_ = fftwf_plan_dft_r2c_1d(n, fft_real_, spectrum, FFTW_ESTIMATE);
    inverse_plan_ = fftwf_plan_dft_c2r_1d(n, spectrum, fft_real_, FFTW_ESTIMATE);
  }
  DIFFRAY_CHECK(forward_plan_ != nullptr && inverse_plan_ != nullptr);

  // IR partitions: h[k·B … (k+1)·B) zero-padded to 2B, transformed, with FFTW's 1/(2B) folded in.
  const auto total = static_cast<size_t>(partitions_) * static_cast<size_t>(bins_);
  ir_spectra_.assign(total, {0.0f, 0.0f});
  const float scale = 1.0f / static_cast<float>(n);
  const auto* c = reinterpret_cast<const std::complex<float>*>(spectrum);  // layout-compatible
  for (int k = 0; k < partitions_; ++k) {
    const long start = static_cast<long>(k) * block_;
    const long count = std::min<long>(block_, ir_length - start);
    std::fill(fft_real_, fft_real_ + n, 0.0f);
    for (long i = 0; i < count; ++i) fft_real_[i] = ir[start + i];
    fftwf_execute(static_cast<fftwf_plan>(forward_plan_));
    for (int b = 0; b < bins_; ++b) ir_spectra_[static_cast<size_t>(k) * bins_ + b] = c[b] * scale;
  }
  input_spectra_.assign(total, {0.0f, 0.0f});
  history_sum_.assign(static_cast<size_t>(bins_), {0.0f, 0.0f});
  accumulator_.assign(static_cast<size_t>(bins_), {0.0f, 0.0f});
  input_block_.assign(static_cast<size_t>(block_), 0.0f);
  overlap_.assign(static_cast<size_t>(block_), 0.0f);
  fill_ = 0;
  current_ = 0;
}

void PartitionedConvolver::reset() {
  std::fill(input_spectra_.begin(), input_spectra_.end(), std::complex<float>(0.0f, 0.0f));
  std::fill(input_block_.begin(), input_block_.end(), 0.0f);
  std::fill(overlap_.begin(), overlap_.end(), 0.0f);
  fill_ = 0;
  current_ = 0;
}

void PartitionedConvolver::process(const float* in, float* out, long n) {
  if (block_ == 0) {
    std::fill(out, out + n, 0.0f);
    return;
  }
  long done = 0;
  while (done < n) {
    const int count = static_cast<int>(std::min<long>(n - done, block_ - fill_));
    processBlockPart(in + done, out + done, count);
    done += count;
  }
}

// Block b (B samples, zero-padded to 2B) convolved with partition k lands at output time (b + k)·B, over
// 2B samples; so the sum over k of H_k·X_{b−k} is the output of block b: its first half goes out now, its
// second half is added to the next block (overlap-add). X_{b−k} for k ≥ 1 are fixed once block b starts,
// so their sum is formed once per block; only H_0·X_b changes as block b fills.
void PartitionedConvolver::processBlockPart(const float* in, float* out, int count) {
  const bool starting = fill_ == 0;
  for (int i = 0; i < count; ++i) input_block_[static_cast<size_t>(fill_ + i)] = in[i];
  const int n = 2 * block_;
  std::copy(input_block_.begin(), input_block_.end(), fft_real_);
  std::fill(fft_real_ + block_, fft_real_ + n, 0.0f);
  fftwf_execute(static_cast<fftwf_plan>(forward_plan_));
  const auto* spectrum = reinterpret_cast<std::complex<float>*>(fft_complex_);
  std::complex<float>* x_now = input_spectra_.data() + static_cast<size_t>(current_) * bins_;
  std::copy(spectrum, spectrum + bins_, x_now);

  if (starting) {
    std::fill(history_sum_.begin(), history_sum_.end(), std::complex<float>(0.0f, 0.0f));
    for (int k = 1; k < partitions_; ++k) {
      const int slot = (current_ + k) % partitions_;  // block b − k
      multiplyAdd(ir_spectra_.data() + static_cast<size_t>(k) * bins_,
                  input_spectra_.data() + static_cast<size_t>(slot) * bins_, history_sum_.data(), bins_);
    }
  }
  std::copy(history_sum_.begin(), history_sum_.end(), accumulator_.begin());
  multiplyAdd(ir_spectra_.data(), x_now, accumulator_.data(), bins_);
  std::copy(accumulator_.begin(), accumulator_.end(), reinterpret_cast<std::complex<float>*>(fft_complex_));
  fftwf_execute(static_cast<fftwf_plan>(inverse_plan_));  // c2r overwrites its input: hence the copy

  for (int i = 0; i < count; ++i)
    out[i] = fft_real_[fill_ + i] + overlap_[static_cast<size_t>(fill_ + i)];
  fill_ += count;
  if (fill_ == block_) {
    std::copy(fft_real_ + block_, fft_real_ + n, overlap_.begin());
    std::fill(input_block_.begin(), input_block_.end(), 0.0f);
    fill_ = 0;
    current_ = (current_ + partitions_ - 1) % partitions_;
  }
}

}  // namespace diffray::dsp
