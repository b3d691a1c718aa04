#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/core/rng.h"

namespace dc = diffray::core;

// Gauss–Legendre with n nodes integrates x^k exactly for k <= 2n-1: oracle ∫_{-1}^{1} x^k = 2/(k+1), k even.
TEST(GaussLegendre, IntegratesPolynomialsExactly) {
  for (int n : {1, 2, 5, 16, 64}) {
    const auto& gl = dc::gaussLegendre(n);
    for (int k = 0; k <= 2 * n - 1; k += 1) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += gl.weights[i] * std::pow(gl.nodes[i], k);
      const double exact = (k % 2 == 0) ? 2.0 / (k + 1) : 0.0;
      EXPECT_NEAR(sum, exact, 1e-12) << "n=" << n << " k=" << k;
    }
  }
}

// The rules are cached once per n and then read without a lock: threads asking for the same new n at once
// all get the one rule.
TEST(GaussLegendre, ConcurrentFirstRequestsShareOneRule) {
  std::vector<const dc::GaussLegendre*> seen(8, nullptr);
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) threads.emplace_back([&seen, t] { seen[t] = &dc::gaussLegendre(97); });
  for (auto& t : threads) t.join();
  for (const auto* rule : seen) EXPECT_EQ(rule, &dc::gaussLegendre(97));
  EXPECT_EQ(dc::gaussLegendre(97).nodes.size(), 97u);
}

TEST(GaussLegendre, CompositeRuleIntegratesSine) {
  EXPECT_NEAR(dc::integrate([](double x) { return std::sin(x); }, 0.0, dc::kPi, 4), 2.0, 1e-13);
}

TEST(FastRng, MatchesTheReferenceXoshiro256StarStarSequence) {
  // The first outputs of the authors' xoshiro256** from the state {1, 2, 3, 4} (computed here by hand for
  // the first two: rotl(2·5, 7)·9 = 11520, and s[1] = 0 after one step).
  diffray::core::FastRng r(1, 2, 3, 4);
  EXPECT_EQ(r.next(), 11520u);
  EXPECT_EQ(r.next(), 0u);
  EXPECT_EQ(r.next(), 1509978240u);
  EXPECT_EQ(r.next(), 1215971899390074240u);
}

TEST(StatFastRng, UniformsHaveTheMomentsOfU01) {
  diffray::core::Rng seeder(5, 0);
  diffray::core::FastRng r(seeder);
  const int n = 1'000'000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  // Mean 1/2 (σ = √(1/12/n)), second moment 1/3 (σ = √(4/45/n)): 5σ.
  EXPECT_NEAR(sum / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(sum2 / n, 1.0 / 3, 5 * std::sqrt(4.0 / 45 / n));
}
