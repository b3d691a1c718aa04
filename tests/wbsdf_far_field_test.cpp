// The far-field sampler of an opening (wbsdf/far_field.h): a chi-square test against its own pdf, its mean
// weight per bin against ∫sinc² by the test's own quadrature, and the identity the portal continuation rests
// on: rays from the far-field law at every point of a slit give, per direction bin, the slit's Wigner
// distribution integrated over the slit (its closed form, integrated here in x and u).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "chi2.h"
#include "quadrature_rules.h"
#include "diffray/wbsdf/far_field.h"

namespace dw = diffray::wbsdf;
namespace dt = diffray::testing;
using dt::midpoint;

namespace {

constexpr double kPi = 3.14159265358979323846;

double sinc2Ref(double w) {
  if (w == 0.0) return 1.0;
  const double s = std::sin(kPi * w) / (kPi * w);
  return s * s;
}

// The rect aperture's Wigner distribution: W(x,u) = 2(a − 2|x|)·sinc(2u(a − 2|x|)), |x| < a/2.
double rectWigner(double a, double x, double u) {
  const double s = a - 2.0 * std::abs(x);
  if (!(s > 0.0)) return 0.0;
  const double z = 2.0 * u * s;
  return 2.0 * s * (z == 0.0 ? 1.0 : std::sin(kPi * z) / (kPi * z));
}

}  // namespace

TEST(StatFarField, SamplesFollowTheirPdfAndWeightsGiveSincSquaredPerBin) {
  // Symmetric ranges, and the tracer's propagating ranges for oblique rays (one side short or off zero).
  const std::vector<std::pair<double, double>> ranges = {{-0.2, 0.2}, {-3.3, 3.3},  {-60.0, 60.0},
                                                         {-0.1, 17.5}, {-9.0, 0.05}, {0.6, 4.0}};
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (const auto& range : ranges) {  // no structured binding: C++17 lambdas cannot capture one
    const double lo = range.first, hi = range.second;
    const int nbins = 48;
    const double width = (hi - lo) / nbins;
    std::vector<double> prob(nbins), observed(nbins, 0.0), wsum(nbins, 0.0), wsq(nbins, 0.0);
    for (int k = 0; k < nbins; ++k)
      prob[k] = midpoint([&](double w) { return dw::farFieldPdf(w, lo, hi); }, lo + k * width, lo + (k + 1) * width, 400);
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const dw::FarFieldSample s = dw::farFieldSample(lo, hi, uni(rng));
      ASSERT_GE(s.w, lo);
      ASSERT_LE(s.w, hi);
      ASSERT_GE(s.weight, 0.0);
      const int k = std::min(nbins - 1, static_cast<int>((s.w - lo) / width));
      observed[k] += 1.0;
      wsum[k] += s.weight;
      wsq[k] += s.weight * s.weight;
    }
    const dt::Chi2Result r = dt::chiSquareTest(observed, prob);
    EXPECT_NEAR(r.probability_sum, 1.0, 1e-4) << lo << " " << hi;
    EXPECT_GT(r.p_value, dt::kChi2Alpha) << lo << " " << hi << " X2 " << r.statistic << " dof " << r.dof;
    // The estimator's expectation per bin: E[weight · 1(bin)] = ∫_bin sinc². Its standard error from the
    // sample's own second moment; 4.8 σ over 48 bins and six ranges keeps a false alarm below 1e-3
    // (288 × 1.6e-6).
    for (int k = 0; k < nbins; ++k) {
      const double expected = midpoint(sinc2Ref, lo + k * width, lo + (k + 1) * width, 400);
      const double mean = wsum[k] / n, sigma = std::sqrt(std::max(0.0, wsq[k] / n - mean * mean) / n);
      EXPECT_NEAR(mean, expected, 4.8 * sigma + 1e-12) << lo << " " << hi << " bin " << k;
    }
  }
}

TEST(FarField, EmptyRangeGivesNoWeight) {
  EXPECT_EQ(dw::farFieldSample(0.3, 0.3, 0.5).weight, 0.0);
  EXPECT_EQ(dw::farFieldPdf(2.0, -1.0, 1.0), 0.0);
}

TEST(StatFarField, SlitPortalIsTheWignerDistributionIntegratedOverTheSlit) {
  // The portal draws u' = w/a from sinc²(w) whatever the point of the slit (its law does not depend on x);
  // the Wigner distribution gives ∫_slit W(x,u) dx / a per unit of u (the second marginal over the width a).
  // Per u-bin, the mean weight must equal (1/a)·∫_bin ∫_slit W dx du, integrated here from the closed-form W:
  // the far-field law is W averaged over the slit. The propagating range |u| < 1/λ cuts both alike.
  const double a = 0.9, lambda = 0.34, u_max = 1.0 / lambda;
  const int nb = 24;
  const double du = 2.0 * u_max / nb;
  std::vector<double> sum(nb, 0.0), sum_sq(nb, 0.0);
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const int n = 300000;
  for (int i = 0; i < n; ++i) {
    const dw::FarFieldSample s = dw::farFieldSample(-a * u_max, a * u_max, uni(rng));
    const double u = s.w / a;
    const int k = std::min(nb - 1, static_cast<int>((u + u_max) / du));
    sum[k] += s.weight;
    sum_sq[k] += s.weight * s.weight;
  }
  for (int k = 0; k < nb; ++k) {
    const double u0 = -u_max + k * du;
    const double expected =
        midpoint([&](double u) { return midpoint([&](double x) { return rectWigner(a, x, u); }, -0.5 * a, 0.5 * a, 400); },
                 u0, u0 + du, 200) / a;
    const double mean = sum[k] / n;
    const double sigma = std::sqrt(std::max(0.0, sum_sq[k] / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4.5 * sigma + 1e-6) << "bin " << k;
  }
}
