#include <gtest/gtest.h>

#include <cmath>

#include "diffray/core/math.h"

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

TEST(GaussLegendre, CompositeRuleIntegratesSine) {
  EXPECT_NEAR(dc::integrate([](double x) { return std::sin(x); }, 0.0, dc::kPi, 4), 2.0, 1e-13);
}
