#include "diffray/utd/coefficient.h"

#include <cerf.h>

#include <cmath>

#include "diffray/core/error.h"
#include "diffray/core/math.h"

namespace diffray::utd {

namespace {

using cd = std::complex<double>;

// Faddeeva's w(z) through libcerf's C interface (C99 double _Complex, a GNU extension in C++; kept to this
// one function, where clang's note that it is an extension is silenced: it is the library's ABI. Its
// re_w_of_z/im_w_of_z would avoid the type but evaluate w twice).
#if defined(__clang__)
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Wc99-extensions"
#endif
cd faddeeva(cd z) {
  double _Complex arg;
  __real__ arg = z.real();
  __imag__ arg = z.imag();
  const double _Complex w = w_of_z(arg);
  return {__real__ w, __imag__ w};
}
#if defined(__clang__)
#pragma clang diagnostic pop
#endif

}  // namespace

std::complex<double> transitionF(double x) {
  if (!(x >= 0.0) || !std::isfinite(x)) throw core::InputError("utd::transitionF", "X must be finite and >= 0");
  if (x == 0.0) return {0.0, 0.0};
  // ∫_a^∞ e^{−iτ²}dτ = (√π/2) e^{−iπ/4} erfc(e^{iπ/4}a) (rotate the contour onto τ = e^{−iπ/4}s), and
  // erfc(z) = e^{−z²} w(iz) with z² = iX: the factor e^{iX} of F cancels, leaving
  // F(X) = √(πX) e^{iπ/4} w(e^{3iπ/4}√X). w is bounded in the upper half-plane, so this holds for any X.
  const double s = std::sqrt(x);
  const cd e1 = std::polar(1.0, 0.25 * core::kPi), e3 = std::polar(1.0, 0.75 * core::kPi);
  return std::sqrt(core::kPi * x) * e1 * faddeeva(e3 * s);
}

namespace {

// cot(ε/2n)·F(2kL sin²(ε/2)) (cotTransition), weighted (on ? 1 − |F| : 0) + |F|·T for a finite edge's
// factor T (wedgeCoefficient).
cd weightedTerm(double n, double kl, double eps, cd truncation, bool on) {
  const cd e1 = std::polar(1.0, 0.25 * core::kPi);
  if (std::abs(eps) <= kBoundaryTolRad) {
    // On the boundary (within the tolerance paths.cpp halves the geometric field in): the mean of the two
    // one-sided limits of cot(ε/2n)·F ≈ n[√(2πkL)·sgn ε − 2kLε e^{iπ/4}]e^{iπ/4} (KP 1974: cot(ε/2n) ≈ 2n/ε,
    // F(X) ≈ √(πX)e^{iπ/4} − 2iX, √X ≈ √(kL/2)|ε|). The total field varies over ~1/√(kL) rad, so taking
    // its boundary value this close costs ~√(kL)·1e-9 relative. |F| vanishes there.
    return on ? n * (-2.0 * kl * eps * e1) * e1 : cd(0.0);
  }
  const double s = std::sin(0.5 * eps);
  const cd f = transitionF(2.0 * kl * s * s);
  const double a = std::abs(f);
  const cd weight = on && truncation == 1.0 ? cd(1.0) : (on ? 1.0 - a : 0.0) + a * truncation;
  return weight * f / std::tan(eps / (2.0 * n));
}

}  // namespace

std::complex<double> cotTransition(double n, double kl, double eps) { return weightedTerm(n, kl, eps, 1.0, true); }

std::complex<double> wedgeCoefficient(double n, double k, double l_m, double phi, double phi_inc, double beta0,
                                      FaceReflection r, std::complex<double> truncation, bool apex_on_edge) {
  const char* where = "utd::wedgeCoefficient";
  if (!(n >= 1.0) || !std::isfinite(n)) throw core::InputError(where, "wedge index n must be >= 1");
  core::requirePositive(where, k);
  core::requirePositive(where, l_m);
  if (!(beta0 > 0.0 && beta0 < core::kPi)) throw core::InputError(where, "beta0 must be in (0, pi)");
  core::requireFinite(where, phi);
  core::requireFinite(where, phi_inc);
  const double kl = k * l_m, two_pi_n = core::kTwoPi * n;
  // ε of the "+" term cot((π + β)/2n)F(kLa⁺(β)): π + β − 2πnN⁺, N⁺ = round((β + π)/2πn); of the "−" term
  // cot((π − β)/2n)F(kLa⁻(β)): π − β + 2πnN⁻, N⁻ = round((β − π)/2πn). cot has period π, so each term is
  // cot(ε/2n)·F(2kL sin²(ε/2)), evaluated without the cancellation of cot near its poles.
  const auto plus = [&](double beta) {
    return weightedTerm(n, kl, core::kPi + beta - two_pi_n * std::round((beta + core::kPi) / two_pi_n), truncation, apex_on_edge);
  };
  const auto minus = [&](double beta) {
    return weightedTerm(n, kl, core::kPi - beta + two_pi_n * std::round((beta - core::kPi) / two_pi_n), truncation, apex_on_edge);
  };
  const double bm = phi - phi_inc, bp = phi + phi_inc;
  const cd sum = plus(bm) + minus(bm) + r.face0 * minus(bp) + r.facen * plus(bp);
  const cd pre = -std::polar(1.0, -0.25 * core::kPi) / (2.0 * n * std::sqrt(core::kTwoPi * k) * std::sin(beta0));
  return pre * sum;
}

}  // namespace diffray::utd
