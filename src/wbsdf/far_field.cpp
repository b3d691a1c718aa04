#include "diffray/wbsdf/far_field.h"

#include <algorithm>
#include <cmath>

#include "diffray/core/math.h"

namespace diffray::wbsdf {
namespace {

constexpr double kCore = 1.0 / core::kPi;  // |w| ≤ 1/π: the envelope is 1; beyond, 1/(πw)²

// The envelope's parts on [w_lo, w_hi]: the left tail |w| in [l1, l2], the core [c1, c2], the right tail
// [r1, r2], and their masses (∫ 1/(πw)² from a to b = (1/a − 1/b)/π²).
struct Parts {
  double l1, l2, c1, c2, r1, r2;
  double left = 0.0, middle = 0.0, right = 0.0;
  double total() const { return left + middle + right; }
};

double tailMass(double a, double b) { return b > a ? (1.0 / a - 1.0 / b) / (core::kPi * core::kPi) : 0.0; }

Parts parts(double w_lo, double w_hi) {
  Parts p{std::max(kCore, -w_hi), -w_lo, std::max(w_lo, -kCore), std::min(w_hi, kCore), std::max(kCore, w_lo), w_hi};
  p.left = tailMass(p.l1, p.l2);
  p.right = tailMass(p.r1, p.r2);
  p.middle = std::max(0.0, p.c2 - p.c1);
  return p;
}

double envelope(double w) { return std::abs(w) <= kCore ? 1.0 : 1.0 / (core::kPi * core::kPi * w * w); }

// |w| in [a, b] (kCore ≤ a < b) with density ∝ 1/w², from a uniform: 1/w linear in ξ.
double tailDraw(double a, double b, double xi) { return 1.0 / (1.0 / a - xi * (1.0 / a - 1.0 / b)); }

// The sine integral Si(x) = ∫_0^x sin(t)/t dt: its power series up to |x| = 20 (terms below 4e7, so about
// 1e-9 of rounding), beyond it the asymptotic series Si = π/2 − f·cos x − g·sin x, f ~ (1/x)Σ(−1)^k (2k)!/x^{2k},
// g ~ (1/x²)Σ(−1)^k (2k+1)!/x^{2k}, cut at its smallest term (below 3e-8 at x = 20; Abramowitz & Stegun 5.2.8,
// 5.2.34–35).
double sineIntegral(double x) {
  if (x < 0.0) return -sineIntegral(-x);
  if (std::isinf(x)) return 0.5 * core::kPi;
  if (x <= 20.0) {
    double term = x, sum = x;  // term_n = (−1)^n x^{2n+1}/(2n+1)!
    for (int n = 1; n < 60; ++n) {
      term *= -x * x / ((2.0 * n) * (2.0 * n + 1.0));
      const double add = term / (2.0 * n + 1.0);
      sum += add;
      if (std::abs(add) < 1e-17 * std::abs(sum)) break;
    }
    return sum;
  }
  double f = 0.0, g = 0.0, tf = 1.0, tg = 1.0;  // the k-th terms (2k)!/x^{2k} and (2k+1)!/x^{2k}, signed
  const double inv2 = 1.0 / (x * x);
  for (int k = 0; k < 40; ++k) {
    f += tf;
    g += tg;
    const double nf = -tf * (2.0 * k + 1.0) * (2.0 * k + 2.0) * inv2, ng = -tg * (2.0 * k + 2.0) * (2.0 * k + 3.0) * inv2;
    if (std::abs(nf) >= std::abs(tf) || std::abs(ng) >= std::abs(tg)) break;
    tf = nf, tg = ng;
  }
  return 0.5 * core::kPi - f / x * std::cos(x) - g * inv2 * std::sin(x);
}

// ∫_0^w sinc²: Si(2πw)/π − sin²(πw)/(π²w) (its derivative is sin(2πw)/(πw) + sinc²(w) − sin(2πw)/(πw)).
double farFieldCumulative(double w) {
  if (std::isinf(w)) return std::copysign(0.5, w);
  if (w == 0.0) return 0.0;
  const double s = std::sin(core::kPi * w);
  return sineIntegral(2.0 * core::kPi * w) / core::kPi - s * s / (core::kPi * core::kPi * w);
}

}  // namespace

double farFieldMass(double w_lo, double w_hi) {
  return w_hi > w_lo ? farFieldCumulative(w_hi) - farFieldCumulative(w_lo) : 0.0;
}

double farFieldEval(double w) {
  if (w == 0.0) return 1.0;
  const double s = std::sin(core::kPi * w) / (core::kPi * w);
  return s * s;
}

double farFieldPdf(double w, double w_lo, double w_hi) {
  if (!(w >= w_lo && w <= w_hi)) return 0.0;
  const double total = parts(w_lo, w_hi).total();
  return total > 0.0 ? envelope(w) / total : 0.0;
}

FarFieldSample farFieldSample(double w_lo, double w_hi, double xi) {
  const Parts p = parts(w_lo, w_hi);
  const double total = p.total();
  if (!(total > 0.0)) return {};
  // One uniform picks the part and, rescaled within it, the point.
  const double t = xi * total;
  double w;
  if (t < p.left) w = -tailDraw(p.l1, p.l2, t / p.left);
  else if (t < p.left + p.middle) w = p.c1 + (t - p.left) / p.middle * (p.c2 - p.c1);
  else w = tailDraw(p.r1, p.r2, std::min(1.0, (t - p.left - p.middle) / p.right));
  w = std::clamp(w, w_lo, w_hi);
  return {w, farFieldEval(w) / envelope(w) * total};
}

}  // namespace diffray::wbsdf
