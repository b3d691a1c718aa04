// The SRL FDTD update, its boundary nodes and its closed forms (fdtd_scheme.h).
#include "diffray/reference/fdtd_scheme.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Flushes denormals to zero while alive (FTZ | DAZ in MXCSR), restoring the thread's mode after.
class FlushDenormals {
 public:
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }
  ~FlushDenormals() { _mm_setcsr(saved_); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned saved_;
};

// The ξ of α_st's maximum, by golden-section search on [1, 3] (α_st is unimodal there).
double xiAtMaximum() {
  double lo = 1.0, hi = 3.0;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 200; ++it) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (parisAbsorption(x1) < parisAbsorption(x2)) lo = x1;
    else hi = x2;
  }
  return 0.5 * (lo + hi);
}

// One x row of the interior update: p⁺ = 2p − p⁻ + λ²·Σ₆(p_nbr − p) at interior air nodes (flag == kAir);
// every other node keeps its p⁻ (non-air nodes stay 0, boundary nodes are updated after). The differences
// are formed before they are scaled, so that a uniform field gives exactly p⁺ = 2p − p⁻: the form
// (2 − 6λ²)·p + λ²·Σ₆ p_nbr rounds its two coefficients apart, and the uniform mode of a closed rigid room
// then grows by e^{√(6·|err|)} per step (err ~ 6e-8: 2.4e-4 per step, 10¹⁰ in energy over 5·10⁴ steps).
// The keep-or-replace is a bit select, not a branch, and the rows do not alias, so that the loop vectorises.
void updateRow(const std::uint8_t* __restrict f, const float* __restrict p, float* __restrict q, int nx,
               std::ptrdiff_t sy, std::ptrdiff_t sz, float l2) {
  for (std::ptrdiff_t i = 1; i < nx - 1; ++i) {
    const float old = q[i], c = p[i];
    const float lap = ((p[i - 1] - c) + (p[i + 1] - c)) + ((p[i - sy] - c) + (p[i + sy] - c)) +
                      ((p[i - sz] - c) + (p[i + sz] - c));
    const float v = (2.0f * c - old) + l2 * lap;
    std::uint32_t vb, ob;
    std::memcpy(&vb, &v, 4);
    std::memcpy(&ob, &old, 4);
    const std::uint32_t keep_new = 0u - static_cast<std::uint32_t>(f[i] == FdtdGrid::kAir);
    const std::uint32_t r = (vb & keep_new) | (ob & ~keep_new);
    std::memcpy(&q[i], &r, 4);
  }
}

}  // namespace

double parisAbsorption(double xi) {
  DIFFRAY_CHECK(xi > 0.0);
  // For large ξ the bracket cancels to O(1/ξ²): its series 1/(1+ξ) − (2/ξ)ln(1+ξ) + 1 is evaluated as is
  // up to ξ = 1e6 (relative rounding ~1e-10 of a term of size 8/ξ), and as 8/ξ·(…) ≈ 8/ξ beyond.
  if (xi > 1e6) return 8.0 / xi;
  return (8.0 / xi) * (1.0 + 1.0 / (1.0 + xi) - (2.0 / xi) * std::log1p(xi));
}

double maxParisAbsorption() {
  static const double value = parisAbsorption(xiAtMaximum());
  return value;
}

double admittanceForAbsorption(double alpha, bool* clamped) {
  if (clamped) *clamped = false;
  if (!(alpha > 0.0)) return 0.0;
  static const double xi_max = xiAtMaximum();
  if (alpha >= maxParisAbsorption()) {
    if (clamped) *clamped = alpha > maxParisAbsorption();
    return 1.0 / xi_max;
  }
  // α_st decreases monotonically on [ξ_max, ∞): bisection in log ξ.
  double lo = std::log(xi_max), hi = std::log(1e12);
  for (int it = 0; it < 200 && hi - lo > 1e-14; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (parisAbsorption(std::exp(mid)) > alpha) lo = mid;
    else hi = mid;
  }
  return 1.0 / std::exp(0.5 * (lo + hi));
}

double srlAxialPhaseVelocityRatio(double f_hz, double h_m, double dt_s, double c_m_s) {
  const double lambda = c_m_s * dt_s / h_m;
  const double omega = 2.0 * kPi * f_hz;
  const double s = std::sin(0.5 * omega * dt_s) / lambda;
  if (!(s <= 1.0) || 0.5 * omega * dt_s > 0.5 * kPi) return std::nan("");
  const double k = 2.0 * std::asin(s) / h_m;
  return omega / (c_m_s * k);
}

double RickerPulse::operator()(double t_s) const {
  const double a = kPi * peak_hz * (t_s - delay());
  return (1.0 - 2.0 * a * a) * std::exp(-a * a);
}

double freeFieldFactor(double h_m, double dt_s, double c_m_s) {
  return h_m * h_m * h_m / (4.0 * kPi * c_m_s * c_m_s * dt_s * dt_s);
}

FdtdScheme::FdtdScheme(const FdtdGrid& grid, double courant, const std::vector<double>& beta_of_material)
    : grid_(grid), lambda_(courant) {
  DIFFRAY_CHECK(courant > 0.0 && courant <= kSrlCourantLimit * (1.0 + 1e-12));
  field_a_.assign(grid.nodes(), 0.0f);
  field_b_.assign(grid.nodes(), 0.0f);
  prev_ = field_a_.data();
  cur_ = field_b_.data();
  // λ² in float, rounded down: at λ = 1/√3, 1/3 rounds up to 0.33333334, past the stability limit.
  coupling_ = static_cast<float>(lambda_ * lambda_);
  if (static_cast<double>(coupling_) > lambda_ * lambda_) coupling_ = std::nextafter(coupling_, 0.0f);
  const double l2 = coupling_;
  for (std::size_t i = 0; i < grid.nodes(); ++i) {
    const std::uint8_t f = grid.flags[i];
    if (!(f & FdtdGrid::kAir) || !(f & FdtdGrid::kBlockedMask)) continue;
    FdtdBoundaryNode bn;
    bn.node = static_cast<std::uint32_t>(i);
    int open = 0;
    double beta_sum = 0.0;
    for (int d = 0; d < kFdtdDirections; ++d) {
      if (f & (1u << d)) {
        const int m = grid.materialOf(i, d);
        beta_sum += m == FdtdGrid::kAbsorbing ? 1.0 : beta_of_material.at(static_cast<std::size_t>(m));
      } else {
        bn.open = static_cast<std::uint8_t>(bn.open | (1u << d));
        ++open;
      }
    }
    const double g = 0.5 * lambda_ * beta_sum;
    bn.a = static_cast<float>(2.0 / (1.0 + g));
    bn.b = static_cast<float>(l2 / (1.0 + g));
    bn.c = static_cast<float>((1.0 - g) / (1.0 + g));
    boundary_.push_back(bn);
  }
}

void FdtdScheme::step() {
  const int nx = grid_.nx, ny = grid_.ny, nz = grid_.nz;
  const std::ptrdiff_t sy = nx, sz = static_cast<std::ptrdiff_t>(nx) * ny;
  const float l2 = coupling_;
  const std::uint8_t* flags = grid_.flags.data();
  float* next = prev_;  // p^{n+1} overwrites p^{n−1} node by node (each reads only its own p^{n−1})
  const float* cur = cur_;
  // Interior nodes, in z slabs: the branch-free form below vectorises (a blend keeps non-interior nodes).
  tbb::parallel_for(tbb::blocked_range<int>(1, nz - 1), [&](const tbb::blocked_range<int>& r) {
    FlushDenormals ftz;
    for (int k = r.begin(); k != r.end(); ++k)
      for (int j = 1; j < ny - 1; ++j) {
        const std::ptrdiff_t row = sy * j + sz * k;
        updateRow(flags + row, cur + row, next + row, nx, sy, sz, l2);
      }
  });
  // Boundary nodes, after (they read only p^n and their own p^{n−1}, which the pass above left as it was).
  std::ptrdiff_t off[kFdtdDirections];
  for (int d = 0; d < kFdtdDirections; ++d) off[d] = grid_.offset(d);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, boundary_.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    FlushDenormals ftz;
    for (std::size_t n = r.begin(); n != r.end(); ++n) {
      const FdtdBoundaryNode& bn = boundary_[n];
      const std::ptrdiff_t i = bn.node;
      const float c = cur[i];
      float sum = 0.0f;
      for (int d = 0; d < kFdtdDirections; ++d)
        if (bn.open & (1u << d)) sum += cur[i + off[d]] - c;
      next[i] = bn.a * cur[i] + bn.b * sum - bn.c * next[i];
    }
  });
  std::swap(prev_, cur_);
}

}  // namespace diffray::reference
