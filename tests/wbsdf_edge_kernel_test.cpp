// The analytic edge-kernel sampler (wbsdf/edge_kernel.h): a chi-square test against its own pdf, its
// mean weight against ∫sinc by the test's own quadrature, and the Fraunhofer slit pattern (the second marginal:
// ∫W dx = |T(u)|² = a²·sinc²(au)) recovered from rays spread over a slit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <algorithm>
#include <vector>

#include "chi2.h"
#include "quadrature_rules.h"
#include "diffray/wbsdf/edge_kernel.h"

namespace dw = diffray::wbsdf;
namespace dt = diffray::testing;
using dt::midpoint;
using dt::simpson;

namespace {

constexpr double kPi = 3.14159265358979323846;

double sincRef(double w) { return w == 0.0 ? 1.0 : std::sin(kPi * w) / (kPi * w); }

}  // namespace

TEST(StatEdgeKernel, SamplesFollowTheirPdfAndMeanIsTheIntegralOfSinc) {
  // Symmetric ranges, and the tracer's propagating ranges for oblique rays (one side short).
  const std::vector<std::pair<double, double>> ranges = {{-0.7, 0.7},   {-7.3, 7.3},    {-250.0, 250.0},
                                                         {-0.4, 37.2}, {-12.5, 3.3}, {-800.0, 0.6}};
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (const auto& range : ranges) {  // no structured binding: C++17 lambdas cannot capture one
    const double lo = range.first, hi = range.second;
    const double a = -std::ceil(-lo), b = std::ceil(hi);  // the support: whole periods
    const int per = 4;
    const int nbins = static_cast<int>((b - a) * per);
    std::vector<double> prob(nbins), observed(nbins, 0.0);
    // The pdf jumps at the main segment's ends (±1 clipped to [lo, hi]): integrate piecewise between them.
    const double cuts[2] = {std::max(-1.0, lo), std::min(1.0, hi)};
    for (int k = 0; k < nbins; ++k) {
      const double x0 = a + static_cast<double>(k) / per, x1 = x0 + 1.0 / per;
      std::vector<double> pts = {x0};
      for (double c : cuts)
        if (c > x0 && c < x1) pts.push_back(c);
      pts.push_back(x1);
      for (std::size_t j = 0; j + 1 < pts.size(); ++j)
        prob[k] += midpoint([&](double w) { return dw::edgeKernelPdf(w, lo, hi); }, pts[j], pts[j + 1], 256);
    }
    const int n = 300000;
    double sum = 0.0, sum_sq = 0.0;
    for (int i = 0; i < n; ++i) {
      const dw::EdgeKernelSample s = dw::edgeKernelSample(lo, hi, uni(rng), uni(rng));
      const int k = static_cast<int>(std::floor((s.w - a) * per));
      ASSERT_GE(k, 0);
      ASSERT_LT(k, nbins);
      observed[k] += 1.0;
      sum += s.weight;
      sum_sq += s.weight * s.weight;
    }
    const dt::Chi2Result r = dt::chiSquareTest(observed, prob);
    EXPECT_NEAR(r.probability_sum, 1.0, 1e-5) << lo << " " << hi;
    EXPECT_GT(r.p_value, dt::kChi2Alpha) << lo << " " << hi << " X2 " << r.statistic << " dof " << r.dof;
    // The main segment is clipped to [lo, hi]; the tails run to whole periods.
    const double m_lo = std::max(-1.0, lo), m_hi = std::min(1.0, hi);
    double expected = simpson(sincRef, m_lo, m_hi, 200);
    if (b > 1) expected += simpson(sincRef, 1.0, b, 200 * static_cast<int>(b));
    if (a < -1) expected += simpson(sincRef, a, -1.0, 200 * static_cast<int>(-a));
    const double mean = sum / n, sigma = std::sqrt((sum_sq / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4.5 * sigma) << lo << " " << hi;
    // The weight is bounded (nearly constant in magnitude): its spread stays of the order of ln M.
    EXPECT_LT(std::sqrt(sum_sq / n), 2.0 + 0.6 * std::log(std::max(b, -a))) << lo << " " << hi;
  }
}

TEST(StatEdgeKernel, SlitFarFieldIsFraunhofer) {
  // Rays uniform over a slit of width a, each drawing w at its own edge distance d (u' = w/(4d)): the mean
  // weight per u-bin is (1/a)·∫_bin |T(u)|² du with |T|² = a² sinc²(au).
  const double a = 0.9, lambda = 0.34, u_max = 2.0 / lambda;
  const int nb = 24;
  const double u_lo = -3.0 / a, du = 6.0 / a / nb;
  std::vector<double> sum(nb, 0.0), sum_sq(nb, 0.0);
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    const double x = (uni(rng) - 0.5) * a, d = 0.5 * a - std::abs(x);
    const dw::EdgeKernelSample s = dw::edgeKernelSample(-4.0 * d * u_max, 4.0 * d * u_max, uni(rng), uni(rng));
    const double u = s.w / (4.0 * d);
    const int k = static_cast<int>(std::floor((u - u_lo) / du));
    if (k < 0 || k >= nb) continue;
    sum[k] += s.weight;
    sum_sq[k] += s.weight * s.weight;
  }
  for (int k = 0; k < nb; ++k) {
    const double lo = u_lo + k * du;
    const double expected = simpson([&](double u) { return a * sincRef(a * u) * sincRef(a * u); }, lo, lo + du, 200);
    const double mean = sum[k] / n;
    const double sigma = std::sqrt((sum_sq[k] / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4.5 * sigma) << "bin " << k;
  }
}
