// The spectrogram against closed forms: a sine's peak at its frequency and amplitude (the documented
// scaling), Parseval's theorem frame by frame (the windowed frame's energy, computed here, equals the
// energy of the one-sided spectrum read back from the dB values), and a linear chirp's peak following its
// instantaneous frequency f0 + (f1 − f0)·t/T; a single click in a long signal shows in the folded frames
// (spectrogramPeaks) at the level an impulse has in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/dsp/spectrogram.h"

namespace {

using diffray::dsp::Spectrogram;

int peakBin(const Spectrogram& s, int frame) {
  int best = 0;
  for (int k = 1; k < s.bins(); ++k)
    if (s.at(frame, k) > s.at(frame, best)) best = k;
  return best;
}

TEST(Spectrogram, AxesAndFrameCount) {
  const std::vector<float> x(10000, 0.0f);
  const Spectrogram s = diffray::dsp::spectrogram(x.data(), 10000, 48000.0, 1024, 256);
  EXPECT_EQ(s.frames(), 1 + 36);  // 1 + ceil((10000 − 1024)/256)
  EXPECT_EQ(s.bins(), 513);
  EXPECT_DOUBLE_EQ(s.freq_hz[512], 24000.0);
  EXPECT_DOUBLE_EQ(s.freq_hz[1], 48000.0 / 1024);
  EXPECT_DOUBLE_EQ(s.time_s[0], 512.0 / 48000.0);
  EXPECT_DOUBLE_EQ(s.time_s[3], (3 * 256 + 512) / 48000.0);
  EXPECT_EQ(s.at(5, 7), static_cast<float>(Spectrogram::kFloorDb));  // silence sits on the floor
  const Spectrogram one = diffray::dsp::spectrogram(x.data(), 100, 48000.0, 1024, 256);
  EXPECT_EQ(one.frames(), 1);
}

TEST(Spectrogram, SinePeaksAtItsFrequencyAndAmplitude) {
  const double fs = 48000.0;
  const int window = 2048;
  for (double f : {1000.0, 375.0 * fs / window /* on bin 375 */, 5432.1}) {
    const double A = 0.25;
    std::vector<float> x(20000);
    for (size_t n = 0; n < x.size(); ++n) x[n] = static_cast<float>(A * std::sin(2.0 * M_PI * f * static_cast<double>(n) / fs + 0.3));
    const Spectrogram s = diffray::dsp::spectrogram(x.data(), static_cast<long>(x.size()), fs, window, 512);
    for (int i = 0; i + 1 < s.frames(); ++i) {  // the last frame is zero-padded
      const int k = peakBin(s, i);
      EXPECT_LE(std::abs(s.freq_hz[static_cast<size_t>(k)] - f), 0.5 * fs / window) << "f " << f << ", frame " << i;
    }
    // On a bin centre the amplitude reads 20·log10(A) (the Hann window's other bins hold its sidelobes;
    // the neighbours read A/2, i.e. 6.02 dB lower).
    if (std::abs(f - 375.0 * fs / window) < 1e-9) {
      EXPECT_NEAR(s.at(3, 375), 20.0 * std::log10(A), 1e-3);
      EXPECT_NEAR(s.at(3, 374), 20.0 * std::log10(A / 2.0), 1e-3);
      EXPECT_NEAR(s.at(3, 376), 20.0 * std::log10(A / 2.0), 1e-3);
    }
  }
}

TEST(Spectrogram, ParsevalFrameByFrame) {
  // Σ_m (w[m]·x[m])² = (1/N)·Σ_{k=0}^{N−1} |X[k]|² = (1/N)·(|X_0|² + 2·Σ_{k=1}^{N/2−1} |X_k|² + |X_{N/2}|²),
  // with |X_k| = 10^(dB/20)·Σw/2 and Σw = N/2 (the documented scaling).
  std::mt19937 rng(12);
  std::normal_distribution<float> g(0.0f, 0.3f);
  const int window = 512, hop = 200;
  std::vector<float> x(6000);
  for (float& v : x) v = g(rng);
  const Spectrogram s = diffray::dsp::spectrogram(x.data(), static_cast<long>(x.size()), 44100.0, window, hop);
  double worst = 0.0;
  for (int i = 0; i < s.frames(); ++i) {
    double time_energy = 0.0;
    for (int m = 0; m < window; ++m) {
      const size_t t = static_cast<size_t>(i * hop + m);
      const double w = std::pow(std::sin(M_PI * m / window), 2);  // ½(1 − cos 2θ) = sin²θ
      const double v = t < x.size() ? w * x[t] : 0.0;
      time_energy += v * v;
    }
    double freq_energy = 0.0;
    for (int k = 0; k < s.bins(); ++k) {
      const double X = std::pow(10.0, s.at(i, k) / 20.0) * (window / 2.0) / 2.0;
      freq_energy += (k == 0 || k == window / 2 ? 1.0 : 2.0) * X * X;
    }
    freq_energy /= window;
    const double rel = std::abs(freq_energy - time_energy) / time_energy;
    worst = std::max(worst, rel);
    EXPECT_LE(rel, 1e-5) << "frame " << i;
  }
  std::cout << "[ measured ] worst Parseval mismatch: " << worst << "\n";
}

TEST(Spectrogram, ChirpPeakFollowsInstantaneousFrequency) {
  // x(t) = sin(2π(f0·t + (f1 − f0)·t²/(2T))): instantaneous frequency f0 + (f1 − f0)·t/T. Over one
  // window (1024 samples, 21 ms) it sweeps 2.2 bins, symmetric about the frame's centre, so the peak sits
  // within a bin of the centre's frequency.
  const double fs = 48000.0, f0 = 100.0, f1 = 10000.0, T = 2.0;
  const int window = 1024;
  std::vector<float> x(static_cast<size_t>(T * fs));
  for (size_t n = 0; n < x.size(); ++n) {
    const double t = static_cast<double>(n) / fs;
    x[n] = static_cast<float>(std::sin(2.0 * M_PI * (f0 * t + (f1 - f0) * t * t / (2.0 * T))));
  }
  const Spectrogram s = diffray::dsp::spectrogram(x.data(), static_cast<long>(x.size()), fs, window, 480);
  double worst_bins = 0.0;
  for (int i = 0; i + 1 < s.frames(); ++i) {
    const double f_inst = f0 + (f1 - f0) * s.time_s[static_cast<size_t>(i)] / T;
    const double off = std::abs(s.freq_hz[static_cast<size_t>(peakBin(s, i))] - f_inst) / (fs / window);
    worst_bins = std::max(worst_bins, off);
    EXPECT_LE(off, 1.0) << "frame " << i << " at " << s.time_s[static_cast<size_t>(i)] << " s";
  }
  std::cout << "[ measured ] chirp: worst peak offset " << worst_bins << " bins\n";
}

TEST(Spectrogram, ClickAnywhereInALongSignalShowsInThePeaks) {
  // A unit impulse of amplitude A at offset m of a frame has |X[k]| = A·w[m] in every bin, i.e. it reads
  // 20·log10(A·w[m]·4/window) (the documented scaling, Σw = window/2). With frames every window/4, some
  // frame holds the click within window/8 of its centre, where w ≥ sin²(3π/8) > ½; folding keeps the loudest
  // frame. The old automatic hop ceil(n/8000) (here 384 > window = 256) puts a click on a frame's first
  // sample, where w = 0, and in no other frame: the spectrogram is floor everywhere.
  const double fs = 48000.0, A = 0.5;
  const int window = 256;
  const long n = 8000L * window * 3 / 2, old_hop = (n + 7999) / 8000;
  const double expected_db = 20.0 * std::log10(A * 0.5 * 4.0 / window);
  for (long click : {old_hop * 5000, old_hop * 5000 + 7, n - 1 - old_hop}) {
    std::vector<float> x(static_cast<size_t>(n), 0.0f);
    x[static_cast<size_t>(click)] = static_cast<float>(A);
    const Spectrogram peaks = diffray::dsp::spectrogramPeaks(x.data(), n, fs, window, window / 4, 8000);
    ASSERT_LE(peaks.frames(), 8000);
    const auto loudest = std::max_element(peaks.magnitude_db.begin(), peaks.magnitude_db.end());
    EXPECT_GE(*loudest, expected_db) << "click at " << click;
    // The loudest row's time lies within its run of frames (g·hop samples) plus half a window of the click.
    const long row = (loudest - peaks.magnitude_db.begin()) / peaks.bins();
    EXPECT_LE(std::abs(peaks.time_s[static_cast<size_t>(row)] - static_cast<double>(click) / fs), (peaks.hop + 0.5 * window) / fs);
    if (click % old_hop == 0) {
      const Spectrogram old = diffray::dsp::spectrogram(x.data(), n, fs, window, static_cast<int>(old_hop));
      EXPECT_EQ(*std::max_element(old.magnitude_db.begin(), old.magnitude_db.end()),
                static_cast<float>(Spectrogram::kFloorDb));
    }
  }
}

TEST(Spectrogram, PeaksWithoutFoldingAreTheSpectrogram) {
  std::mt19937 rng(3);
  std::normal_distribution<float> g(0.0f, 0.3f);
  std::vector<float> x(5000);
  for (float& v : x) v = g(rng);
  const Spectrogram a = diffray::dsp::spectrogram(x.data(), 5000, 44100.0, 512, 128);
  const Spectrogram b = diffray::dsp::spectrogramPeaks(x.data(), 5000, 44100.0, 512, 128, 1000);
  EXPECT_EQ(a.magnitude_db, b.magnitude_db);
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_EQ(a.hop, b.hop);
  // Folded by 3: each row is the element-wise maximum of three frames.
  const Spectrogram c = diffray::dsp::spectrogramPeaks(x.data(), 5000, 44100.0, 512, 128, (a.frames() + 2) / 3);
  ASSERT_EQ(c.frames(), (a.frames() + 2) / 3);
  EXPECT_EQ(c.hop, 3 * 128);
  for (int r = 0; r < c.frames(); ++r)
    for (int k = 0; k < c.bins(); k += 17) {
      float m = a.at(3 * r, k);
      for (int i = 3 * r + 1; i < std::min(3 * r + 3, a.frames()); ++i) m = std::max(m, a.at(i, k));
      EXPECT_EQ(c.at(r, k), m) << "row " << r << ", bin " << k;
    }
}

TEST(Spectrogram, RefusesBadArguments) {
  const std::vector<float> x(100, 0.1f), bad{0.0f, NAN};
  using diffray::core::InputError;
  using diffray::dsp::spectrogram;
  EXPECT_THROW(spectrogram(x.data(), 0, 48000.0, 64, 16), InputError);
  EXPECT_THROW(spectrogram(x.data(), 100, 0.0, 64, 16), InputError);
  EXPECT_THROW(spectrogram(x.data(), 100, 48000.0, 63, 16), InputError);  // odd
  EXPECT_THROW(spectrogram(x.data(), 100, 48000.0, 4, 16), InputError);   // too short
  EXPECT_THROW(spectrogram(x.data(), 100, 48000.0, 64, 0), InputError);
  EXPECT_THROW(spectrogram(bad.data(), 2, 48000.0, 64, 16), InputError);
}

}  // namespace
