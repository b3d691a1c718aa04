// Closed-form microstructure WDFs (Openings, PhaseGrating) and their cell integrals, plus the chi-square
// harness the sampler tests use. Oracles (wbsdf_fixtures.h, chi2.h), sharing no code with diffray:
//  * closed forms (rect, double slit, half-plane WDFs from the WDF definition, Cuypers et al. 2012, eq. 2);
//  * the numeric pseudo-Wigner of a sampled transmittance (wigner_fft.h, an independent FFT implementation)
//    with the sampled rect's known Dirichlet-kernel error bound (see tests/wigner_fft_test.cpp);
//  * brute-force Gauss–Legendre quadrature of the closed forms;
//  * Fourier coefficients of the grating's transmittance by the trapezoid rule, cross-checked against
//    std::cyl_bessel_j.
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
#include "wbsdf_fixtures.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/table.h"
#include "diffray/wbsdf/wigner_fft.h"

namespace dw = diffray::wbsdf;
namespace dt = diffray::testing;
using Cx = std::complex<double>;
using namespace diffray::testing;  // fixtures

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

TEST(OpeningsWdf, SlitMatchesRectClosedForm) {
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

TEST(OpeningsWdf, DoubleSlitMatchesClosedFormWithSignedMidAirTerm) {
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

namespace {

// n slits of width a, centres (j − (n−1)/2)·d: the pairwise sum of cross-Wigner terms, each pair's signed cross term
// midway between its two slits.
double manySlitsWdf(double x, double u, double a, double d, int n) {
  double w = 0.0;
  for (int j = 0; j < n; ++j) {
    const double cj = (j - 0.5 * (n - 1)) * d;
    w += rectWdf(x - cj, u, a);
    for (int k = j + 1; k < n; ++k) {
      const double ck = (k - 0.5 * (n - 1)) * d;
      w += 2.0 * std::cos(2.0 * kPi * u * (cj - ck)) * rectWdf(x - 0.5 * (cj + ck), u, a);
    }
  }
  return w;
}

}  // namespace

// N equal slits (double slit generalised): W = Σ_j W_r(x − c_j) + Σ_{j<k} 2cos(2πu(c_j − c_k))·W_r(x − c̄_jk),
// c̄_jk the pair's midpoint. Checks the per-piece pruning of pairs (only pairs placed about x contribute).
TEST(OpeningsWdf, ManySlitsMatchPairwiseFormula) {
  const double a = 1e-6, d = 2.3e-6;
  const int n = 9;
  const auto slits = dw::Openings::slits(n, a, d);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(-0.5 * (n * d + a), 0.5 * (n * d + a)), uu(-3.0 / a, 3.0 / a);
  for (int i = 0; i < 2000; ++i) {
    const double x = ux(rng), u = uu(rng);
    EXPECT_NEAR(slits->wdf(x, u), manySlitsWdf(x, u, a, d, n), 1e-11 * a * n * n) << "x=" << x << " u=" << u;
  }
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
// table needs (far below Monte Carlo noise); for reference, a 6-point Gauss rule with ≥ 1 panel per
// oscillation of the integrand in u (what cellMass uses) has an error bound of ~7e-7 of that.

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
      {-dx, dx, -du / 2, du / 2},                // two table rows around the kink x = 0
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

// Openings::rowMasses, the table's row sweep (sines and cosines by rotation from panel to panel), against
// cellMass cell by cell (the same panels and nodes by direct evaluation: agreement to rounding, 1e-10 of the
// row's largest cell; cellMass shares the x pieces and pair lags with it) and, on every 23rd cell, against
// the brute-force quadrature of the closed forms, which shares nothing
// (tolerance as above). Five slits (the pairwise formula) on rows straddling kinks, between slits and
// outside, with one panel per cell (600-cell rows: the rotation runs across hundreds of panels and is
// reseeded every 16) and with 7 (not a divisor of 16: reseeds fall inside cells), and the half-plane (an
// infinite opening) near its edge, against both oracles too.
TEST(OpeningsCellMass, RowMassesMatchCellByCellAndBruteForceQuadrature) {
  const double a = 1e-5, d = 2.7 * a;
  const int n = 5;
  const auto slits = dw::Openings::slits(n, a, d);
  const auto many = [&](double x, double u) { return manySlitsWdf(x, u, a, d, n); };
  std::vector<double> kinks;
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      const double c = 0.5 * ((j - 0.5 * (n - 1)) * d + (k - 0.5 * (n - 1)) * d);
      for (double e : {-a / 2, 0.0, a / 2}) kinks.push_back(c + e);
    }
  const double span = (n - 1) * d + a;
  struct Row {
    double x1, x2, u_first, du;
    int count;
  };
  const double lo = -0.5 * span;
  const Row rows[] = {
      {-a / 32, a / 32, -6.0 / a, 0.02 / a, 600},              // straddles x = 0 (a kink), 1 panel per cell
      {0.5 * d - a / 16, 0.5 * d, -6.0 / a, 0.02 / a, 600},    // between two slits: cross terms only
      {lo + 0.2 * a, lo + 0.3 * a, -3.0 / a, 0.3 / a, 20},     // the outer slit, 7 panels per cell
      {lo - 0.2 * a, lo - 0.1 * a, -1.0 / a, 0.1 / a, 20},     // outside: all 0
  };
  for (const Row& r : rows) {
    SCOPED_TRACE(::testing::Message() << "row x [" << r.x1 << ", " << r.x2 << "] du " << r.du);
    std::vector<double> got(r.count);
    slits->rowMasses(r.x1, r.x2, r.u_first, r.du, r.count, got.data());
    std::vector<double> want(r.count);
    double largest = 0.0;
    for (int k = 0; k < r.count; ++k) {
      const double u1 = r.u_first + k * r.du;
      want[k] = slits->cellMass(r.x1, r.x2, u1, u1 + r.du);
      largest = std::max(largest, std::abs(want[k]));
    }
    for (int k = 0; k < r.count; ++k) {
      EXPECT_NEAR(got[k], want[k], 1e-10 * largest) << "cell " << k;
      if (k % 23 != 0) continue;
      const double u1 = r.u_first + k * r.du;
      const double exact = bruteCellIntegral(many, kinks, r.x1, r.x2, u1, u1 + r.du, 2.0 * span) / (r.x2 - r.x1);
      EXPECT_NEAR(got[k], exact, 1e-6 * 2.0 * a * n * n * r.du) << "cell " << k;
    }
  }
  const double lambda = 1e-6;
  const auto edge = dw::Openings::halfPlane(20 * lambda);
  for (const Row& r : {Row{-0.5 * lambda, 0.5 * lambda, -1.0 / lambda, 0.01 / lambda, 200},
                       Row{3 * lambda, 3.2 * lambda, -0.3 / lambda, 0.05 / lambda, 12}}) {
    std::vector<double> got(r.count), want(r.count);
    edge->rowMasses(r.x1, r.x2, r.u_first, r.du, r.count, got.data());
    double largest = 0.0;
    for (int k = 0; k < r.count; ++k) {
      const double u1 = r.u_first + k * r.du;
      want[k] = edge->cellMass(r.x1, r.x2, u1, u1 + r.du);
      largest = std::max(largest, std::abs(want[k]));
    }
    for (int k = 0; k < r.count; ++k) EXPECT_NEAR(got[k], want[k], 1e-10 * largest) << "half-plane cell " << k;
    for (int k = 0; k < r.count; k += 11) {
      const double u1 = r.u_first + k * r.du;
      const double exact =
          bruteCellIntegral(halfPlaneWdf, {0.0}, r.x1, r.x2, u1, u1 + r.du, 4.0 * std::abs(r.x2)) / (r.x2 - r.x1);
      EXPECT_NEAR(got[k], exact, 1e-6 * 4.0 * std::abs(r.x2) * r.du) << "half-plane cell " << k;
    }
  }
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
      // The same through cellMass over a vanishing x-cell (1e-9 Λ: the x-average moves each line weight by
      // ≲ 1e-9·2π·|q1 − q2| ≲ 1e-7·J_q1·J_q2, far inside 1e-8 in total) and every line.
      EXPECT_NEAR(g.cellMass(x, x + 1e-9 * period, -61 / (2.0 * period), 61 / (2.0 * period)), 1.0, 1e-8);
    }
  }
}

