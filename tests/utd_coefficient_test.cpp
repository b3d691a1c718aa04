// Tests of the UTD transition function and the Kouyoumjian–Pathak wedge coefficient (Kouyoumjian & Pathak,
// Proc. IEEE 62(11), 1974).
// Oracles: F(X) by direct quadrature of its integral written here (no libcerf), its known small- and
// large-X expansions, and Sommerfeld's exact half-plane solution (reference/fresnel.h, its own Fresnel
// integrals): for a plane wave on a half-plane UTD with the exact F is the exact solution, so the two agree
// to rounding, boundaries included. The half-plane check values of
// reference_test.cpp are tested through the same path.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/fresnel.h"
#include "diffray/utd/coefficient.h"

namespace utd = diffray::utd;
using Complex = std::complex<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;
double degrees(double d) { return d * kPi / 180.0; }

// F(X) = 2i√X e^{iX} ∫_{√X}^∞ e^{−iτ²}dτ by composite Simpson along the steepest-descent path
// τ = √X + e^{−iπ/4}s, s ≥ 0 (the integrand is entire and decays in the swept sector, so Cauchy allows the
// rotation): e^{−iτ²} = e^{−iX} e^{−√2(1+i)√X s} e^{−s²}, smooth and decaying; s up to 12 leaves < e^{−144}.
Complex quadratureF(double x) {
  const double a = std::sqrt(x);
  const Complex rot = std::polar(1.0, -0.25 * kPi);
  const auto g = [&](double s) { return std::exp(Complex(-std::sqrt(2.0) * a * s - s * s, -std::sqrt(2.0) * a * s)); };
  // Past s_max the integrand is below e^{−40} (e^{−144} at most for small X): the rest is negligible.
  const double s_max = std::min(12.0, 40.0 / (std::sqrt(2.0) * a));
  const int n = 24000;
  const double h = s_max / n;
  Complex sum = g(0.0) + g(s_max);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * g(i * h);
  const Complex integral_times_eix = rot * sum * (h / 3.0);  // e^{iX}·∫ (the e^{−iX} cancels)
  return Complex(0.0, 2.0 * a) * integral_times_eix;
}

// The UTD total field of a plane wave e^{ikρcos(φ−φ0)} on a half-plane (faces φ = 0 and 2π, n = 2):
// geometric optics (incident where φ < π + φ0, face-0 reflection ±e^{ikρcos(φ+φ0)} where φ < π − φ0,
// weight ½ on a boundary, within the kBoundaryTolRad that coefficient.h counts as on it) plus the diffracted field D(L = ρ)·e^{−ikρ}/√ρ (β0 = π/2).
Complex utdHalfPlane(double lambda, double rho, double phi, double phi0, bool rigid) {
  const double k = 2.0 * kPi / lambda, r = rigid ? 1.0 : -1.0;
  const auto lit = [](double margin) { return margin > 1e-9 ? 1.0 : (margin >= -1e-9 ? 0.5 : 0.0); };
  Complex go = lit(kPi + phi0 - phi) * std::exp(Complex(0.0, k * rho * std::cos(phi - phi0)));
  go += r * lit(kPi - phi0 - phi) * std::exp(Complex(0.0, k * rho * std::cos(phi + phi0)));
  const Complex d = utd::wedgeCoefficient(2.0, k, rho, phi, phi0, 0.5 * kPi, {r, r});
  return go + d * std::exp(Complex(0.0, -k * rho)) / std::sqrt(rho);
}

}  // namespace

TEST(UtdTransition, MatchesQuadratureOfItsIntegral) {
  for (double x : {1e-6, 1e-3, 0.01, 0.1, 0.3, 1.0, 2.0, 5.0, 10.0, 30.0, 100.0}) {
    const Complex ref = quadratureF(x);
    EXPECT_NEAR(std::abs(utd::transitionF(x) - ref), 0.0, 1e-11 * std::max(1.0, std::abs(ref))) << "X=" << x;
  }
}

TEST(UtdTransition, Limits) {
  EXPECT_EQ(utd::transitionF(0.0), Complex(0.0, 0.0));
  // Small X: F = √(πX)e^{i(π/4 + X)} − 2iX + O(X^{3/2}).
  for (double x : {1e-12, 1e-8, 1e-5, 1e-3}) {
    const Complex lead = std::sqrt(kPi * x) * std::polar(1.0, 0.25 * kPi + x);
    EXPECT_NEAR(std::abs(utd::transitionF(x) - lead), 2.0 * x, 3.0 * std::pow(x, 1.5)) << x;
    EXPECT_NEAR(std::abs(utd::transitionF(x) - lead + Complex(0.0, 2.0 * x)), 0.0, 3.0 * std::pow(x, 1.5)) << x;
  }
  // Large X: F = 1 + i/(2X) − 3/(4X²) − 15i/(8X³) + O(X⁻⁴).
  for (double x : {30.0, 100.0, 1e3, 1e5, 1e8, 1e12}) {
    const Complex series = 1.0 + Complex(0.0, 0.5 / x) - 0.75 / (x * x) - Complex(0.0, 15.0 / 8.0) / (x * x * x);
    EXPECT_NEAR(std::abs(utd::transitionF(x) - series), 0.0, 110.0 / std::pow(x, 4) + 1e-14) << x;
  }
  EXPECT_THROW(utd::transitionF(-1.0), diffray::core::InputError);
  EXPECT_THROW(utd::transitionF(std::nan("")), diffray::core::InputError);
}

TEST(UtdCoefficient, CotTransitionLimitMatchesTheProduct) {
  // Off the boundary cotTransition is the product cot(ε/2n)·F(2kL sin²(ε/2)), written out here (F already
  // checked against quadrature above), whose one-sided limits are ±n√(2πkL) in size; within 1e-9 rad of it,
  // the mean of those limits, n(−2kLε e^{iπ/4})e^{iπ/4}, far smaller.
  for (double n : {1.5, 2.0}) {
    for (double kl : {0.1, 10.0, 1e4}) {
      for (double eps : {-3e-9, -1.5e-9, 1.5e-9, 3e-9, 1e-6}) {
        const double s = std::sin(0.5 * eps);
        const Complex product = utd::transitionF(2.0 * kl * s * s) / std::tan(eps / (2.0 * n));
        const Complex value = utd::cotTransition(n, kl, eps);
        EXPECT_NEAR(std::abs(value - product), 0.0, 1e-12 * std::abs(product)) << n << " " << kl << " " << eps;
        if (std::abs(eps) < 1e-8) {
          EXPECT_NEAR(std::abs(value), n * std::sqrt(2.0 * kPi * kl), 1e-4 * std::abs(value));
        }
      }
      for (double eps : {-1e-9, -1e-12, 0.0, 1e-12, 1e-9}) {
        const Complex mean = n * Complex(0.0, -2.0 * kl * eps);  // e^{iπ/4}·e^{iπ/4} = i
        EXPECT_NEAR(std::abs(utd::cotTransition(n, kl, eps) - mean), 0.0, 1e-12 * (1.0 + std::abs(mean))) << eps;
      }
    }
  }
}

TEST(UtdCoefficient, HalfPlaneCheckValues) {
  // Sommerfeld's half-plane to 5 digits, computed by quadrature in reference_test.cpp
  // (SommerfeldHalfPlane.MatchesCheckValues): λ = 1 m, ρ = 3 m, φ0 = 60°, φ = 260° (in the shadow: the
  // field is the diffracted one).
  EXPECT_NEAR(std::abs(utdHalfPlane(1.0, 3.0, degrees(260), degrees(60), true)), 0.27525, 5e-6);
  EXPECT_NEAR(std::abs(utdHalfPlane(1.0, 3.0, degrees(260), degrees(60), false)), 0.18061, 5e-6);
}

TEST(UtdCoefficient, HalfPlaneEqualsSommerfeldEverywhere) {
  // Many angles, both boundary conditions, several kρ, and points within 1e-6 and 1e-12 rad of the
  // shadow and reflection boundaries on both sides (and exactly on them, GO weighted ½).
  double worst = 0.0;
  for (bool rigid : {true, false}) {
    for (double rho : {0.05, 0.5, 3.0, 40.0}) {
      for (double phi0_deg : {10.0, 45.0, 60.0, 90.0, 135.0}) {
        const double phi0 = degrees(phi0_deg);
        std::vector<double> phis;
        for (int i = 1; i < 72; ++i) phis.push_back(degrees(5.0 * i));
        for (double b : {kPi + phi0, kPi - phi0})
          for (double d : {-1e-6, -1e-12, 0.0, 1e-12, 1e-6}) phis.push_back(b + d);
        for (double phi : phis) {
          const Complex ref = diffray::reference::sommerfeldHalfPlane(1.0, rho, phi, phi0, rigid);
          const double err = std::abs(utdHalfPlane(1.0, rho, phi, phi0, rigid) - ref);
          worst = std::max(worst, err);
          EXPECT_NEAR(err, 0.0, 1e-12) << "rigid=" << rigid << " rho=" << rho << " phi0=" << phi0_deg
                                      << " phi=" << phi;
        }
      }
    }
  }
  RecordProperty("worst_abs_error", std::to_string(worst));
  std::printf("UTD vs Sommerfeld half-plane: worst |u_utd - u_exact| = %.3g\n", worst);
}

TEST(UtdCoefficient, RejectsBadArguments) {
  EXPECT_THROW(utd::wedgeCoefficient(0.5, 1.0, 1.0, 1.0, 0.5, 1.0), diffray::core::InputError);
  EXPECT_THROW(utd::wedgeCoefficient(2.0, 0.0, 1.0, 1.0, 0.5, 1.0), diffray::core::InputError);
  EXPECT_THROW(utd::wedgeCoefficient(2.0, 1.0, -1.0, 1.0, 0.5, 1.0), diffray::core::InputError);
  EXPECT_THROW(utd::wedgeCoefficient(2.0, 1.0, 1.0, 1.0, 0.5, 0.0), diffray::core::InputError);
}
