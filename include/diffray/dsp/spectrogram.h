#pragma once
// Short-time Fourier magnitudes of one channel, in dB, for looking at how a sound's spectrum changes (the
// closing door's muffling). Frame i holds x[i·hop, i·hop + window) (zero past the signal's end), times the
// periodic Hann window w[m] = ½(1 − cos(2πm/window)); its real FFT X_i[k] (FFTW r2c, k = 0 … window/2,
// frequency k·fs/window) is stored as the one-sided amplitude
//     magnitude_db = 20·log10(|X_i[k]| · 2/Σw)  (Σw = window/2),
// so a sine of amplitude A centred on a bin reads 20·log10(A) there (0 dB for a full-scale sine; the DC and
// Nyquist bins, which have no mirror image, read 6 dB above their amplitude); values are floored at kFloorDb.
// Frames: 1 + ceil((n − window)/hop) (one frame when n ≤ window); frame i's time
// is its centre, (i·hop + window/2)/fs seconds. The FFT plan is made under core::fftwPlannerMutex().
// Thread-safety: a pure function; concurrent calls are safe.
#include <cstddef>
#include <vector>

namespace diffray::dsp {

struct Spectrogram {
  static constexpr double kFloorDb = -240.0;
  double sample_rate_hz = 0.0;
  int window = 0;  ///< frame length in samples (even)
  int hop = 0;     ///< frame step in samples
  std::vector<double> time_s;        ///< frames: each frame's centre
  std::vector<double> freq_hz;       ///< bins: k·fs/window, k = 0 … window/2
  std::vector<float> magnitude_db;   ///< frames × bins, frame-major: (i, k) at i·bins() + k

  int frames() const { return static_cast<int>(time_s.size()); }
  int bins() const { return static_cast<int>(freq_hz.size()); }
  float at(int frame, int bin) const {
    return magnitude_db[static_cast<std::size_t>(frame) * freq_hz.size() + static_cast<std::size_t>(bin)];
  }
};

/// The spectrogram of x[0 … n) (n ≥ 1 finite samples) sampled at `fs_hz` (> 0), with frames of `window`
/// samples (even, 8 … 2^20) every `hop` samples (1 … 2^20). Throws core::InputError for a bad argument or
/// a result of more than 2^28 values.
Spectrogram spectrogram(const float* x, long n, double fs_hz, int window, int hop);

/// The number of frames spectrogram() makes: 1 + ceil((n − window)/hop), or 1 when n ≤ window.
long frameCount(long n, int window, int hop);

/// spectrogram() with its frames folded to at most `max_frames` (≥ 1) rows, for drawing long signals with
/// bounded memory (max_frames × bins values, whatever n): row r holds, bin by bin, the loudest of the g
/// consecutive frames [r·g, (r+1)·g), g = ceil(frameCount/max_frames), so a click in any one frame still
/// shows; the result's `hop` is g·hop and row r's time the mean of its frames' centres (g = 1: exactly
/// spectrogram()). Frames are still every `hop` samples, so with hop ≤ window/4 every sample lies where the
/// Hann window is at least ½ in some frame. Same arguments and errors as spectrogram().
Spectrogram spectrogramPeaks(const float* x, long n, double fs_hz, int window, int hop, long max_frames);

}  // namespace diffray::dsp
