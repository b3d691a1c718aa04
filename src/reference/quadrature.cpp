#include "diffray/reference/quadrature.h"

#include <cmath>

namespace diffray::reference {

namespace {
// Gauss–Legendre nodes and weights on [−1, 1] by Newton iteration on P_n from Tricomi's initial guesses;
// weights 2/((1 − x²) P_n'(x)²).
GaussRule makeGaussRule() {
  constexpr double kPi = 3.14159265358979323846;
  GaussRule rule;
  const int n = GaussRule::kNodes;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p_prev = 1.0;
      double p = x;
      for (int j = 2; j <= n; ++j) {
        const double p_next = ((2.0 * j - 1.0) * x * p - (j - 1.0) * p_prev) / j;
        p_prev = p;
        p = p_next;
      }
      derivative = n * (x * p - p_prev) / (x * x - 1.0);
      const double dx = p / derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    rule.nodes[static_cast<std::size_t>(i)] = x;
    rule.weights[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}
}  // namespace

const GaussRule& gaussRule16() {
  static const GaussRule rule = makeGaussRule();  // thread-safe initialisation (C++11 magic statics)
  return rule;
}

}  // namespace diffray::reference
