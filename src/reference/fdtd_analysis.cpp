// Brick-wall band-pass and energy histograms of FDTD recordings (fdtd_analysis.h).
#include "diffray/reference/fdtd_analysis.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <mutex>

#include "diffray/core/error.h"
#include "diffray/core/fftw_planner.h"

namespace diffray::reference {
namespace {

// The smallest 2^a·3^b·5^c ≥ n (FFTW is fastest on such lengths).
std::size_t fastLength(std::size_t n) {
  std::size_t best = 1;
  while (best < n) best *= 2;
  for (std::size_t p5 = 1; p5 < best; p5 *= 5)
    for (std::size_t p3 = p5; p3 < best; p3 *= 3) {
      std::size_t v = p3;
      while (v < n) v *= 2;
      if (v < best) best = v;
    }
  return best;
}

constexpr double kPi = 3.14159265358979323846;

// The gain of the lower edge's ramp at f: sin(π/2·S(x)), S(x) = x − sin(2πx)/(2π), x the position of f across
// [edge·2^(−w), edge·2^(+w)] in log frequency (0 below, 1 above).
double ramp(double f, double edge, double w) {
  if (f <= 0.0) return 0.0;
  const double x = std::clamp((std::log2(f / edge) + w) / (2.0 * w), 0.0, 1.0);
  const double s = x - std::sin(2.0 * kPi * x) / (2.0 * kPi);
  return std::sin(0.5 * kPi * s);
}

}  // namespace

double bandGain(double f_hz, double f_lo_hz, double f_hi_hz) {
  return ramp(f_hz, f_lo_hz, kBandTransitionOctaves) *
         std::sqrt(std::max(0.0, 1.0 - std::pow(ramp(f_hz, f_hi_hz, kBandTransitionOctaves), 2)));
}

std::vector<double> bandPass(const std::vector<double>& x, double dt_s, double f_lo_hz, double f_hi_hz) {
  DIFFRAY_CHECK(dt_s > 0.0 && f_lo_hz < f_hi_hz);
  if (x.empty()) return {};
  const std::size_t n = fastLength(x.size() + x.size() / 4 + 16);
  std::vector<double> buf(n, 0.0);
  std::vector<std::complex<double>> spec(n / 2 + 1);
  std::copy(x.begin(), x.end(), buf.begin());
  fftw_plan fwd, inv;
  {
    std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
    fwd = fftw_plan_dft_r2c_1d(static_cast<int>(n), buf.data(), reinterpret_cast<fftw_complex*>(spec.data()), FFTW_ESTIMATE);
    inv = fftw_plan_dft_c2r_1d(static_cast<int>(n), reinterpret_cast<fftw_complex*>(spec.data()), buf.data(), FFTW_ESTIMATE);
  }
  fftw_execute(fwd);
  const double df = 1.0 / (static_cast<double>(n) * dt_s);
  for (std::size_t k = 0; k < spec.size(); ++k) {
    const double f = static_cast<double>(k) * df;
    spec[k] *= bandGain(f, f_lo_hz, f_hi_hz) / static_cast<double>(n);
  }
  fftw_execute(inv);
  {
    std::lock_guard<std::mutex> lock(core::fftwPlannerMutex());
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(inv);
  }
  buf.resize(x.size());
  return buf;
}

std::vector<double> energyHistogram(const std::vector<double>& x, double dt_s, double t0_s, double bin_s, int bins) {
  std::vector<double> e(static_cast<std::size_t>(std::max(bins, 0)), 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = static_cast<double>(i) * dt_s - t0_s;
    if (t < 0.0) continue;
    const double k = std::floor(t / bin_s);
    if (k >= bins) break;
    e[static_cast<std::size_t>(k)] += x[i] * x[i] * dt_s;
  }
  return e;
}

}  // namespace diffray::reference
