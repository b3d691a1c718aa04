// Tests of the closed-form microstructure WDFs (Openings, PhaseGrating), of their cell integrals, of the
// tabulated WBSDF built from them (marginals) and of its importance sampler, plus the chi-square harness
// (tests/chi2.h) the sampler tests use. Oracles, all written here and sharing no code with diffray:
//  * design.md §1 closed forms (rect, double slit, half-plane WDFs; slit Fraunhofer |T(u)|² = a²sinc²(au));
//  * the numeric pseudo-Wigner of a sampled transmittance (wigner_fft.h, an independent FFT implementation)
//    with the sampled rect's known Dirichlet-kernel error bound (see tests/wigner_fft_test.cpp);
//  * brute-force Gauss–Legendre quadrature (nodes computed here by Newton's method) of the closed forms,
//    and the sine integral Si computed by the same quadrature;
//  * Fourier coefficients of the grating's transmittance by the trapezoid rule (exact for periodic
//    analytic integrands), cross-checked against std::cyl_bessel_j;
//  * chi-square tests of WbsdfTable::sample against WbsdfTable::pdf, and sample means against the row's
//    signed mass with standard errors estimated from the same samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "chi2.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/table.h"
#include "diffray/wbsdf/wigner_fft.h"

namespace dw = diffray::wbsdf;
namespace dt = diffray::testing;
using Cx = std::complex<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;

double sincOracle(double z) { return z == 0.0 ? 1.0 : std::sin(kPi * z) / (kPi * z); }

/// design.md §1: rect of width a centred on 0, W = 2(a − 2|x|)·sinc(2u(a − 2|x|)) for |x| < a/2.
double rectWdf(double x, double u, double a) {
  const double l = a - 2.0 * std::abs(x);
  return l > 0.0 ? 2.0 * l * sincOracle(2.0 * u * l) : 0.0;
}

/// design.md §1: double slit of width a, centres ±d/2: W_r(x−d/2) + W_r(x+d/2) + 2cos(2πud)·W_r(x).
double doubleSlitWdf(double x, double u, double a, double d) {
  return rectWdf(x - 0.5 * d, u, a) + rectWdf(x + 0.5 * d, u, a) + 2.0 * std::cos(2.0 * kPi * u * d) * rectWdf(x, u, a);
}

/// design.md §4: the step (half-plane x ≥ 0 open) has W = sin(4πux)/(πu) for x > 0 (4x at u = 0).
double halfPlaneWdf(double x, double u) {
  if (x <= 0.0) return 0.0;
  return u == 0.0 ? 4.0 * x : std::sin(4.0 * kPi * u * x) / (kPi * u);
}

// ---- Quadrature written for these tests ----------------------------------------------------------------

struct Rule {
  std::vector<double> nodes, weights;
};

/// n-point Gauss–Legendre on [−1, 1] by Newton's method on P_n (Numerical Recipes' gauleg).
Rule gaussRule(int n) {
  Rule r;
  r.nodes.resize(n);
  r.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    r.nodes[i] = x;
    r.weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return r;
}

const Rule& rule10() {
  static const Rule r = gaussRule(10);
  return r;
}

/// Composite 10-point Gauss–Legendre of f over [a, b] with `panels` equal panels.
template <class F>
double quad(F&& f, double a, double b, int panels) {
  const Rule& r = rule10();
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = a + (p + 0.5) * h;
    for (std::size_t i = 0; i < r.nodes.size(); ++i) sum += r.weights[i] * f(mid + 0.5 * h * r.nodes[i]);
  }
  return 0.5 * h * sum;
}

/// Sine integral Si(z) = ∫_0^z sin(t)/t dt: cumulative 10-point Gauss over panels of width π/2 (each panel
/// is a quarter period: the rule's error there is far below 1e-16), cached at multiples of π/2.
double sineIntegral(double z) {
  if (z < 0.0) return -sineIntegral(-z);
  static std::vector<double> knots{0.0};  // Si(k·π/2)
  const double step = 0.5 * kPi;
  const auto integrand = [](double t) { return t == 0.0 ? 1.0 : std::sin(t) / t; };
  const std::size_t k = static_cast<std::size_t>(z / step);
  while (knots.size() <= k) {
    const double t0 = static_cast<double>(knots.size() - 1) * step;
    knots.push_back(knots.back() + quad(integrand, t0, t0 + step, 1));
  }
  const double t0 = static_cast<double>(k) * step;
  return knots[k] + (z > t0 ? quad(integrand, t0, z, 1) : 0.0);
}

/// ∫_{x1}^{x2} ∫_{u1}^{u2} w(x,u) du dx by 2D composite Gauss, x split at the closed form's kinks; panels
/// chosen so that each spans ≤ 1/4 of an oscillation (x-frequency ≤ 2|u|max, u-frequency ≤ max_lag), where
/// the 10-point rule is exact to rounding.
template <class W>
double bruteCellIntegral(W&& w, const std::vector<double>& kinks, double x1, double x2, double u1, double u2,
                         double max_lag) {
  std::vector<double> cuts{x1};
  for (double k : kinks)
    if (k > x1 && k < x2) cuts.push_back(k);
  cuts.push_back(x2);
  std::sort(cuts.begin(), cuts.end());
  const double umax = std::max(std::abs(u1), std::abs(u2));
  const int panels_u = 1 + static_cast<int>(std::ceil(4.0 * (u2 - u1) * max_lag));
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const int panels_x = 1 + static_cast<int>(std::ceil(4.0 * (cuts[i + 1] - cuts[i]) * 2.0 * umax));
    total += quad([&](double x) { return quad([&](double u) { return w(x, u); }, u1, u2, panels_u); }, cuts[i],
                  cuts[i + 1], panels_x);
  }
  return total;
}

/// Uniform in [0, 1) from a 64-bit engine (53 random bits).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

dw::TableOptions optionsFor(double wavelength) {
  dw::TableOptions o;
  o.wavelength_m = wavelength;
  return o;
}

}  // namespace

// ---- The chi-square harness itself -------------------------------------------------------------------------

// Q(a, x) against closed forms: Q(1, x) = e^{−x}; integer a: e^{−x}Σ_{k<a} x^k/k!; Q(1/2, x) = erfc(√x); and
// the tabulated 95 % quantile of χ²_10, 18.307 (to its 3 printed decimals: Q moves by ~4e-6 per 1e-3).
// Both branches (series for x < a + 1, continued fraction above) are exercised.
TEST(Chi2Harness, IncompleteGammaMatchesClosedForms) {
  EXPECT_NEAR(dt::regularizedGammaQ(1.0, 1.0), std::exp(-1.0), 1e-14);
  for (double x : {0.1, 0.5, 1.9, 2.5, 7.0, 30.0}) {
    EXPECT_NEAR(dt::regularizedGammaQ(1.0, x), std::exp(-x), 1e-14 * std::max(1.0, std::exp(-x))) << x;
    for (int a : {2, 3, 6}) {
      double s = 0.0, term = 1.0;
      for (int k = 0; k < a; ++k) {
        s += term;
        term *= x / (k + 1);
      }
      const double exact = std::exp(-x) * s;
      EXPECT_NEAR(dt::regularizedGammaQ(a, x), exact, 1e-13 * exact + 1e-15) << "a=" << a << " x=" << x;
    }
    EXPECT_NEAR(dt::regularizedGammaQ(0.5, x), std::erfc(std::sqrt(x)), 1e-13 * std::erfc(std::sqrt(x)) + 1e-15)
        << x;
  }
  EXPECT_NEAR(dt::chiSquareSurvival(18.307, 10), 0.05, 1e-5);
  EXPECT_NEAR(dt::chiSquareSurvival(3.841, 1), 0.05, 1e-4);  // χ²_1 95 % quantile, 3.841
  EXPECT_DOUBLE_EQ(dt::chiSquareSurvival(0.0, 4), 1.0);
}

// Pearson statistic and merging on hand-computed cases. 4 equiprobable bins, counts {30, 20, 25, 25}:
// X² = (25 + 25)/25 = 2, dof 3, p = erfc(1) + √(4/π)e^{−1} (χ²_3 survival in closed form).
TEST(Chi2Harness, StatisticAndMerging) {
  const dt::Chi2Result r = dt::chiSquareTest({30, 20, 25, 25}, {0.25, 0.25, 0.25, 0.25});
  EXPECT_NEAR(r.statistic, 2.0, 1e-14);
  EXPECT_EQ(r.dof, 3);
  EXPECT_NEAR(r.p_value, std::erfc(1.0) + std::sqrt(4.0 / kPi) * std::exp(-1.0), 1e-13);
  // Expected counts 50, 49, 0.5, 0.5: the last two (1 < 5) fold into the second group → 2 groups, dof 1.
  const dt::Chi2Result m = dt::chiSquareTest({50, 48, 1, 1}, {0.5, 0.49, 0.005, 0.005});
  EXPECT_EQ(m.bins, 2);
  EXPECT_EQ(m.dof, 1);
  EXPECT_NEAR(m.statistic, 0.0, 1e-12);
  EXPECT_NEAR(m.p_value, 1.0, 1e-12);
  // A count where nothing is expected is impossible: p = 0.
  EXPECT_EQ(dt::chiSquareTest({10, 10, 1}, {0.5, 0.5, 0.0}).p_value, 0.0);
}

// ---- Openings: closed-form WDF -----------------------------------------------------------------------------

TEST(OpeningsWdf, SlitMatchesDesignClosedForm) {
  const double a = 1e-5;
  for (double centre : {0.0, 3.7e-6}) {
    const auto slit = dw::Openings::slit(a, centre);
    for (int i = 0; i <= 56; ++i) {
      const double x = centre + (-0.7 + 1.4 * i / 56.0) * a;
      for (double ua : {0.0, 0.3, -0.3, 0.5, 1.0, 2.71, -7.3, 50.2, 1000.1}) {
        const double u = ua / a;
        EXPECT_NEAR(slit->wdf(x, u), rectWdf(x - centre, u, a), 1e-12 * 2.0 * a) << "x=" << x << " u=" << u;
      }
    }
  }
}

TEST(OpeningsWdf, DoubleSlitMatchesDesignFormulaWithSignedMidAirTerm) {
  const double a = 1e-5, d = 3.5 * a;
  const auto slits = dw::Openings::slits(2, a, d);
  for (int i = 0; i <= 120; ++i) {
    const double x = (-2.5 + 5.0 * i / 120.0) * a;
    for (double ua : {0.0, 0.13, -0.13, 0.5 * a / d, 0.77, -2.2, 9.9}) {
      const double u = ua / a;
      EXPECT_NEAR(slits->wdf(x, u), doubleSlitWdf(x, u, a, d), 1e-12 * 4.0 * a) << "x=" << x << " u=" << u;
    }
  }
  // Midway, where t = 0: W(0,u) = 2cos(2πud)·2a·sinc(2ua), −4a·sinc(a/d) at u = 1/(2d).
  EXPECT_EQ(std::norm(slits->transmittance(0.0)), 0.0);
  EXPECT_NEAR(slits->wdf(0.0, 0.5 / d), -4.0 * a * sincOracle(a / d), 1e-12 * a);
  EXPECT_LT(slits->wdf(0.0, 0.5 / d), -2.0 * a);
  EXPECT_NEAR(slits->wdf(0.0, 0.0), 4.0 * a, 1e-12 * a);
}

TEST(OpeningsWdf, HalfPlaneMatchesStepFormula) {
  const double extent = 1e-3;
  const auto edge = dw::Openings::halfPlane(extent);
  for (double x : {-2e-4, -1e-9, 1e-9, 3.3e-7, 1e-6, 4.7e-5, 9.99e-4}) {
    for (double u : {0.0, 1e3, -1e3, 2.5e5, 1.3e6, -4e6}) {
      EXPECT_NEAR(edge->wdf(x, u), halfPlaneWdf(x, u), 1e-12 * 4.0 * std::max(x, 1e-9)) << x << " " << u;
    }
  }
}

// Openings::wdf against the discrete pseudo-Wigner of the sampled double slit (wignerFFT, an independent
// implementation: FFT over lags of the sampled t, built here from the test's own indicator). Geometry as
// in tests/wigner_fft_test.cpp: every edge half-way between samples, so each term of the discrete W is the
// closed-form term times (2πu·dx)/sin(2πu·dx) exactly, and |W_fft − W| ≤ (that ratio − 1)·Σ|terms|
// (≤ 2.6 % of Σ|terms| for |u| < 1/(16dx), well inside the band |u| < 1/(4dx)).
TEST(OpeningsWdf, DoubleSlitMatchesNumericWigner) {
  const double dx = 1e-6, a = 10 * dx, d = 41 * dx;
  const auto slits = dw::Openings::slits(2, a, d);
  const auto indicator = [&](double x) {
    return Cx(std::abs(x - d / 2) < a / 2 || std::abs(x + d / 2) < a / 2 ? 1.0 : 0.0);
  };
  const dw::WignerGrid w = dw::wignerFFT(dw::sampleProfile(indicator, -40 * dx, 40 * dx, dx), 256);
  int checked = 0;
  double min_mid = 0.0;
  for (int j = 0; j < w.nx; ++j) {
    const double x = w.xAt(j);
    for (int k = 0; k < w.nu; ++k) {
      const double u = w.uAt(k);
      if (std::abs(u) >= 1.0 / (16 * dx)) continue;
      const double z = 2.0 * kPi * u * dx;
      const double ratio = z == 0.0 ? 1.0 : z / std::sin(z);
      const double terms = std::abs(rectWdf(x - d / 2, u, a)) + std::abs(rectWdf(x + d / 2, u, a)) +
                           2.0 * std::abs(rectWdf(x, u, a));
      EXPECT_NEAR(slits->wdf(x, u), w.at(j, k), (ratio - 1.0) * terms + 1e-12 * a) << "x=" << x << " u=" << u;
      if (std::abs(x) < 0.5 * dx) min_mid = std::min(min_mid, slits->wdf(x, u));
      ++checked;
    }
  }
  EXPECT_GT(checked, 81 * 60);
  EXPECT_LT(min_mid, -0.5 * 4 * a);  // the mid-air term is strongly negative in both
}

// ---- Openings: cell integrals ------------------------------------------------------------------------------
// Oracle: 2D composite Gauss (written above) of the closed forms, split at their kinks. Tolerance: 1e-6 of
// P·(u2 − u1), the largest mass a cell of that u-width can hold (P = peak |W|). This is the accuracy the
// table needs (far below Monte Carlo noise), and a 6-point Gauss rule with ≥ 1 panel per oscillation of
// the integrand in u (what the code documents) has an error bound of ~7e-7 of that.

TEST(OpeningsCellMass, SlitMatchesBruteForceQuadrature) {
  const double a = 1e-5;
  const auto slit = dw::Openings::slit(a);
  const std::vector<double> kinks{-a / 2, 0.0, a / 2};
  const auto w = [&](double x, double u) { return rectWdf(x, u, a); };
  struct Cell {
    double x1, x2, u1, u2;
  };
  const double dx = a / 64, du = 1.0 / (32 * a);
  const Cell cells[] = {
      {-a / 8, a / 8, 0.3 / a, 2.7 / a},         // straddles the kink at x = 0, several lobes
      {0.45 * a, 0.55 * a, -1.0 / a, 1.0 / a},   // straddles the edge a/2 (half outside)
      {0.1 * a, 0.2 * a, 5.0 / a, 5.2 / a},      // far lobe, small mass
      {-a / 2, a / 2, -3.0 / a, 3.0 / a},        // the whole slit
      {3 * dx, 4 * dx, 7 * du, 8 * du},          // a table-sized cell
      {-dx, dx, -du / 2, du / 2},                // table-sized, centred on both kinks' neighbour x = 0
      {0.6 * a, 0.7 * a, -1.0 / a, 1.0 / a},     // outside: exactly 0
  };
  for (const Cell& c : cells) {
    const double exact = bruteCellIntegral(w, kinks, c.x1, c.x2, c.u1, c.u2, a) / (c.x2 - c.x1);
    EXPECT_NEAR(slit->cellMass(c.x1, c.x2, c.u1, c.u2), exact, 1e-6 * 2.0 * a * (c.u2 - c.u1))
        << "cell x [" << c.x1 << ", " << c.x2 << "] u [" << c.u1 << ", " << c.u2 << "]";
  }
}

TEST(OpeningsCellMass, DoubleSlitMatchesBruteForceQuadrature) {
  const double a = 1e-5, d = 4.0 * a;
  const auto slits = dw::Openings::slits(2, a, d);
  std::vector<double> kinks;
  for (double c : {-d / 2, 0.0, d / 2})
    for (double s : {-a / 2, 0.0, a / 2}) kinks.push_back(c + s);
  const auto w = [&](double x, double u) { return doubleSlitWdf(x, u, a, d); };
  struct Cell {
    double x1, x2, u1, u2;
  };
  const Cell cells[] = {
      {-a / 10, a / 10, 0.2 / d, 0.8 / d},                    // midway: the negative cross term
      {-a / 10, a / 10, -3.0 / a, 3.0 / a},                   // midway, many fringes
      {0.4 * a, 0.6 * a, -1.0 / a, 1.0 / a},                  // the cross term's edge at a/2
      {d / 2 - 0.6 * a, d / 2 - 0.4 * a, -1.0 / a, 1.5 / a},  // a slit's inner edge
      {d / 2 - 0.1 * a, d / 2 + 0.1 * a, 0.0, 0.25 / a},      // a slit's centre
      {-d / 2 - a, d / 2 + a, -2.0 / a, 2.0 / a},             // everything
  };
  for (const Cell& c : cells) {
    const double exact = bruteCellIntegral(w, kinks, c.x1, c.x2, c.u1, c.u2, d + a) / (c.x2 - c.x1);
    EXPECT_NEAR(slits->cellMass(c.x1, c.x2, c.u1, c.u2), exact, 1e-6 * 4.0 * a * (c.u2 - c.u1))
        << "cell x [" << c.x1 << ", " << c.x2 << "] u [" << c.u1 << ", " << c.u2 << "]";
  }
  // Midway the cell at u ∈ [0.2, 0.8]/d is negative: mass where t = 0.
  EXPECT_LT(slits->cellMass(-a / 10, a / 10, 0.2 / d, 0.8 / d), 0.0);
}

TEST(OpeningsCellMass, HalfPlaneMatchesBruteForceQuadrature) {
  const double lambda = 1e-6;
  const auto edge = dw::Openings::halfPlane(20 * lambda);
  struct Cell {
    double x1, x2, u1, u2;
  };
  const Cell cells[] = {
      {0.0, lambda, -1.0 / lambda, 1.0 / lambda},
      {-0.5 * lambda, 0.5 * lambda, 0.1 / lambda, 0.6 / lambda},  // straddles the edge
      {3 * lambda, 3.2 * lambda, -0.3 / lambda, -0.1 / lambda},
  };
  for (const Cell& c : cells) {
    const double exact =
        bruteCellIntegral(halfPlaneWdf, {0.0}, c.x1, c.x2, c.u1, c.u2, 4.0 * c.x2) / (c.x2 - c.x1);
    EXPECT_NEAR(edge->cellMass(c.x1, c.x2, c.u1, c.u2), exact, 1e-6 * 4.0 * c.x2 * (c.u2 - c.u1))
        << "cell x [" << c.x1 << ", " << c.x2 << "] u [" << c.u1 << ", " << c.u2 << "]";
  }
}

// ---- Table marginals ---------------------------------------------------------------------------------------
// u-marginal per row: ∫_{−H}^{H} W du = (2/π)Si(2πHw) for a rect term of lag length w = a − 2|x| (and
// (2/π)[Si(2πH(w+d)) + Si(2πH(w−d))] for a double slit's cross term), so Σ_k mass(j,k) must equal the
// x-average of that over row j, and x-average |t|² minus it is the row's truncated share. Tolerance 1e-6 of
// |t|² (energy conservation per row, far below Monte Carlo noise).

TEST(WbsdfTableMarginals, SlitRowsAndColumns) {
  const double lambda = 1e-6, a = 10 * lambda;
  const auto slit = dw::Openings::slit(a);
  const auto table = dw::WbsdfTable::build(*slit, optionsFor(lambda));
  const dw::TableLayout& L = table->layout();
  const double h = 2.0 / lambda;  // default half-range: 2/λ
  ASSERT_NEAR(L.u0_per_m, -h, 1e-9 * h);
  ASSERT_NEAR(L.u0_per_m + L.nu * L.du_per_m, h, 1e-9 * h);
  ASSERT_NEAR(L.x0_m, -a / 2, 1e-15);
  ASSERT_NEAR(L.x0_m + L.nx * L.dx_m, a / 2, 1e-15);
  ASSERT_FALSE(L.line_spectrum);

  const auto inRange = [&](double x) { return (2.0 / kPi) * sineIntegral(2.0 * kPi * h * (a - 2.0 * std::abs(x))); };
  double tail_sum = 0.0;
  for (int j = 0; j < L.nx; ++j) {
    const double x1 = L.x0_m + j * L.dx_m, x2 = x1 + L.dx_m;
    double row = 0.0;
    for (int k = 0; k < L.nu; ++k) row += table->mass(j, k);
    // Rows are split at x = 0 (the kink) by construction (nx even); the integrand oscillates ≤ 2H per metre.
    double expect = 0.0;
    for (const auto& [p, q] : {std::pair{x1, std::min(x2, 0.0)}, std::pair{std::max(x1, 0.0), x2}})
      if (q > p) expect += quad(inRange, p, q, 4);
    expect /= L.dx_m;
    const double t2 = 1.0;  // every row lies inside the opening: x-average of |t|² = 1
    const double tail = t2 - expect;
    EXPECT_NEAR(row + tail, t2, 1e-6) << "row " << j;
    tail_sum += tail;
  }
  EXPECT_NEAR(table->truncatedMass(), tail_sum / L.nx, 1e-6);
  EXPECT_GT(table->truncatedMass(), 0.0);

  // Column marginal: Σ_j mass(j,k)·dx = ∫_cell |T(u)|² du, T(u) = a·sinc(au) (the Fraunhofer pattern).
  // Tolerance: the per-cell 1e-6·(2a·du) of the cell-mass tests, summed over rows with weight dx.
  for (int k = 0; k < L.nu; ++k) {
    double column = 0.0;
    for (int j = 0; j < L.nx; ++j) column += table->mass(j, k) * L.dx_m;
    const double u1 = L.u0_per_m + k * L.du_per_m;
    const double exact = quad([&](double u) { return a * a * sincOracle(a * u) * sincOracle(a * u); }, u1,
                              u1 + L.du_per_m, 2);
    EXPECT_NEAR(column, exact, 2e-6 * a * a * L.du_per_m) << "column " << k;
  }
}

TEST(WbsdfTableMarginals, DoubleSlitRows) {
  const double lambda = 1e-6, a = 5 * lambda, d = 20 * lambda;
  const auto slits = dw::Openings::slits(2, a, d);
  const auto table = dw::WbsdfTable::build(*slits, optionsFor(lambda));
  const dw::TableLayout& L = table->layout();
  const double h = -L.u0_per_m;
  ASSERT_NEAR(h, 2.0 / lambda, 1e-9 * h);
  ASSERT_NEAR(L.u0_per_m + L.nu * L.du_per_m, h, 1e-9 * h);
  const auto si2 = [&](double w) { return (2.0 / kPi) * sineIntegral(2.0 * kPi * h * w); };
  // ∫_{−H}^{H} W(x,u) du in closed form (see the comment above the slit test).
  const auto inRange = [&](double x) {
    double s = 0.0;
    for (double c : {-d / 2, d / 2}) {
      const double w = a - 2.0 * std::abs(x - c);
      if (w > 0) s += si2(w);
    }
    const double w = a - 2.0 * std::abs(x);
    if (w > 0) s += si2(w + d) + si2(w - d);
    return s;
  };
  std::vector<double> kinks;
  for (double c : {-d / 2, 0.0, d / 2})
    for (double s : {-a / 2, 0.0, a / 2}) kinks.push_back(c + s);
  const auto open = [&](double p, double q) {  // length of [p, q] inside the openings
    double len = 0.0;
    for (double c : {-d / 2, d / 2}) len += std::max(0.0, std::min(q, c + a / 2) - std::max(p, c - a / 2));
    return len;
  };
  int midway_rows = 0;
  for (int j = 0; j < L.nx; ++j) {
    const double x1 = L.x0_m + j * L.dx_m, x2 = x1 + L.dx_m;
    double row = 0.0;
    for (int k = 0; k < L.nu; ++k) row += table->mass(j, k);
    std::vector<double> cuts{x1};
    for (double kk : kinks)
      if (kk > x1 && kk < x2) cuts.push_back(kk);
    cuts.push_back(x2);
    double expect = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) expect += quad(inRange, cuts[i], cuts[i + 1], 2);
    expect /= L.dx_m;
    const double t2 = open(x1, x2) / L.dx_m;
    const double tail = t2 - expect;
    EXPECT_NEAR(row + tail, t2, 1e-6) << "row " << j << " x=" << x1;
    if (t2 == 0.0 && std::abs(x1) < a / 2) {
      ++midway_rows;  // where nothing is open the row still carries signed mass, summing to ≈ 0 − tail
      double abs_row = 0.0;
      for (int k = 0; k < L.nu; ++k) abs_row += std::abs(table->mass(j, k));
      EXPECT_GT(abs_row, 0.5) << "row " << j;
    }
  }
  EXPECT_GT(midway_rows, 10);
}

// ---- PhaseGrating ------------------------------------------------------------------------------------------
// Oracles: c_q = (1/Λ)∫_0^Λ t(x)e^{−i2πqx/Λ}dx (order q carries |c_q|²), and, pointwise, the line weights of
// W(x,·): the mutual intensity K(s) = t(x+s/2)t*(x−s/2) has period 2Λ in s, so W(x,u) = Σ_n c_n(x)·δ(u − n/(2Λ))
// with c_n(x) = (1/(2Λ))∫_0^{2Λ} K(s)e^{−iπns/Λ}ds. Both by the trapezoid rule on a period (exact to rounding
// for these analytic periodic integrands with ≲ 30 significant harmonics and 512 nodes).

namespace {

Cx gratingT(double x, double period, double m) { return std::polar(1.0, 0.5 * m * std::sin(2.0 * kPi * x / period)); }

double gratingOrder(int q, double period, double m) {
  const int n = 512;
  Cx c = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = period * i / n;
    c += gratingT(x, period, m) * std::polar(1.0, -2.0 * kPi * q * x / period);
  }
  return std::norm(c / static_cast<double>(n));
}

Cx gratingLine(int line, double x, double period, double m) {
  const int n = 512;
  Cx c = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s = 2.0 * period * i / n;
    c += gratingT(x + s / 2, period, m) * std::conj(gratingT(x - s / 2, period, m)) *
         std::polar(1.0, -kPi * line * s / period);
  }
  return c / static_cast<double>(n);
}

}  // namespace

TEST(PhaseGratingWdf, PeriodAveragedLinesAreBesselEfficiencies) {
  const double period = 1.6e-6;
  for (double m : {3.0, -2.2, 0.7}) {
    const dw::PhaseGrating g(period, m);
    double total = 0.0;
    for (int q = -8; q <= 8; ++q) {
      const double oracle = gratingOrder(q, period, m);
      // The oracle itself against the Jacobi–Anger result J_q(m/2)² (J_{−q} = ±J_q).
      const double j = std::cyl_bessel_j(static_cast<double>(std::abs(q)), std::abs(0.5 * m));
      ASSERT_NEAR(oracle, j * j, 1e-14) << "m=" << m << " q=" << q;
      for (double x0 : {0.0, 0.37 * period}) {
        const double line = g.cellMass(x0, x0 + period, (q - 0.25) / period, (q + 0.25) / period);
        EXPECT_NEAR(line, oracle, 1e-13) << "m=" << m << " q=" << q << " x0=" << x0;
        // Half-order lines (q + 1/2)/Λ carry cross terms only, which average to 0 over a period.
        const double half = g.cellMass(x0, x0 + period, (q + 0.4) / period, (q + 0.6) / period);
        EXPECT_NEAR(half, 0.0, 1e-13) << "m=" << m << " q=" << q << " x0=" << x0;
      }
      total += oracle;
    }
    EXPECT_NEAR(total, 1.0, 1e-10);  // |q| ≤ 8 holds all but ~1e-13 of the energy for |m|/2 ≤ 1.5
  }
}

TEST(PhaseGratingWdf, PointwiseLinesMatchMutualIntensitySeriesAndSumToOne) {
  const double period = 1.6e-6;
  for (double m : {3.0, -2.2}) {
    const dw::PhaseGrating g(period, m);
    for (double xf : {0.0, 0.1, 0.25, 0.61, 0.9}) {
      const double x = xf * period;
      double sum = 0.0;
      for (int n = -60; n <= 60; ++n) {
        const double w = g.wdf(x, n / (2.0 * period));
        const Cx oracle = gratingLine(n, x, period, m);
        ASSERT_LT(std::abs(oracle.imag()), 1e-13);
        EXPECT_NEAR(w, oracle.real(), 1e-13) << "m=" << m << " x=" << xf << "Λ line " << n;
        sum += w;
      }
      EXPECT_NEAR(sum, 1.0, 1e-12) << "m=" << m << " x=" << xf << "Λ";  // Σ lines = |t(x)|² = 1
      // The same through cellMass over a vanishing x-cell and every line.
      EXPECT_NEAR(g.cellMass(x, x + 1e-9 * period, -61 / (2.0 * period), 61 / (2.0 * period)), 1.0, 1e-8);
    }
  }
}

// ---- Sampling ----------------------------------------------------------------------------------------------

namespace {

/// Draws n samples of u' at x and checks (i) a chi-square test of their histogram, over half-cells of the
/// table (cells for line spectra), against pdf(x,·)·(bin width); (ii) every |weight| = rowAbsMass(row);
/// (iii) the mean weight equals the row's signed mass Σ_k mass (its expectation, table.h) within 5
/// standard errors, the standard error s/√n from the same samples (a 5σ two-sided normal tail is 6e-7).
void checkSampler(const dw::WbsdfTable& table, double x, int n, std::uint64_t seed) {
  const dw::TableLayout& L = table.layout();
  const int row = static_cast<int>(std::floor((x - L.x0_m) / L.dx_m));
  ASSERT_GE(row, 0);
  ASSERT_LT(row, L.nx);
  const int sub = L.line_spectrum ? 1 : 2;
  const int bins = L.nu * sub;
  const double width = L.du_per_m / sub;
  std::vector<double> observed(bins + 1, 0.0), prob(bins + 1, 0.0);  // last bin: outside the table
  for (int b = 0; b < bins; ++b) {
    const double centre = L.u0_per_m + (b + 0.5) * width;
    prob[b] = table.pdf(x, centre) * (L.line_spectrum ? 1.0 : width);
  }
  double row_signed = 0.0;
  for (int k = 0; k < L.nu; ++k) row_signed += table.mass(row, k);
  std::mt19937_64 rng(seed);
  double sum_w = 0.0, sum_w2 = 0.0;
  int bad_weight = 0, off_line = 0;
  for (int i = 0; i < n; ++i) {
    const dw::WbsdfTable::Sample s = table.sample(x, uniform01(rng));
    if (std::abs(s.weight) != table.rowAbsMass(row)) ++bad_weight;
    sum_w += s.weight;
    sum_w2 += s.weight * s.weight;
    const double pos = (s.u_shift - L.u0_per_m) / width;
    if (L.line_spectrum) {
      // Lines sit exactly on cell centres n/(2Λ) = n·du (u0 = −(n_half + 1/2)·du).
      const double line = s.u_shift / L.du_per_m;
      if (std::abs(line - std::round(line)) > 1e-9) ++off_line;
    }
    const int b = pos >= 0.0 && pos < bins ? static_cast<int>(pos) : bins;
    observed[b] += 1.0;
  }
  EXPECT_EQ(bad_weight, 0) << "x=" << x;
  EXPECT_EQ(off_line, 0) << "x=" << x;
  const dt::Chi2Result r = dt::chiSquareTest(observed, prob);
  EXPECT_NEAR(r.probability_sum, 1.0, 1e-9) << "x=" << x;
  EXPECT_GT(r.p_value, dt::kChi2Alpha) << "x=" << x << " X²=" << r.statistic << " dof=" << r.dof;
  const double mean = sum_w / n;
  const double var = (sum_w2 - n * mean * mean) / (n - 1.0);
  const double se = std::sqrt(std::max(var, 0.0) / n);
  EXPECT_NEAR(mean, row_signed, 5.0 * se) << "x=" << x << " row " << row;
}

}  // namespace

TEST(StatWbsdfSampler, SlitMatchesPdfAndRowMass) {
  const double lambda = 1e-6, a = 10 * lambda;
  const auto table = dw::WbsdfTable::build(*dw::Openings::slit(a), optionsFor(lambda));
  std::uint64_t seed = 101;
  for (double xf : {0.0, 0.13, -0.31, 0.47}) checkSampler(*table, xf * a, 200000, seed++);
}

TEST(StatWbsdfSampler, DoubleSlitMatchesPdfAndRowMass) {
  const double lambda = 1e-6, a = 5 * lambda, d = 20 * lambda;
  const auto table = dw::WbsdfTable::build(*dw::Openings::slits(2, a, d), optionsFor(lambda));
  EXPECT_GT(table->negativeFraction(), 0.05);
  std::uint64_t seed = 202;
  // Midway (t = 0, only the signed cross term), inside a slit, and near an outer edge.
  for (double x : {0.01 * a, d / 2 + 0.1 * a, -d / 2 - 0.4 * a}) checkSampler(*table, x, 200000, seed++);
}

TEST(StatWbsdfSampler, GratingSamplesLineCentres) {
  const double lambda = 0.5e-6, period = 1.6e-6;
  const dw::PhaseGrating g(period, 3.0);
  const auto table = dw::WbsdfTable::build(g, optionsFor(lambda));
  const dw::TableLayout& L = table->layout();
  ASSERT_TRUE(L.line_spectrum);
  ASSERT_NEAR(L.du_per_m, 0.5 / period, 1e-9 / period);
  std::uint64_t seed = 303;
  for (double xf : {0.05, 0.3, 0.77}) checkSampler(*table, xf * period, 200000, seed++);
}
