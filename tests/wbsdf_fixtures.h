#pragma once
// Shared oracles of the WBSDF tests (wbsdf_closed_form_test.cpp, wbsdf_table_test.cpp): the WDF
// closed forms (from Cuypers et al. 2012, eq. 2) written out independently, Gauss–Legendre quadrature with nodes
// computed here, and the sine integral. They share no code with diffray.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "diffray/wbsdf/table.h"
#include "quadrature_rules.h"
#include "temp_dir.h"

namespace diffray::testing {

namespace dw = diffray::wbsdf;

constexpr double kPi = 3.14159265358979323846;

inline double sincOracle(double z) { return z == 0.0 ? 1.0 : std::sin(kPi * z) / (kPi * z); }

/// Rect of width a centred on 0, W = 2(a − 2|x|)·sinc(2u(a − 2|x|)) for |x| < a/2.
inline double rectWdf(double x, double u, double a) {
  const double l = a - 2.0 * std::abs(x);
  return l > 0.0 ? 2.0 * l * sincOracle(2.0 * u * l) : 0.0;
}

/// Double slit of width a, centres ±d/2: W_r(x−d/2) + W_r(x+d/2) + 2cos(2πud)·W_r(x).
inline double doubleSlitWdf(double x, double u, double a, double d) {
  return rectWdf(x - 0.5 * d, u, a) + rectWdf(x + 0.5 * d, u, a) + 2.0 * std::cos(2.0 * kPi * u * d) * rectWdf(x, u, a);
}

/// The step (half-plane x ≥ 0 open) has W = sin(4πux)/(πu) for x > 0 (4x at u = 0).
inline double halfPlaneWdf(double x, double u) {
  if (x <= 0.0) return 0.0;
  return u == 0.0 ? 4.0 * x : std::sin(4.0 * kPi * u * x) / (kPi * u);
}

// ---- Quadrature written for these tests ----------------------------------------------------------------

inline const Rule& rule10() {
  static const Rule r = gaussRule(10);
  return r;
}

/// Composite 10-point Gauss–Legendre of f over [a, b] with `panels` equal panels.
template <class F>
inline double quad(F&& f, double a, double b, int panels) {
  const Rule& r = rule10();
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = a + (p + 0.5) * h;
    for (std::size_t i = 0; i < r.nodes.size(); ++i) sum += r.weights[i] * f(mid + 0.5 * h * r.nodes[i]);
  }
  return 0.5 * h * sum;
}

/// Sine integral Si(z) = ∫_0^z sin(t)/t dt: cumulative 10-point Gauss over panels of width π/2 (each panel
/// is a quarter period: the rule's error there is far below 1e-16), cached at multiples of π/2.
inline double sineIntegral(double z) {
  if (z < 0.0) return -sineIntegral(-z);
  static std::vector<double> knots{0.0};  // Si(k·π/2)
  const double step = 0.5 * kPi;
  const auto integrand = [](double t) { return t == 0.0 ? 1.0 : std::sin(t) / t; };
  const std::size_t k = static_cast<std::size_t>(z / step);
  while (knots.size() <= k) {
    const double t0 = static_cast<double>(knots.size() - 1) * step;
    knots.push_back(knots.back() + quad(integrand, t0, t0 + step, 1));
  }
  const double t0 = static_cast<double>(k) * step;
  return knots[k] + (z > t0 ? quad(integrand, t0, z, 1) : 0.0);
}

/// ∫_{x1}^{x2} ∫_{u1}^{u2} w(x,u) du dx by 2D composite Gauss, x split at the closed form's kinks; panels
/// chosen so that each spans ≤ 1/4 of an oscillation (x-frequency ≤ 2|u|max, u-frequency ≤ max_lag), where
/// the 10-point rule is exact to rounding.
template <class W>
inline double bruteCellIntegral(W&& w, const std::vector<double>& kinks, double x1, double x2, double u1, double u2,
                         double max_lag) {
  std::vector<double> cuts{x1};
  for (double k : kinks)
    if (k > x1 && k < x2) cuts.push_back(k);
  cuts.push_back(x2);
  std::sort(cuts.begin(), cuts.end());
  const double umax = std::max(std::abs(u1), std::abs(u2));
  const int panels_u = 1 + static_cast<int>(std::ceil(4.0 * (u2 - u1) * max_lag));
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const int panels_x = 1 + static_cast<int>(std::ceil(4.0 * (cuts[i + 1] - cuts[i]) * 2.0 * umax));
    total += quad([&](double x) { return quad([&](double u) { return w(x, u); }, u1, u2, panels_u); }, cuts[i],
                  cuts[i + 1], panels_x);
  }
  return total;
}

/// Uniform in [0, 1) from a 64-bit engine (53 random bits).
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

inline dw::TableOptions optionsFor(double wavelength) {
  dw::TableOptions o;
  o.wavelength_m = wavelength;
  return o;
}

/// Writes `content` to <tag>_<name>.csv in this test process's own temporary folder (removed with all it
/// holds when the process exits) and returns its path (profile CSVs for wbsdf::readProfileCsv).
inline std::string writeTempCsv(const std::string& tag, const std::string& name, const std::string& content) {
  static const diffray::test::TempDir dir("wbsdf_csv");
  const std::string path = dir.file(tag + "_" + name + ".csv");
  std::ofstream(path) << content;
  return path;
}

}  // namespace diffray::testing
