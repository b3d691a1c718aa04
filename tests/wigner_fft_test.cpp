// Tests of the numeric Wigner distribution (wigner_fft), profile CSV input and the rough-surface WBSDF.
// Every oracle here is independent of the implementation: direct O(N²) sums instead of FFTW, closed forms
// (the rect's WDF from Cuypers et al. 2012, eq. 2), and the closed-form series of the Gaussian rough surface derived
// below.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/wbsdf/profile_csv.h"
#include "diffray/wbsdf/rough_surface.h"
#include "diffray/wbsdf/wigner_fft.h"

#include "wbsdf_fixtures.h"

namespace dw = diffray::wbsdf;
using Cx = std::complex<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;

double sincOracle(double z) { return z == 0.0 ? 1.0 : std::sin(kPi * z) / (kPi * z); }

/// Closed-form WDF of a rect of width a centred on 0: W = 2(a − 2|x|)·sinc(2u(a − 2|x|)), |x| < a/2.
double rectWdf(double x, double u, double a) {
  const double l = a - 2.0 * std::abs(x);
  return l > 0.0 ? 2.0 * l * sincOracle(2.0 * u * l) : 0.0;
}

/// T(u) = Σ_n t_n e^{−i2πu x_n} dx by direct summation (the Fraunhofer pattern of the samples).
Cx directSpectrum(const dw::SampledProfile& p, double u) {
  Cx sum = 0.0;
  for (size_t n = 0; n < p.t.size(); ++n) {
    const double x = p.x0_m + static_cast<double>(n) * p.dx_m;
    sum += p.t[n] * std::exp(Cx(0.0, -2.0 * kPi * u * x));
  }
  return sum * p.dx_m;
}

/// Random complex samples (amplitude 0..1, any phase), fixed seed.
dw::SampledProfile randomProfile(int n, double dx, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  dw::SampledProfile p{-0.3, dx, {}};
  for (int j = 0; j < n; ++j) p.t.push_back(std::polar(unit(rng), 2.0 * kPi * unit(rng)));
  return p;
}

/// (2πu·dx)/sin(2πu·dx): the ratio of the sampled rect's Dirichlet kernel 2dx·sin(2πuL)/sin(2πu·dx) to
/// the continuous sin(2πuL)/(πu) when the edges lie half-way between samples (L = (2M+1)·dx exactly).
double dirichletRatio(double u, double dx) {
  const double z = 2.0 * kPi * u * dx;
  return z == 0.0 ? 1.0 : z / std::sin(z);
}

}  // namespace

// Σ_k W(x_j,u_k)·du = |t_j|² exactly (only lag 0 survives the sum over a full period), with and without lag
// truncation; and the transform agrees with a direct sum of the definition, end lags ±nu/2 half-weighted.
TEST(WignerFFT, RowMarginalAndDirectSum) {
  const dw::SampledProfile p = randomProfile(40, 2e-6, 7);
  for (int nu : {128, 16}) {
    const dw::WignerGrid w = dw::wignerFFT(p, nu);
    ASSERT_EQ(w.nx, 40);
    ASSERT_EQ(w.nu, nu);
    EXPECT_NEAR(w.du_per_m, 1.0 / (2.0 * nu * p.dx_m), 1e-9);
    EXPECT_NEAR(w.u0_per_m, -0.5 * nu * w.du_per_m, 1e-6);
    for (int j = 0; j < w.nx; ++j) {
      double row = 0.0;
      for (int k = 0; k < nu; ++k) row += w.at(j, k) * w.du_per_m;
      EXPECT_NEAR(row, std::norm(p.t[j]), 1e-12) << "nu=" << nu << " j=" << j;
      for (int k = 0; k < nu; k += 5) {
        double direct = 0.0;
        for (int m = -nu / 2; m <= nu / 2; ++m) {
          if (j + m < 0 || j + m >= w.nx || j - m < 0 || j - m >= w.nx) continue;
          const double weight = (std::abs(m) == nu / 2) ? 0.5 : 1.0;
          direct += weight * 2.0 * p.dx_m *
                    (p.t[j + m] * std::conj(p.t[j - m]) *
                     std::exp(Cx(0.0, -4.0 * kPi * w.uAt(k) * m * p.dx_m))).real();
        }
        EXPECT_NEAR(w.at(j, k), direct, 1e-16) << "nu=" << nu << " j=" << j << " k=" << k;
      }
    }
  }
}

// Σ_j W(x_j,u)·dx is exactly |T(u)|² + |T(u + 1/(2dx))|² (only even index differences p − q = 2m appear),
// i.e. |T(u)|² plus its alias; for a signal oversampled ×2 the alias vanishes. Total mass = Σ|t|²·dx.
TEST(WignerFFT, ColumnAndTotalMarginals) {
  const double dx = 1e-3;
  const dw::SampledProfile noisy = randomProfile(30, dx, 11);
  // Gaussian envelope (s = 8 dx) with carrier 0.05/dx: spectrum ≈ e^{−2π²s²(u−u_c)²} is < 1e-21 beyond
  // |u| = 1/(4dx), so the alias term is below 1e-40 of the peak.
  const double s = 8.0 * dx, u_c = 0.05 / dx;
  const dw::SampledProfile smooth = dw::sampleProfile(
      [&](double x) { return std::exp(-x * x / (2 * s * s)) * std::exp(Cx(0.0, 2 * kPi * u_c * x)); },
      -60 * dx, 60 * dx, dx);
  ASSERT_EQ(smooth.t.size(), 121u);
  for (const dw::SampledProfile* p : {&noisy, &smooth}) {
    const int nu = 256;  // ≥ 2·samples: no lag truncation
    const dw::WignerGrid w = dw::wignerFFT(*p, nu);
    double peak = 0.0, total = 0.0, energy = 0.0;
    for (const Cx& t : p->t) energy += std::norm(t) * dx;
    for (int k = 0; k < nu; ++k) peak = std::max(peak, std::norm(directSpectrum(*p, w.uAt(k))));
    for (int k = 0; k < nu; ++k) {
      double column = 0.0;
      for (int j = 0; j < w.nx; ++j) column += w.at(j, k) * dx;
      total += column * w.du_per_m;
      const double direct = std::norm(directSpectrum(*p, w.uAt(k)));
      const double alias = std::norm(directSpectrum(*p, w.uAt(k) + 0.5 / dx));
      EXPECT_NEAR(column, direct + alias, 1e-12 * peak) << "k=" << k;
      if (p == &smooth) {
        EXPECT_NEAR(column, direct, 1e-12 * peak) << "k=" << k;
      }
    }
    EXPECT_NEAR(total, energy, 1e-13 * energy);
  }
}

// Rect of width a = 64 dx, edges half-way between samples. The rect is not band-limited: the discrete W is
// the closed form times (2πu·dx)/sin(2πu·dx) (see dirichletRatio), which is ≤ 1.0262 for |u| < 1/(16dx):
// expected error ≤ 2.6 % of |W|, growing to 11 % at 1/(8dx) and π/2 − 1 at the band edge 1/(4dx).
// We check the bound pointwise (with 1e-12 slack) and the plain 2.7 % of the local peak 2(a − 2|x|).
TEST(WignerFFT, RectApertureMatchesClosedForm) {
  const double a = 0.1, dx = a / 64;
  const dw::SampledProfile p = dw::sampleProfile([&](double x) { return Cx(std::abs(x) < a / 2 ? 1.0 : 0.0); },
                                                 -a / 2 - 16 * dx + dx / 2, a / 2 + 16 * dx, dx);
  ASSERT_EQ(p.t.size(), 96u);
  const dw::WignerGrid w = dw::wignerFFT(p, 256);
  int checked = 0;
  for (int j = 0; j < w.nx; ++j) {
    const double x = w.xAt(j);
    for (int k = 0; k < w.nu; ++k) {
      const double u = w.uAt(k);
      const double exact = rectWdf(x, u, a);
      if (std::abs(x) > a / 2) {
        EXPECT_NEAR(w.at(j, k), 0.0, 1e-15) << "outside the opening, x=" << x;
        continue;
      }
      if (std::abs(u) >= 1.0 / (16 * dx)) continue;
      const double bound = (dirichletRatio(u, dx) - 1.0) * std::abs(exact) + 1e-12 * a;
      EXPECT_NEAR(w.at(j, k), exact, bound) << "x=" << x << " u=" << u;
      EXPECT_NEAR(w.at(j, k), exact, 0.027 * 2 * (a - 2 * std::abs(x))) << "x=" << x << " u=" << u;
      ++checked;
    }
  }
  EXPECT_GT(checked, 64 * 30);
}

// Double slit (width a, centres ±d/2): W = W_r(x − d/2) + W_r(x + d/2) + 2cos(2πud)·W_r(x). The cross term
// lives midway, where t = 0: "mid-air" diffraction, signed, with zero row integral (|t(0)|² = 0).
TEST(WignerFFT, DoubleSlitCrossTermMidAir) {
  const double dx = 1e-6, a = 10 * dx, d = 41 * dx;  // all edges half-way between samples
  const auto slits = [&](double x) {
    return Cx(std::abs(x - d / 2) < a / 2 || std::abs(x + d / 2) < a / 2 ? 1.0 : 0.0);
  };
  const dw::SampledProfile p = dw::sampleProfile(slits, -40 * dx, 40 * dx, dx);
  const dw::WignerGrid w = dw::wignerFFT(p, 256);
  const int mid = 40;
  ASSERT_NEAR(w.xAt(mid), 0.0, 1e-15);
  ASSERT_EQ(std::abs(p.t[mid]), 0.0);
  double min_mid = 0.0, max_mid = 0.0, row_mid = 0.0;
  for (int j = 0; j < w.nx; ++j) {
    const double x = w.xAt(j);
    for (int k = 0; k < w.nu; ++k) {
      const double u = w.uAt(k);
      const double r1 = rectWdf(x - d / 2, u, a), r2 = rectWdf(x + d / 2, u, a), rc = rectWdf(x, u, a);
      const double exact = r1 + r2 + 2 * std::cos(2 * kPi * u * d) * rc;
      if (j == mid) {
        min_mid = std::min(min_mid, w.at(j, k));
        max_mid = std::max(max_mid, w.at(j, k));
        row_mid += w.at(j, k) * w.du_per_m;
      }
      if (std::abs(u) >= 1.0 / (16 * dx)) continue;
      const double bound =
          (dirichletRatio(u, dx) - 1.0) * (std::abs(r1) + std::abs(r2) + 2 * std::abs(rc)) + 1e-12 * a;
      EXPECT_NEAR(w.at(j, k), exact, bound) << "x=" << x << " u=" << u;
    }
  }
  EXPECT_NEAR(max_mid, 4 * a, 1e-12 * a);  // 2·W_r(0, 0) = 2·2a at u = 0
  EXPECT_LT(min_mid, -0.5 * 4 * a);        // strongly negative fringes where nothing is open
  EXPECT_NEAR(row_mid, 0.0, 1e-13);
}

// Im W is round-off only (the end lags are folded symmetrically), and a carrier e^{i2πu0x} shifts W to u0:
// by exactly k0 columns when u0 = k0·du, and with the u-centroid at u0 otherwise.
TEST(WignerFFT, RealValuedAndLinearPhaseShift) {
  const dw::SampledProfile noisy = randomProfile(50, 1e-3, 3);
  for (int nu : {8, 64, 256}) {
    const dw::WignerGrid w = dw::wignerFFT(noisy, nu);
    double peak = 0.0;
    for (double v : w.values) peak = std::max(peak, std::abs(v));
    EXPECT_LE(w.max_abs_imag, 1e-14 * peak) << "nu=" << nu;
  }
  const double dx = 1e-3, s = 8 * dx;
  const int nu = 256;
  const double du = 1.0 / (2.0 * nu * dx);
  const auto envelope = [&](double x) { return Cx(std::exp(-x * x / (2 * s * s))); };
  const dw::WignerGrid base = dw::wignerFFT(dw::sampleProfile(envelope, -100 * dx, 100 * dx, dx), nu);
  for (double shift : {7.0, 7.3}) {
    const double u0 = shift * du;
    const auto carrier = [&](double x) { return envelope(x) * std::exp(Cx(0.0, 2 * kPi * u0 * x)); };
    const dw::WignerGrid w = dw::wignerFFT(dw::sampleProfile(carrier, -100 * dx, 100 * dx, dx), nu);
    for (int j = 0; j < w.nx; j += 7) {
      double mass = 0.0, moment = 0.0;
      for (int k = 0; k < nu; ++k) {
        mass += w.at(j, k);
        moment += w.at(j, k) * w.uAt(k);
        if (shift == 7.0 && k >= 7) {
          EXPECT_NEAR(w.at(j, k), base.at(j, k - 7), 1e-14) << j << " " << k;
        }
      }
      if (std::norm(envelope(w.xAt(j))) > 1e-6) {
        EXPECT_NEAR(moment / mass, u0, 1e-9 / dx) << "j=" << j;
      }
    }
  }
}

// Rough surface, Gaussian ρ_h = e^{−x²/ℓ²}, g = σ_α². Oracle (derived here, not in the code):
//   γ = e^{−g}·e^{gρ} = e^{−g} Σ_n gⁿ/n!·e^{−n x²/ℓ²},  and  ∫ e^{−n x²/ℓ²} e^{−i2πux} dx = √(πℓ²/n)·e^{−π²ℓ²u²/n},
//   so W_γ(u) = e^{−g}[δ(u) + Σ_{n≥1} (gⁿ/n!)·√(πℓ²/n)·e^{−π²ℓ²u²/n}] (n = 0 gives the specular δ).
double roughSeries(double g, double ell, double u) {
  double sum = 0.0;
  for (int n = 1;; ++n) {
    const double log_poisson = -g + n * std::log(g) - std::lgamma(n + 1.0);
    sum += std::exp(log_poisson - kPi * kPi * ell * ell * u * u / n) * std::sqrt(kPi * ell * ell / n);
    if (n > g && log_poisson < -60.0) return sum;  // remaining Poisson weight < e^{−60}
  }
}

TEST(RoughSurface, MatchesClosedFormSeries) {
  const double lambda = 500e-9;
  struct Case { double sigma_h, ell, cos_i, u_max; int nu; };
  const Case cases[] = {{0.02 * lambda, 2 * lambda, 1.0, 4 / lambda, 512},   // g ≈ 0.063
                        {0.14 * lambda, 1 * lambda, 0.8, 8 / lambda, 400},   // g ≈ 2.5
                        {0.6 * lambda, 3 * lambda, 0.5, 4 / lambda, 1000},   // g ≈ 32
                        {0.6 * lambda, 3 * lambda, 0.5, 0.3 / lambda, 64}};  // same, lobe cut by u_max
  for (const Case& c : cases) {
    const dw::RoughSurfaceWdf r = dw::roughSurfaceWdf(c.sigma_h, c.ell, lambda, c.cos_i, c.nu, c.u_max);
    const double g = std::pow(2 * kPi * c.sigma_h / lambda * (1 + c.cos_i), 2);
    EXPECT_NEAR(r.phase_variance, g, 1e-12 * g);
    EXPECT_NEAR(r.specular_weight, std::exp(-g), 1e-15);
    EXPECT_NEAR(r.diffuse_weight, 1 - std::exp(-g), 1e-15);
    ASSERT_EQ(r.diffuse.size(), static_cast<size_t>(c.nu));
    EXPECT_NEAR(r.u0_per_m, -c.u_max, 1e-9 * c.u_max);
    EXPECT_NEAR(r.du_per_m, 2 * c.u_max / c.nu, 1e-9 * c.u_max);
    const double peak = roughSeries(g, c.ell, 0.0);
    EXPECT_NEAR(r.diffuse[static_cast<size_t>(c.nu / 2)], peak, 1e-10 * peak);
    for (int k = 0; k < c.nu; ++k) {
      const double u = r.u0_per_m + k * r.du_per_m;
      EXPECT_NEAR(r.diffuse[static_cast<size_t>(k)], roughSeries(g, c.ell, u), 1e-10 * peak) << "u=" << u;
      EXPECT_GE(r.diffuse[static_cast<size_t>(k)], 0.0);
    }
  }
}

// ∫W_γ du = γ(0) = 1: specular weight + Σ diffuse·du when u_max covers the lobe (spectrally accurate sum).
TEST(RoughSurface, UnitTotalWeightAndSmoothLimit) {
  const double lambda = 0.17;  // 2 kHz sound; a gravel-like wall
  for (double sigma_h : {0.001, 0.01, 0.03}) {
    const dw::RoughSurfaceWdf r = dw::roughSurfaceWdf(sigma_h, 0.05, lambda, 0.9, 2000, 400.0);
    double diffuse = 0.0;
    for (double v : r.diffuse) diffuse += v * r.du_per_m;
    EXPECT_NEAR(r.specular_weight + diffuse, 1.0, 1e-10) << "sigma_h=" << sigma_h;
  }
  // σ_h = λ/1000 at normal incidence: g = (4π·1e-3)² ≈ 1.6e-4, nearly all specular, lobe weight ≈ g.
  const dw::RoughSurfaceWdf smooth = dw::roughSurfaceWdf(1e-3 * lambda, lambda, lambda, 1.0, 512, 10 / lambda);
  const double g = std::pow(4 * kPi * 1e-3, 2);
  EXPECT_GT(smooth.specular_weight, 0.9998);
  double diffuse = 0.0;
  for (double v : smooth.diffuse) diffuse += v * smooth.du_per_m;
  EXPECT_NEAR(diffuse, g, 1e-3 * g);
}

TEST(RoughSurface, RejectsBadParameters) {
  const double nan = std::nan("");
  using diffray::core::InputError;
  EXPECT_THROW(dw::roughSurfaceWdf(0.0, 1e-6, 5e-7, 1.0, 64, 1e7), InputError);
  EXPECT_THROW(dw::roughSurfaceWdf(nan, 1e-6, 5e-7, 1.0, 64, 1e7), InputError);
  EXPECT_THROW(dw::roughSurfaceWdf(1e-7, -1e-6, 5e-7, 1.0, 64, 1e7), InputError);
  EXPECT_THROW(dw::roughSurfaceWdf(1e-7, 1e-6, 0.0, 1.0, 64, 1e7), InputError);
  EXPECT_THROW(dw::roughSurfaceWdf(1e-7, 1e-6, 5e-7, nan, 64, 1e7), InputError);
  EXPECT_THROW(dw::roughSurfaceWdf(1e-7, 1e-6, 5e-7, 1.5, 64, 1e7), InputError);
  EXPECT_THROW(dw::roughSurfaceWdf(1e-7, 1e-6, 5e-7, 1.0, 63, 1e7), InputError);
  EXPECT_THROW(dw::roughSurfaceWdf(1e-7, 1e-6, 5e-7, 1.0, 64, 0.0), InputError);
  EXPECT_THROW(dw::wignerFFT(dw::SampledProfile{0.0, 1e-6, {}}, 64), InputError);
  EXPECT_THROW(dw::wignerFFT(dw::SampledProfile{0.0, 0.0, {Cx(1.0)}}, 64), InputError);
  EXPECT_THROW(dw::wignerFFT(dw::SampledProfile{0.0, 1e-6, {Cx(1.0)}}, 7), InputError);
  EXPECT_THROW(dw::sampleProfile([](double) { return Cx(1.0); }, 1.0, 0.0, 0.1), InputError);
}

namespace {
std::string writeTemp(const std::string& name, const std::string& content) {
  return diffray::testing::writeTempCsv("profile", name, content);
}
}  // namespace

TEST(ProfileCsv, GoodFileRoundTripsAndResamples) {
  const std::string path = writeTemp("good",
                                     "# a measured groove\n"
                                     "x_m, amplitude, phase_rad\n"
                                     "\n"
                                     "0.0, 1.0, 0.0\n"
                                     "1e-6, 0.5, 1.5   # trailing comment\n"
                                     "3e-6, 0.0, -4.5\n");
  const dw::ProfilePoints pts = dw::readProfileCsv(path);
  ASSERT_EQ(pts.x_m.size(), 3u);
  EXPECT_EQ(pts.x_m, (std::vector<double>{0.0, 1e-6, 3e-6}));
  EXPECT_EQ(pts.amplitude, (std::vector<double>{1.0, 0.5, 0.0}));
  EXPECT_EQ(pts.phase_rad, (std::vector<double>{0.0, 1.5, -4.5}));
  const dw::SampledProfile p = dw::resampleProfile(pts, 0.5e-6);
  ASSERT_EQ(p.t.size(), 7u);
  EXPECT_EQ(p.x0_m, 0.0);
  const double a[] = {1.0, 0.75, 0.5, 0.375, 0.25, 0.125, 0.0};
  const double phi[] = {0.0, 0.75, 1.5, 0.0, -1.5, -3.0, -4.5};  // interpolated as given, not wrapped
  for (size_t j = 0; j < 7; ++j) {
    EXPECT_NEAR(std::abs(p.t[j] - std::polar(a[j], phi[j])), 0.0, 1e-12) << "j=" << j;
  }
}

TEST(ProfileCsv, BadInputNamesFileAndLine) {
  struct Bad { const char* name; const char* content; const char* line; };
  const Bad cases[] = {
      {"columns", "x,a,p\n0,1,0\n1e-6,1\n", ":3:"},         {"extra", "0,1,0\n1e-6,1,0,5\n", ":2:"},
      {"text", "0,1,0\n# c\n1e-6,one,0\n", ":3:"},         {"nan", "0,1,0\n1e-6,1,nan\n", ":2:"},
      {"inf", "0,1,0\n1e-6,1,0\n2e-6,inf,0\n", ":3:"},     {"amp_hi", "0,1.5,0\n1e-6,1,0\n", ":1:"},
      {"amp_lo", "0,1,0\n1e-6,-0.1,0\n", ":2:"},            {"x_equal", "0,1,0\n0,1,0\n", ":2:"},
      {"x_down", "0,1,0\n2e-6,1,0\n1e-6,1,0\n", ":3:"},     {"one_row", "x,a,p\n0,1,0\n\n", ":3:"},
      {"empty_field", "0,1,0\n1e-6,,0\n", ":2:"},
  };
  for (const Bad& c : cases) {
    const std::string path = writeTemp(c.name, c.content);
    try {
      dw::readProfileCsv(path);
      ADD_FAILURE() << c.name << ": no exception";
    } catch (const diffray::core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path + c.line), std::string::npos) << c.name << ": " << e.what();
    }
  }
  const diffray::test::TempDir empty("no_profile");
  const std::string missing = empty.file("no_such_profile.csv");
  EXPECT_THROW(dw::readProfileCsv(missing), diffray::core::InputError);
  EXPECT_THROW(dw::resampleProfile(dw::ProfilePoints{{0.0, 1.0}, {1.0, 1.0}, {0.0, 0.0}}, 0.0),
               diffray::core::InputError);
}
