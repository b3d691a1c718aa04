// The tabulated WBSDF (table.h): marginals of built tables against closed forms (|t|² per row, a²sinc² per
// column), and the importance sampler: chi-square tests of WbsdfTable::sample against WbsdfTable::pdf, and
// sample means against the row's signed mass with standard errors estimated from the same samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
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
#include "diffray/wbsdf/rough_surface.h"
#include "diffray/wbsdf/table.h"
#include "diffray/wbsdf/wigner_fft.h"

namespace dw = diffray::wbsdf;
namespace dt = diffray::testing;
using Cx = std::complex<double>;
using namespace diffray::testing;  // fixtures

// ---- Table marginals ---------------------------------------------------------------------------------------
// u-marginal per row: ∫_{−H}^{H} W du = (2/π)Si(2πHw) for a rect term of lag length w = a − 2|x| (and
// (2/π)[Si(2πH(w+d)) + Si(2πH(w−d))] for a double slit's cross term), so Σ_k mass(j,k) must equal the
// x-average of that over row j, and x-average |t|² minus it is the row's truncated share. Tolerance 1e-6 of
// |t|² (energy conservation per row, far below Monte Carlo noise).

namespace {

/// (1/(x2 − x1)) ∫_{x1}^{x2} ∫_{−h}^{h} W_slit(x,u) du dx for a slit of width a centred on 0 (the x-range
/// inside the slit), split at the kink x = 0; the integrand oscillates ≤ 2h per metre in x (≤ 1/4 cycle per
/// panel below).
double slitRowMassInRange(double x1, double x2, double a, double h) {
  const auto inRange = [&](double x) { return (2.0 / kPi) * sineIntegral(2.0 * kPi * h * (a - 2.0 * std::abs(x))); };
  double sum = 0.0;
  for (const auto& [p, q] : {std::pair{x1, std::min(x2, 0.0)}, std::pair{std::max(x1, 0.0), x2}})
    if (q > p) sum += quad(inRange, p, q, 1 + static_cast<int>(std::ceil(8.0 * h * (q - p))));
  return sum / (x2 - x1);
}

}  // namespace

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

  double tail_sum = 0.0;
  for (int j = 0; j < L.nx; ++j) {
    const double x1 = L.x0_m + j * L.dx_m, x2 = x1 + L.dx_m;
    double row = 0.0;
    for (int k = 0; k < L.nu; ++k) row += table->mass(j, k);
    const double expect = slitRowMassInRange(x1, x2, a, h);
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

// Half-plane (x ≥ 0 open, table over [0, extent], open beyond): ∫_{−H}^{H} sin(4πux)/(πu) du = (2/π)Si(4πHx),
// so each row's Σ_k mass is the x-average of that (1e-6), and the truncated mass is the average of the rest
// (|t|² = 1 on every row). Past the table the occluder is fully open (u' = 0, weight 1, table.h); before the
// edge it is opaque (weight 0).
TEST(WbsdfTableMarginals, HalfPlaneRowsAndOpenSide) {
  const double lambda = 1e-6, extent = 4 * lambda;
  const auto table = dw::WbsdfTable::build(*dw::Openings::halfPlane(extent), optionsFor(lambda));
  const dw::TableLayout& L = table->layout();
  const double h = 2.0 / lambda;
  ASSERT_TRUE(L.open_beyond);
  ASSERT_NEAR(L.x0_m, 0.0, 1e-18);
  ASSERT_NEAR(L.x0_m + L.nx * L.dx_m, extent, 1e-15);
  ASSERT_LE(L.dx_m, lambda / 8 * (1 + 1e-12));
  ASSERT_NEAR(L.u0_per_m, -h, 1e-9 * h);
  ASSERT_NEAR(L.u0_per_m + L.nu * L.du_per_m, h, 1e-9 * h);
  const auto inRange = [&](double x) { return (2.0 / kPi) * sineIntegral(4.0 * kPi * h * x); };
  double tail_sum = 0.0;
  for (int j = 0; j < L.nx; ++j) {
    const double x1 = L.x0_m + j * L.dx_m;
    double row = 0.0;
    for (int k = 0; k < L.nu; ++k) row += table->mass(j, k);
    const double expect =
        quad(inRange, x1, x1 + L.dx_m, 1 + static_cast<int>(std::ceil(8.0 * h * L.dx_m))) / L.dx_m;
    EXPECT_NEAR(row, expect, 1e-6) << "row " << j;
    tail_sum += 1.0 - expect;
  }
  EXPECT_NEAR(table->truncatedMass(), tail_sum / L.nx, 1e-6);
  for (double xi : {0.0, 0.3, 0.999}) {
    const dw::WbsdfTable::Sample open = table->sample(1.5 * extent, xi);
    EXPECT_EQ(open.u_shift, 0.0);
    EXPECT_EQ(open.weight, 1.0);
    EXPECT_EQ(table->sample(-0.5 * lambda, xi).weight, 0.0);
  }
}

// A periodic table (the grating) is indexed by x modulo the period: the same uniform gives the same draw.
TEST(WbsdfTableSampling, PeriodicTableWrapsX) {
  const double lambda = 0.5e-6, period = 1.6e-6;
  const auto table = dw::WbsdfTable::build(dw::PhaseGrating(period, 3.0), optionsFor(lambda));
  ASSERT_TRUE(table->layout().periodic);
  for (int i = 0; i < 1000; ++i) {
    const double xi = (i + 0.5) / 1000.0;
    const dw::WbsdfTable::Sample base = table->sample(0.3 * period, xi);
    for (double shift : {-3.0, 5.0}) {
      const dw::WbsdfTable::Sample s = table->sample((0.3 + shift) * period, xi);
      EXPECT_EQ(s.u_shift, base.u_shift) << xi << " " << shift;
      EXPECT_EQ(s.weight, base.weight) << xi << " " << shift;
    }
  }
}

// TableOptions::coarsen_to_fit (table.h): "When the table would exceed max_cells: widen du to fit (true)".
// With a limit of nx·101 cells the table must fit (≤ the limit), stay symmetric (nu even, u' ∈ [−2/λ, 2/λ])
// and keep every row's mass (the closed-form u-marginal above, 1e-6).
// (This caught a bug: an odd max_cells/nx was rounded *up* to even, so the table overshot the limit.)
// Shifts beyond 2/λ are evanescent for any incidence: a larger requested range is clamped, so an absurd
// --u-range (1e10 /m) builds the default table instead of running for ever.
TEST(WbsdfTableBuild, HugeURangeIsClampedToTwoOverLambda) {
  const auto slit = dw::Openings::slit(2e-6);
  dw::TableOptions o;
  o.wavelength_m = 500e-9;
  o.max_cells = 4'000'000;
  o.coarsen_to_fit = true;
  const auto reference = dw::WbsdfTable::build(*slit, o);
  o.u_half_range_per_m = 1e10;
  const auto clamped = dw::WbsdfTable::build(*slit, o);
  EXPECT_DOUBLE_EQ(clamped->layout().u0_per_m, -2.0 / o.wavelength_m);
  EXPECT_EQ(clamped->layout().nu, reference->layout().nu);
  EXPECT_EQ(clamped->layout().nx, reference->layout().nx);
}

TEST(WbsdfTableBuild, CoarsenToFitStaysWithinTheCellLimit) {
  const double lambda = 1e-6, a = 10 * lambda;
  const auto slit = dw::Openings::slit(a);
  const int nx = dw::WbsdfTable::build(*slit, optionsFor(lambda))->layout().nx;
  for (int per_row : {100, 101}) {
    dw::TableOptions o = optionsFor(lambda);
    o.max_cells = static_cast<std::size_t>(nx) * static_cast<std::size_t>(per_row);
    o.coarsen_to_fit = true;
    std::shared_ptr<const dw::WbsdfTable> table;
    EXPECT_NO_THROW(table = dw::WbsdfTable::build(*slit, o)) << "limit " << o.max_cells;
    if (!table) continue;
    const dw::TableLayout& L = table->layout();
    EXPECT_LE(static_cast<std::size_t>(L.nx) * static_cast<std::size_t>(L.nu), o.max_cells);
    EXPECT_EQ(L.nu % 2, 0);
    const double h = 2.0 / lambda;
    EXPECT_NEAR(L.u0_per_m, -h, 1e-9 * h);
    EXPECT_NEAR(L.u0_per_m + L.nu * L.du_per_m, h, 1e-9 * h);
    for (int j = 0; j < L.nx; j += 7) {
      double row = 0.0;
      for (int k = 0; k < L.nu; ++k) row += table->mass(j, k);
      const double x1 = L.x0_m + j * L.dx_m;
      EXPECT_NEAR(row, slitRowMassInRange(x1, x1 + L.dx_m, a, h), 1e-6) << "row " << j;
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
  // Plus the round-off of summing n weights (≤ n·ε relative): a row of one sign has zero variance.
  const double roundoff = n * 0x1.0p-52 * table.rowAbsMass(row);
  EXPECT_NEAR(mean, row_signed, 5.0 * se + roundoff) << "x=" << x << " row " << row;
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

TEST(StatWbsdfSampler, HalfPlaneMatchesPdfAndRowMass) {
  const double lambda = 1e-6;
  const auto table = dw::WbsdfTable::build(*dw::Openings::halfPlane(4 * lambda), optionsFor(lambda));
  std::uint64_t seed = 404;
  for (double x : {0.05 * lambda, 0.7 * lambda, 3.3 * lambda}) checkSampler(*table, x, 200000, seed++);
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


// The rough surface's table (rough_surface.h): its second moment in u against the closed form from the
// correlation function, ∫u²W du = −γ''(0)/(4π²) = g/(2π²ℓ²) for γ(x') = exp(−g(1 − e^{−x'²/ℓ²})) (Cuypers
// et al. 2012, eq:WDF_gamma); total mass 1. Tolerance: the cell-centre quadrature error du²/12 per unit mass
// plus 1e-3 relative for the lobe beyond the tabulated range (Gaussian tails, far below that here).
TEST(WbsdfTableRough, SecondMomentMatchesCorrelationCurvature) {
  const double lambda = 0.5e-6, sigma_h = 0.2e-6, ell = 4e-6;
  const auto wdf = dw::roughSurfaceWdf(sigma_h, ell, lambda, 1.0, 4096, 2.0 / lambda);
  const auto table = dw::roughSurfaceTable(wdf);
  const double g = std::pow(2.0 * M_PI * (sigma_h / lambda) * 2.0, 2);
  const auto& L = table->layout();
  double mass = 0.0, second = 0.0;
  for (int k = 0; k < L.nu; ++k) {
    const double u = L.u0_per_m + (k + 0.5) * L.du_per_m;
    mass += table->mass(0, k);
    second += table->mass(0, k) * u * u;
  }
  const double expected = g / (2.0 * M_PI * M_PI * ell * ell);
  EXPECT_NEAR(mass, 1.0, 1e-6);
  EXPECT_NEAR(second, expected, 1e-3 * expected + L.du_per_m * L.du_per_m / 12.0);
  // Stationary: the same row at any x.
  EXPECT_EQ(table->sample(-3.7, 0.3).u_shift, table->sample(12.1, 0.3).u_shift);
}

// The third member of the sampling triad: eval(x, u') is the tabulated W, mass/du for continuous tables
// and the line's mass for line spectra; pdf = |eval|/rowAbsMass (per unit u for continuous tables). The
// oracle is the closed form integrated by the tests' own quadrature (slit) and the Bessel products (grating).
TEST(WbsdfTableSampling, EvalIsTheTabulatedDistribution) {
  const double a = 1e-4, lambda = 5e-7;
  const auto slit = dw::Openings::slit(a);
  const auto table = dw::WbsdfTable::build(*slit, optionsFor(lambda));
  const auto& L = table->layout();
  const int j = L.nx / 3;
  const double x1 = L.x0_m + j * L.dx_m;
  for (int k : {L.nu / 2 - 7, L.nu / 2, L.nu / 2 + 40}) {
    const double u1 = L.u0_per_m + k * L.du_per_m;
    const double mass =
        quad([&](double x) { return quad([&](double u) { return rectWdf(x, u, a); }, u1, u1 + L.du_per_m, 2); },
             x1, x1 + L.dx_m, 4) /
        L.dx_m;
    const double x_mid = x1 + 0.5 * L.dx_m, u_mid = u1 + 0.5 * L.du_per_m;
    EXPECT_NEAR(table->eval(x_mid, u_mid) * L.du_per_m, mass, 1e-6 * 2.0 * a * L.du_per_m);
    EXPECT_NEAR(table->pdf(x_mid, u_mid), std::abs(table->eval(x_mid, u_mid)) / table->rowAbsMass(j), 1e-12);
  }
  // Grating: eval at a line is its weight; x-averaged over a period, line 2q carries J_q(m/2)².
  const double period = 1.6e-6, m = 2.0;
  dw::PhaseGrating grating(period, m);
  const auto gt = dw::WbsdfTable::build(grating, optionsFor(lambda));
  double order1 = 0.0;
  for (int r = 0; r < gt->layout().nx; ++r)
    order1 += gt->eval(gt->layout().x0_m + (r + 0.5) * gt->layout().dx_m, 1.0 / period) / gt->layout().nx;
  EXPECT_NEAR(order1, std::pow(std::cyl_bessel_j(1, 0.5 * m), 2), 1e-9);
}

// TableOptions::on_row (a progress bar's feed): called once per row, from worker threads, with the row
// count, and without changing a single mass.
TEST(WbsdfTableBuild, ReportsEachRowAndBuildsTheSameTable) {
  const auto slits = diffray::wbsdf::Openings::slits(3, 100e-6, 250e-6);
  diffray::wbsdf::TableOptions o;
  o.wavelength_m = 500e-9;
  o.u_half_range_per_m = 0.02 / o.wavelength_m;
  const auto plain = diffray::wbsdf::WbsdfTable::build(*slits, o);
  std::atomic<std::uint64_t> calls{0}, wrong_total{0};
  const auto nx = static_cast<std::uint64_t>(plain->layout().nx);
  o.on_row = [&](std::uint64_t rows) {
    ++calls;
    if (rows != nx) ++wrong_total;
  };
  const auto watched = diffray::wbsdf::WbsdfTable::build(*slits, o);
  EXPECT_EQ(calls.load(), nx);
  EXPECT_EQ(wrong_total.load(), 0u);
  ASSERT_EQ(watched->layout().nu, plain->layout().nu);
  for (int j = 0; j < plain->layout().nx; ++j)
    for (int k = 0; k < plain->layout().nu; ++k) ASSERT_EQ(watched->mass(j, k), plain->mass(j, k)) << j << " " << k;
}
