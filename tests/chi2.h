#pragma once
// A small chi-square goodness-of-fit harness for tests of samplers against their own pdf (header-only).
// Pearson's statistic X² = Σ (O − E)²/E over bins whose expected counts E = N·p are at least 5 (smaller
// neighbours are merged, in order, so the χ² approximation holds), and its p-value
// P(χ²_dof ≥ X²) = Q(dof/2, X²/2), Q the regularised upper incomplete gamma function, computed here
// (Numerical Recipes §6.2: the series for P when x < a + 1, Lentz's continued fraction for Q otherwise).
// Nothing here uses diffray's own code. Callers use the significance level kChi2Alpha.
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace diffray::testing {

/// Significance level for chi-square tests in this project.
inline constexpr double kChi2Alpha = 1e-3;

namespace detail {

/// Regularised lower incomplete gamma P(a, x) by its series, for x < a + 1.
inline double gammaPSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 100000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-17) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

/// Regularised upper incomplete gamma Q(a, x) by its continued fraction (modified Lentz), for x ≥ a + 1.
inline double gammaQContinuedFraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace detail

/// Regularised upper incomplete gamma Q(a, x) = Γ(a, x)/Γ(a), a > 0, x ≥ 0.
inline double regularizedGammaQ(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return 1.0;
  if (std::isinf(x)) return 0.0;
  if (x < a + 1.0) return 1.0 - detail::gammaPSeries(a, x);
  return detail::gammaQContinuedFraction(a, x);
}

/// P(χ²_dof ≥ statistic).
inline double chiSquareSurvival(double statistic, int dof) {
  return regularizedGammaQ(0.5 * dof, 0.5 * statistic);
}

struct Chi2Result {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  int bins = 0;              ///< bins after merging
  double total = 0.0;        ///< N = Σ observed
  double probability_sum = 0.0;  ///< Σ expected probabilities (callers check it is 1)
};

/// Pearson's chi-square test of `observed` counts against `probability` per bin (bins must partition the
/// sample space, in an order where neighbours may be merged). Bins are merged left to right until each
/// group expects at least `min_expected` counts; a short remainder joins the last group. A group that
/// expects nothing but observed something gives X² = ∞ (p = 0). dof = groups − 1.
inline Chi2Result chiSquareTest(const std::vector<double>& observed, const std::vector<double>& probability,
                                double min_expected = 5.0) {
  Chi2Result r;
  if (observed.size() != probability.size() || observed.empty()) {
    r.p_value = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  bool impossible = false;  // a count where nothing can happen: no merging may hide it
  for (std::size_t i = 0; i < observed.size(); ++i) {
    r.total += observed[i];
    r.probability_sum += probability[i];
    if (probability[i] <= 0.0 && observed[i] > 0.0) impossible = true;
  }
  std::vector<double> group_obs, group_exp;
  double o = 0.0, e = 0.0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    o += observed[i];
    e += r.total * probability[i];
    if (e >= min_expected) {
      group_obs.push_back(o);
      group_exp.push_back(e);
      o = e = 0.0;
    }
  }
  if (o > 0.0 || e > 0.0) {
    if (group_obs.empty()) {
      group_obs.push_back(o);
      group_exp.push_back(e);
    } else {
      group_obs.back() += o;
      group_exp.back() += e;
    }
  }
  r.bins = static_cast<int>(group_obs.size());
  r.dof = r.bins - 1;
  for (std::size_t g = 0; g < group_obs.size(); ++g) {
    if (group_exp[g] <= 0.0) {
      if (group_obs[g] > 0.0) r.statistic = std::numeric_limits<double>::infinity();
      continue;
    }
    const double diff = group_obs[g] - group_exp[g];
    r.statistic += diff * diff / group_exp[g];
  }
  if (impossible) r.statistic = std::numeric_limits<double>::infinity();
  r.p_value = r.dof >= 1 ? chiSquareSurvival(r.statistic, r.dof) : (std::isinf(r.statistic) ? 0.0 : 1.0);
  return r;
}

}  // namespace diffray::testing
