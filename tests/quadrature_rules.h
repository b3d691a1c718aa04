#pragma once
// Composite quadrature rules for tests' own oracles (header-only; nothing here uses diffray's code).
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

}  // namespace diffray::testing
