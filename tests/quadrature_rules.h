#pragma once
// Composite quadrature rules for tests' own oracles (header-only; nothing here uses diffray's code).
#include <cmath>
#include <vector>

namespace diffray::testing {

/// ∫_a^b f by composite Simpson with n (even) panels.
template <class F>
double simpson(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

/// ∫_a^b f by the composite midpoint rule with n panels (no end points: for integrands with a jump or a kink
/// at the ends).
template <class F>
double midpoint(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += f(a + (i + 0.5) * h);
  return s * h;
}

struct Rule {
  std::vector<double> nodes, weights;
};

/// n-point Gauss–Legendre on [−1, 1] by Newton's method on P_n (Numerical Recipes' gauleg).
inline Rule gaussRule(int n) {
  Rule r;
  r.nodes.resize(n);
  r.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(3.14159265358979323846 * (i + 0.75) / (n + 0.5));
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

}  // namespace diffray::testing
