#include "diffray/wbsdf/edge_kernel.h"

#include <algorithm>
#include <cmath>

#include "diffray/core/math.h"

namespace diffray::wbsdf {
namespace {

// Approximate masses of the proposal's parts, for the mixing probabilities: sinc averages about 0.59 over the
// main lobe, and each side lobe n holds about 2/(π²(n + ½)), about (2/π²)·ln M for the periods 1 … M − 1.
constexpr double kMainLobeMean = 0.58948987223608;  // Si(π)/π

struct Proposal {
  double main_lo = 0.0, main_hi = 0.0;  ///< the main segment, |w| < 1 within [w_lo, w_hi]
  int m_left = 1, m_right = 1;          ///< the tails cover periods 1 … m − 1 on each side
  double p_main = 1.0, p_left = 0.0, p_right = 0.0;
};

int periodsUpTo(double w) { return static_cast<int>(std::clamp(std::ceil(w), 1.0, 1e9)); }

Proposal proposal(double w_lo, double w_hi) {
  Proposal p;
  p.main_lo = std::max(-1.0, w_lo);
  p.main_hi = std::min(1.0, w_hi);
  p.m_left = periodsUpTo(-w_lo);
  p.m_right = periodsUpTo(w_hi);
  const double k = 2.0 / (core::kPi * core::kPi);
  const double a_main = kMainLobeMean * std::max(0.0, p.main_hi - p.main_lo);
  const double a_left = p.m_left > 1 ? k * std::log(static_cast<double>(p.m_left)) : 0.0;
  const double a_right = p.m_right > 1 ? k * std::log(static_cast<double>(p.m_right)) : 0.0;
  const double total = a_main + a_left + a_right;
  if (total > 0.0) p.p_main = a_main / total, p.p_left = a_left / total, p.p_right = a_right / total;
  return p;
}

// Density of a tail point at |w| = a ≥ 1 given its side was chosen (periods 1 … m − 1).
double tailPdf(double a, int m) {
  if (m <= 1 || !(a < m)) return 0.0;
  const double n = std::floor(a), t = a - n;
  return std::log1p(1.0 / n) / std::log(static_cast<double>(m)) * 0.5 * core::kPi * std::sin(core::kPi * t);
}

// |w| in the tail from two uniforms: the period log-uniformly, the offset from (π/2)·sin(πt).
double tailSample(int m, double xi1, double xi2) {
  const double r = std::exp(xi1 * std::log(static_cast<double>(m)));
  const double n = std::clamp(std::floor(r), 1.0, static_cast<double>(m - 1));
  const double t = std::acos(std::clamp(1.0 - 2.0 * xi2, -1.0, 1.0)) / core::kPi;  // CDF (1 − cos πt)/2
  return n + std::min(t, 1.0 - 1e-12);
}

}  // namespace

double edgeKernelEval(double w) {
  if (w == 0.0) return 1.0;
  const double x = core::kPi * w;
  return std::sin(x) / x;
}

double edgeKernelPdf(double w, double w_lo, double w_hi) {
  const Proposal p = proposal(w_lo, w_hi);
  if (w >= p.main_lo && w <= p.main_hi && p.main_hi > p.main_lo) return p.p_main / (p.main_hi - p.main_lo);
  if (w >= 1.0) return p.p_right * tailPdf(w, p.m_right);
  if (w <= -1.0) return p.p_left * tailPdf(-w, p.m_left);
  return 0.0;
}

EdgeKernelSample edgeKernelSample(double w_lo, double w_hi, double xi1, double xi2) {
  const Proposal p = proposal(w_lo, w_hi);
  EdgeKernelSample s;
  // xi1 picks the part; rescaled, it is also the part's first uniform (stays uniform and independent of xi2).
  if (xi1 < p.p_main) {
    s.w = p.main_lo + (xi1 / p.p_main) * (p.main_hi - p.main_lo);
  } else if (xi1 < p.p_main + p.p_right) {
    s.w = tailSample(p.m_right, (xi1 - p.p_main) / p.p_right, xi2);
  } else {
    s.w = -tailSample(p.m_left, std::min(1.0, (xi1 - p.p_main - p.p_right) / p.p_left), xi2);
  }
  const double pdf = edgeKernelPdf(s.w, w_lo, w_hi);
  s.weight = pdf > 0.0 ? edgeKernelEval(s.w) / pdf : 0.0;
  return s;
}

}  // namespace diffray::wbsdf
