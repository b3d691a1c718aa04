// Wavelength importance sampling: the density against an independent quadrature and the CMF sum it is
// defined by, sample/pdf consistency, and (Stat*) a chi-square test of the samples against the density and
// an unbiased Monte Carlo estimate of the equal-energy XYZ.
#include <gtest/gtest.h>

#include <cmath>

#include "chi2.h"
#include "diffray/color/cie1931.h"
#include "diffray/color/wavelength.h"
#include "diffray/core/error.h"
#include "diffray/core/rng.h"

namespace diffray::color {
namespace {

// ∫ pdf over [a, b] by composite Simpson on a grid finer than the 1 nm knots.
double integratePdf(const WavelengthSampler& s, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = s.pdf(a) + s.pdf(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * s.pdf(a + i * h);
  return sum * h / 3.0;
}

double cmfSum(double l) {
  const Xyz c = cie1931(l);
  return c.x + c.y + c.z;
}

TEST(ColorWavelength, DensityIsNormalisedAndFollowsTheCmfSum) {
  const WavelengthSampler s(380.0, 780.0);
  EXPECT_NEAR(integratePdf(s, 380.0, 780.0, 40000), 1.0, 1e-6);
  // Above the floor the density is proportional to x̄ + ȳ + z̄.
  EXPECT_NEAR(s.pdf(450.0) / s.pdf(550.0), cmfSum(450.0) / cmfSum(550.0), 1e-9);
  EXPECT_NEAR(s.pdf(600.5) / s.pdf(520.0), cmfSum(600.5) / cmfSum(520.0), 1e-9);
  // Below it the density is flat at the floor: the ends of the range stay reachable.
  EXPECT_NEAR(s.pdf(770.0), s.pdf(779.0), 1e-12);
  EXPECT_GT(s.pdf(780.0), 0.0);
  EXPECT_GT(s.pdf(380.0), 0.0);
  EXPECT_EQ(s.pdf(379.9), 0.0);
  EXPECT_EQ(s.pdf(780.1), 0.0);
}

TEST(ColorWavelength, SampleReturnsItsOwnPdfAndIsMonotone) {
  const WavelengthSampler s(400.5, 700.25);  // ends off the integer knots
  EXPECT_NEAR(integratePdf(s, 400.5, 700.25, 30000), 1.0, 1e-6);
  double prev = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double u = i / 1000.0;
    const WavelengthSample w = s.sample(u);
    EXPECT_GE(w.wavelength_nm, 400.5);
    EXPECT_LE(w.wavelength_nm, 700.25);
    EXPECT_GE(w.wavelength_nm, prev);
    prev = w.wavelength_nm;
    EXPECT_NEAR(w.pdf_per_nm, s.pdf(w.wavelength_nm), 1e-12);
  }
  EXPECT_NEAR(s.sample(0.0).wavelength_nm, 400.5, 1e-9);
  EXPECT_NEAR(s.sample(1.0).wavelength_nm, 700.25, 1e-6);
  // The CDF is inverted exactly: ∫_lo^λ(u) pdf = u.
  for (double u : {0.1, 0.37, 0.5, 0.81, 0.99}) {
    const double l = s.sample(u).wavelength_nm;
    EXPECT_NEAR(integratePdf(s, 400.5, l, 20000), u, 1e-6) << u;
  }
}

TEST(ColorWavelength, FreeFunctionsMatchTheSampler) {
  const WavelengthSampler s(380.0, 780.0);
  for (double u : {0.0, 0.25, 0.5, 0.75, 0.999}) {
    EXPECT_EQ(sampleWavelength(u).wavelength_nm, s.sample(u).wavelength_nm);
    EXPECT_EQ(sampleWavelength(u).pdf_per_nm, s.sample(u).pdf_per_nm);
  }
  const WavelengthSampler t(450.0, 650.0);
  EXPECT_EQ(sampleWavelength(0.3, 450.0, 650.0).wavelength_nm, t.sample(0.3).wavelength_nm);
  EXPECT_EQ(wavelengthPdf(500.0, 450.0, 650.0), t.pdf(500.0));
  EXPECT_EQ(wavelengthPdf(500.0), s.pdf(500.0));
}

TEST(ColorWavelength, BadRangeIsAnInputError) {
  EXPECT_THROW(WavelengthSampler(350.0, 700.0), core::InputError);
  EXPECT_THROW(WavelengthSampler(400.0, 900.0), core::InputError);
  EXPECT_THROW(WavelengthSampler(600.0, 500.0), core::InputError);
  EXPECT_THROW(WavelengthSampler(500.0, 500.0), core::InputError);
  EXPECT_THROW(sampleWavelength(0.5, std::nan(""), 700.0), core::InputError);
}

TEST(StatColorWavelength, SamplesFollowTheDensity) {
  const WavelengthSampler s(380.0, 780.0);
  const int bins = 200, n = 200000;  // 2 nm bins
  std::vector<double> observed(bins, 0.0), probability(bins, 0.0);
  for (int b = 0; b < bins; ++b)
    probability[b] = integratePdf(s, 380.0 + 2.0 * b, 380.0 + 2.0 * (b + 1), 64);
  core::Rng rng(6, 0);
  for (int i = 0; i < n; ++i) {
    const double l = s.sample(rng.uniform()).wavelength_nm;
    observed[std::min(bins - 1, static_cast<int>((l - 380.0) / 2.0))] += 1.0;
  }
  const auto r = testing::chiSquareTest(observed, probability);
  EXPECT_NEAR(r.probability_sum, 1.0, 1e-6);
  EXPECT_GT(r.p_value, testing::kChi2Alpha) << "X2 = " << r.statistic << ", dof = " << r.dof;
}

TEST(StatColorWavelength, EqualEnergyXyzEstimateIsUnbiased) {
  // E[cmf(λ)/p(λ)] = ∫ cmf over the range. Reference: Simpson quadrature of the table, 0.05 nm steps,
  // which also gives ∫ cmf², hence the per-sample variance of uniform sampling, (b − a)∫cmf² − (∫cmf)².
  double ref[3] = {0, 0, 0}, ref2[3] = {0, 0, 0};
  const int m = 8000;
  const double h = 400.0 / m;
  for (int i = 0; i <= m; ++i) {
    const double w = ((i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0)) * h / 3.0;
    const Xyz c = cie1931(380.0 + i * h);
    const double v[3] = {c.x, c.y, c.z};
    for (int k = 0; k < 3; ++k) ref[k] += w * v[k], ref2[k] += w * v[k] * v[k];
  }
  const int n = 100000;
  core::Rng rng(6, 1);
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const WavelengthSample w = sampleWavelength(rng.uniform());
    const Xyz c = cie1931(w.wavelength_nm);
    const double v[3] = {c.x / w.pdf_per_nm, c.y / w.pdf_per_nm, c.z / w.pdf_per_nm};
    for (int k = 0; k < 3; ++k) sum[k] += v[k], sum2[k] += v[k] * v[k];
  }
  for (int k = 0; k < 3; ++k) {
    const double mean = sum[k] / n;
    const double variance = sum2[k] / n - mean * mean;  // per sample
    EXPECT_NEAR(mean, ref[k], 4.0 * std::sqrt(variance / n)) << k;  // 4σ: false alarm 6e-5 per component
    const double uniform_variance = 400.0 * ref2[k] - ref[k] * ref[k];
    EXPECT_LT(variance, uniform_variance) << k;
    std::printf("component %d: relative sd per sample %.3f (importance) vs %.3f (uniform)\n", k,
                std::sqrt(variance) / ref[k], std::sqrt(uniform_variance) / ref[k]);
  }
}

}  // namespace
}  // namespace diffray::color
