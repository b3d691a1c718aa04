// Tests of the 3D Rayleigh–Sommerfeld point-source aperture reference (reference/aperture_point.h).
// Oracles independent of its quadrature: a brute-force uniform 8-point rule written here,
// Fraunhofer's sinc² product (Goodman, ch. 4), the paraxial Fresnel product with fresnel.h's integrals, the
// free field through a huge opening (with the edge-wave ripple bounded by the half-plane asymptotics),
// the small-opening limit of RS1's (non-)reciprocity, and explicit unfolding for the floor option.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "diffray/core/error.h"
#include "diffray/reference/aperture_point.h"
#include "diffray/reference/fresnel.h"
#include "reference_fixtures.h"

namespace dr = diffray::reference;
using Complex = std::complex<double>;
using dr::ApertureRect;
using dr::ApertureScreen;
using dr::CartesianPoint;
using diffray_test::gauss8;

namespace {

constexpr double kPi = 3.14159265358979323846;

double distance(const CartesianPoint& a, const CartesianPoint& b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m, a.z_m - b.z_m);
}

// U·R·e^{ikR}: the field relative to the free field, phase included.
Complex reFreeField(double wavelength, const ApertureScreen& screen, const CartesianPoint& s,
                    const CartesianPoint& p) {
  const double r = distance(s, p), k = 2.0 * kPi / wavelength;
  return dr::aperturePointSource(wavelength, screen, s, p) * std::polar(r, k * r);
}

// The RS1 integral by a uniform tensor grid of 8-point panels of side `panel`.
Complex bruteForce(double wavelength, const ApertureRect& a, const CartesianPoint& s, const CartesianPoint& p,
                   double panel) {
  const double k = 2.0 * kPi / wavelength;
  auto integrand = [&](double x, double y) {
    const double rs = std::hypot(x - s.x_m, y - s.y_m, s.z_m), r = std::hypot(x - p.x_m, y - p.y_m, p.z_m);
    return std::polar(1.0 / rs, -k * rs) * (p.z_m / (2.0 * kPi * r)) * Complex(1.0 / r, k) *
           std::polar(1.0 / r, -k * r);
  };
  const int nx = static_cast<int>(std::ceil((a.x1_m - a.x0_m) / panel));
  const int ny = static_cast<int>(std::ceil((a.y1_m - a.y0_m) / panel));
  const double hx = (a.x1_m - a.x0_m) / nx, hy = (a.y1_m - a.y0_m) / ny;
  Complex sum(0.0, 0.0);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const double x0 = a.x0_m + i * hx, y0 = a.y0_m + j * hy;
      sum += gauss8([&](double x) { return gauss8([&](double y) { return integrand(x, y); }, y0, y0 + hy); },
                    x0, x0 + hx);
    }
  return sum;
}

}  // namespace

TEST(AperturePointSource, AgreesWithBruteForceQuadrature) {
  // A 0.3 × 0.2 m opening at λ = 5 cm, and the receiver close to the screen (the kernel's peak has width
  // ~z_P): the brute force uses uniform panels of λ/16 (phase ≤ π/4 per panel).
  const double lambda = 0.05;
  const ApertureRect rect{-0.1, 0.2, -0.05, 0.15};
  const CartesianPoint source{0.1, -0.05, -0.4};
  for (const CartesianPoint& receiver : {CartesianPoint{-0.2, 0.3, 0.5}, CartesianPoint{0.05, 0.02, 0.06}}) {
    const Complex u = dr::aperturePointSource(lambda, {{rect}, {}}, source, receiver);
    const Complex oracle = bruteForce(lambda, rect, source, receiver, lambda / 16.0);
    EXPECT_LT(std::abs(u - oracle) / std::abs(oracle), 1e-9) << receiver.z_m;
  }
}

TEST(AperturePointSource, FarFieldMatchesFraunhoferSincProduct) {
  // a × b = 0.2 × 0.1 m, λ = 1 cm, source and receiver 10 km away (Fresnel phase k·a²/8·(2/z) = 6e-4 rad).
  // Fraunhofer (Goodman, ch. 4): I = (ab/λz)² sinc²(ax/λz) sinc²(by/λz) for unit incidence; here the incidence is
  // 1/z_S, and RS1 adds the obliquity cosθ of the receiver direction.
  const double lambda = 0.01, a = 0.2, b = 0.1, zs = 1e4, zr = 1e4;
  const ApertureScreen screen{{{-0.5 * a, 0.5 * a, -0.5 * b, 0.5 * b}}, {}};
  const CartesianPoint source{0.0, 0.0, -zs};
  auto sinc = [](double t) { return t == 0.0 ? 1.0 : std::sin(kPi * t) / (kPi * t); };
  const double peak = a * b / (lambda * zr * zs);
  // Direction cosines hitting the centre, half-maxima, the first zeros and sidelobes of both factors.
  for (double alpha : {0.0, 0.02, 0.05, 0.0715}) {
    for (double beta : {0.0, 0.05, 0.1, 0.143}) {
      const double cos_theta = std::sqrt(1.0 - alpha * alpha - beta * beta);
      const CartesianPoint receiver{zr * alpha / cos_theta, zr * beta / cos_theta, zr};
      const double r = std::hypot(receiver.x_m, receiver.y_m, receiver.z_m);
      const double expected =
          a * b / (lambda * r * zs) * cos_theta *
          std::abs(sinc(a * alpha / lambda) * sinc(b * beta / lambda));
      const double u = std::abs(dr::aperturePointSource(lambda, screen, source, receiver));
      EXPECT_NEAR(u, expected, 2e-3 * peak) << alpha << " " << beta;
    }
  }
}

TEST(AperturePointSource, ParaxialFresnelRegimeMatchesFresnelIntegrals) {
  // Fresnel number ~2: U/U_free ≈ (i/2)·conj(ΔF_x·ΔF_y), ΔF = F(t2) − F(t1), t = √(2/(λd))·(edge − x_c),
  // 1/d = 1/z_S + 1/z_P, x_c the crossing point of the ray S→P (e^{+iωt} conjugates the e^{−iωt} form).
  // Neglected at the aperture's far corners (ρ <= 0.25 m from either foot point): the quartic phase
  // k·ρ⁴/(8z³) per side (<= 1.2e-3 rad together) and the amplitude's (ρ/z)²/2 (<= 5e-4); their effect on U
  // is weighted further by the edge waves, so 2e-3 is a bound.
  const double lambda = 0.005, zs = 8.0, zr = 8.0;
  const ApertureRect rect{-0.1, 0.1, -0.08, 0.1};
  const CartesianPoint source{0.01, 0.0, -zs};
  const double d = 1.0 / (1.0 / zs + 1.0 / zr), scale = std::sqrt(2.0 / (lambda * d));
  for (const CartesianPoint& receiver :
       {CartesianPoint{0.02, 0.01, zr}, CartesianPoint{0.1, -0.05, zr}, CartesianPoint{-0.15, 0.12, zr}}) {
    const double xc = (source.x_m * zr + receiver.x_m * zs) / (zs + zr);
    const double yc = (source.y_m * zr + receiver.y_m * zs) / (zs + zr);
    auto delta = [&](double lo, double hi, double c) {
      return dr::fresnelIntegral(scale * (hi - c)) - dr::fresnelIntegral(scale * (lo - c));
    };
    const Complex fx = delta(rect.x0_m, rect.x1_m, xc), fy = delta(rect.y0_m, rect.y1_m, yc);
    const Complex paraxial = Complex(0.0, 0.5) * std::conj(fx * fy);
    EXPECT_LT(std::abs(reFreeField(lambda, {{rect}, {}}, source, receiver) - paraxial), 2e-3) << receiver.x_m;
  }
}

TEST(AperturePointSource, HugeOpeningTransmitsTheFreeField) {
  // A 12 × 12 m opening, source and receiver within 1.5 m of it: U/U_free − 1 is the edge-wave ripple. Each
  // edge contributes at most like a half-plane's diffracted wave, (R/L)/(2√π·√(k(L − R))) with L the
  // shortest path via that edge (asymptotics of half_plane_point.h, checked there against BTM).
  const double lambda = 0.2, k = 2.0 * kPi / lambda, half = 6.0;
  const ApertureScreen screen{{{-half, half, -half, half}}, {}};
  const CartesianPoint source{0.0, 0.0, -1.0}, receiver{0.3, -0.2, 1.5};
  const double r = distance(source, receiver);
  double ripple = 0.0;
  for (int edge = 0; edge < 4; ++edge) {
    // Shortest path to the edge line x = ±half (or y = ±half): unfold about the edge (a 1D minimisation).
    const bool along_x = edge < 2;
    const double e = edge % 2 == 0 ? half : -half;
    const double ds = std::abs(e - (along_x ? source.x_m : source.y_m));
    const double dr_ = std::abs(e - (along_x ? receiver.x_m : receiver.y_m));
    const double hs = std::hypot(ds, source.z_m), hr = std::hypot(dr_, receiver.z_m);
    const double along = along_x ? receiver.y_m - source.y_m : receiver.x_m - source.x_m;
    const double l = std::hypot(hs + hr, along);
    ripple += (r / l) / (2.0 * std::sqrt(kPi) * std::sqrt(k * (l - r)));
  }
  EXPECT_LT(ripple, 0.05);
  EXPECT_LT(std::abs(reFreeField(lambda, screen, source, receiver) - 1.0), ripple);
}

TEST(AperturePointSource, SmallOpeningShowsRS1Obliquity) {
  // RS1 is not reciprocal: for an opening of side a ≪ λ the swap (source ↔ receiver, mirrored in z = 0)
  // changes U by [cosθ_P(1 + 1/(ikr))]/[cosθ_S(1 + 1/(ik·r_s))], up to the integrand's O(a/r) variation.
  const double lambda = 0.5, k = 2.0 * kPi / lambda, a = 1e-3;
  const ApertureScreen screen{{{-0.5 * a, 0.5 * a, -0.5 * a, 0.5 * a}}, {}};
  const CartesianPoint s{0.3, 0.2, -0.8}, p{-0.5, 0.4, 1.1};
  const CartesianPoint s_swapped{p.x_m, p.y_m, -p.z_m}, p_swapped{s.x_m, s.y_m, -s.z_m};
  const CartesianPoint origin{0.0, 0.0, 0.0};
  const double rs = distance(s, origin), r = distance(p, origin);
  const Complex expected = (p.z_m / r) * (1.0 + 1.0 / Complex(0.0, k * r)) /
                           ((-s.z_m / rs) * (1.0 + 1.0 / Complex(0.0, k * rs)));
  const Complex ratio = dr::aperturePointSource(lambda, screen, s, p) /
                        dr::aperturePointSource(lambda, screen, s_swapped, p_swapped);
  EXPECT_LT(std::abs(ratio - expected), 2.0 * a / std::min(rs, r));
  // Mirror-symmetric geometry (receiver = source mirrored): the swap is the same configuration.
  const CartesianPoint mirror{s.x_m, s.y_m, -s.z_m};
  const ApertureScreen door{{{-0.45, 0.45, 0.0, 2.1}}, {}};
  EXPECT_NEAR(std::abs(dr::aperturePointSource(lambda, door, s, mirror) -
                       dr::aperturePointSource(lambda, door, {mirror.x_m, mirror.y_m, -mirror.z_m},
                                               {s.x_m, s.y_m, -s.z_m})),
              0.0, 1e-15);
}

TEST(AperturePointSource, FloorImagesEqualExplicitUnfolding) {
  const double lambda = 0.343, floor = -0.3;
  const ApertureRect door{-0.45, 0.45, floor, floor + 2.1};
  const ApertureRect mirrored{-0.45, 0.45, floor - 2.1, floor};
  const ApertureScreen with_floor{{door}, floor};
  const ApertureScreen unfolded{{door, mirrored}, {}};
  const CartesianPoint source{0.4, 1.2, -1.5}, receiver{-1.0, 0.9, 2.5};
  const CartesianPoint image{source.x_m, 2.0 * floor - source.y_m, source.z_m};
  const Complex explicit_sum = dr::aperturePointSource(lambda, unfolded, source, receiver) +
                               dr::aperturePointSource(lambda, unfolded, image, receiver);
  const Complex u = dr::aperturePointSource(lambda, with_floor, source, receiver);
  EXPECT_LT(std::abs(u - explicit_sum) / std::abs(explicit_sum), 1e-12);
  // A source on the floor is its own image: twice the unfolded opening's field.
  const CartesianPoint on_floor{0.4, floor, -1.5};
  const Complex doubled = 2.0 * dr::aperturePointSource(lambda, unfolded, on_floor, receiver);
  EXPECT_LT(std::abs(dr::aperturePointSource(lambda, with_floor, on_floor, receiver) - doubled) /
                std::abs(doubled),
            1e-12);
}

TEST(AperturePointSource, LevelsAndBandAverage) {
  const ApertureScreen screen{{{-0.2, 0.3, -0.1, 0.25}}, {}};
  const CartesianPoint source{0.1, 0.0, -0.7}, receiver{0.4, -0.3, 1.2};
  const double c = 343.0, r = distance(source, receiver);
  const Complex u = dr::aperturePointSource(c / 1000.0, screen, source, receiver);
  EXPECT_NEAR(dr::apertureLevelDb(c / 1000.0, screen, source, receiver), 20.0 * std::log10(std::abs(u) * r),
              1e-12);
  EXPECT_NEAR(dr::apertureBandLevelDb(1000.0, 1000.0, 1, c, screen, source, receiver),
              dr::apertureLevelDb(c / 1000.0, screen, source, receiver), 1e-9);
  // 300 points (crosses the recurrence's re-seed at 256) against single-frequency evaluations.
  const double lo = 707.0, hi = 1414.0;
  const int n = 300;
  const double by_hand = diffray_test::bandLevelByHandDb(
      lo, hi, n, [&](double f) {
        return std::norm(dr::aperturePointSource(c / f, screen, source, receiver) * r);
      });
  EXPECT_NEAR(dr::apertureBandLevelDb(lo, hi, n, c, screen, source, receiver), by_hand, 1e-8);
}

TEST(AperturePointSource, RejectsBadInput) {
  using diffray::core::InputError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ApertureScreen ok{{{-0.5, 0.5, 0.0, 2.0}}, {}};
  const CartesianPoint s{0.0, 1.0, -1.0}, p{0.0, 1.0, 1.0};
  EXPECT_THROW(dr::aperturePointSource(0.0, ok, s, p), InputError);
  EXPECT_THROW(dr::aperturePointSource(nan, ok, s, p), InputError);
  EXPECT_THROW(dr::aperturePointSource(0.3, ok, {0.0, 1.0, 1.0}, p), InputError);   // source behind
  EXPECT_THROW(dr::aperturePointSource(0.3, ok, s, {0.0, 1.0, 0.0}), InputError);   // receiver on screen
  EXPECT_THROW(dr::aperturePointSource(0.3, ok, s, {nan, 1.0, 1.0}), InputError);
  EXPECT_THROW(dr::aperturePointSource(0.3, {{}, {}}, s, p), InputError);
  EXPECT_THROW(dr::aperturePointSource(0.3, {{{0.5, -0.5, 0.0, 2.0}}, {}}, s, p), InputError);  // reversed
  EXPECT_THROW(dr::aperturePointSource(0.3, {{{0.5, 0.5, 0.0, 2.0}}, {}}, s, p), InputError);   // empty
  EXPECT_THROW(dr::aperturePointSource(0.3, {{{-0.5, 0.5, 0.0, 2.0}, {0.0, 1.0, 1.0, 3.0}}, {}}, s, p),
               InputError);  // overlapping
  EXPECT_THROW(dr::aperturePointSource(0.3, {ok.openings, 0.5}, s, p), InputError);  // opening below floor
  EXPECT_THROW(dr::aperturePointSource(0.3, {ok.openings, 0.0}, {0.0, -1.0, -1.0}, p), InputError);
  EXPECT_THROW(dr::aperturePointSource(1e-6, ok, s, p), InputError);  // too many nodes
  EXPECT_THROW(dr::apertureBandLevelDb(500.0, 250.0, 10, 343.0, ok, s, p), InputError);
  EXPECT_THROW(dr::apertureBandLevelDb(250.0, 500.0, 10, 0.0, ok, s, p), InputError);
}
