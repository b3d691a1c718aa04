// Tests of the diffraction references (reference/fraunhofer.h, fresnel.h,
// rayleigh_sommerfeld.h). Each reference is checked against something
// independent of its own implementation: published check values, values of mpmath (30 digits),
// limits, symmetries, Parseval, boundary conditions, or a brute-force quadrature written here.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <utility>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/angular_spectrum.h"
#include "diffray/reference/fraunhofer.h"
#include "diffray/reference/fresnel.h"
#include "diffray/reference/rayleigh_sommerfeld.h"

namespace dr = diffray::reference;
using Complex = std::complex<double>;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Composite Simpson rule with n (even) intervals: a brute-force oracle independent of the module.
template <class T>
T simpson(const std::function<T(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  T sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
  return sum * (h / 3.0);
}

double degrees(double deg) { return deg * kPi / 180.0; }

using Openings = std::vector<std::pair<double, double>>;

}  // namespace

// ---- Fresnel integrals -----------------------------------------------------------------------------------

TEST(FresnelIntegral, MatchesReferenceValues) {
  // {w, C(w), S(w)}: C(1), S(1) from the brief; the others from mpmath.fresnelc/fresnels at 30 digits.
  const double table[][3] = {
      {0.1, 0.0999975326270850736, 0.000523589547612210687},
      {0.5, 0.492344225871446393, 0.0647324328599992776},
      {1.0, 0.7798934003768228, 0.4382591473903548},
      {1.5, 0.445261176039821535, 0.697504960082093013},
      {1.8, 0.333632927221557117, 0.450938769267583060},
      {2.0, 0.488253406075340755, 0.343415678363698242},
      {2.5, 0.457413009641777045, 0.619181755819592936},
      {3.0, 0.605720789297685630, 0.496312998967375036},
      {5.0, 0.563631188704012231, 0.499191381917116887},
      {10.0, 0.499898694205515724, 0.468169978584882240},
      {1000.0, 0.499999999898678816, 0.499681690113816306},
  };
  for (const auto& row : table) {
    const Complex f = dr::fresnelIntegral(row[0]);
    EXPECT_NEAR(f.real(), row[1], 1e-13) << "C(" << row[0] << ")";
    EXPECT_NEAR(f.imag(), row[2], 1e-13) << "S(" << row[0] << ")";
  }
}

TEST(FresnelIntegral, IsOddAndTendsToHalf) {
  for (double w : {0.0, 0.3, 1.2, 1.5, 2.7, 8.1, 55.5}) {
    const Complex sum = dr::fresnelIntegral(w) + dr::fresnelIntegral(-w);
    EXPECT_NEAR(std::abs(sum), 0.0, 1e-15) << w;
  }
  // C(w), S(w) − 1/2 ~ ±1/(πw): within 1e-6 of 1/2 at w = 1e6, 1e9.
  for (double w : {1e6, 1e9}) {
    EXPECT_NEAR(dr::fresnelIntegral(w).real(), 0.5, 1.0 / (kPi * w) + 1e-15);
    EXPECT_NEAR(dr::fresnelIntegral(w).imag(), 0.5, 1.0 / (kPi * w) + 1e-15);
    EXPECT_NEAR(dr::fresnelIntegral(-w).real(), -0.5, 1.0 / (kPi * w) + 1e-15);
  }
  // Leading asymptotics C(w) ≈ 1/2 + sin(πw²/2)/(πw), S(w) ≈ 1/2 − cos(πw²/2)/(πw); error O(w⁻³).
  const double w = 40.1;
  EXPECT_NEAR(dr::fresnelIntegral(w).real(), 0.5 + std::sin(0.5 * kPi * w * w) / (kPi * w), 1e-5);
  EXPECT_NEAR(dr::fresnelIntegral(w).imag(), 0.5 - std::cos(0.5 * kPi * w * w) / (kPi * w), 1e-5);
}

TEST(FresnelIntegral, DerivativeIsTheKernelAcrossTheMethodSwitch) {
  // dF/dw = exp(iπw²/2); central differences straddle the series / continued-fraction switch at 1.5.
  const double h = 1e-5;
  for (double w : {0.7, 1.49999, 1.5, 1.50001, 2.2, 6.3}) {
    const Complex derivative = (dr::fresnelIntegral(w + h) - dr::fresnelIntegral(w - h)) / (2.0 * h);
    const Complex kernel = std::polar(1.0, 0.5 * kPi * w * w);
    EXPECT_NEAR(std::abs(derivative - kernel), 0.0, 1e-8) << w;
  }
  EXPECT_NEAR(std::abs(dr::fresnelIntegral(1.5 - 1e-13) - dr::fresnelIntegral(1.5 + 1e-13)), 0.0, 1e-12);
}

TEST(FresnelIntegral, AgreesWithBruteForceQuadrature) {
  for (double w : {0.9, 2.3, 4.7}) {
    const Complex brute =
        simpson<Complex>([](double t) { return std::polar(1.0, 0.5 * kPi * t * t); }, 0.0, w, 20000);
    EXPECT_NEAR(std::abs(dr::fresnelIntegral(w) - brute), 0.0, 1e-12) << w;
  }
}

TEST(FresnelIntegral, TailAndSommerfeldGAreConsistent) {
  const Complex half(0.5, 0.5);
  for (double w : {-30.0, -2.0, -0.4, 0.0, 0.4, 1.5, 2.0, 30.0})
    EXPECT_NEAR(std::abs(dr::fresnelIntegralTail(w) + dr::fresnelIntegral(w) - half), 0.0, 1e-14) << w;
  // Far tail without cancellation: ∫_w^∞ exp(iπt²/2) dt ≈ i·exp(iπw²/2)/(πw), relative error ~1/(πw)².
  const double w = 3.0e4;
  const Complex asymptotic =
      Complex(0.0, 1.0) * std::polar(1.0, 0.5 * kPi * std::fmod(w * w, 4.0)) / (kPi * w);
  EXPECT_NEAR(std::abs(dr::fresnelIntegralTail(w) / asymptotic - 1.0), 0.0, 1e-9);
  // G(a) = ∫_a^∞ e^{−iτ²} dτ: G(0) = (√π/2)e^{−iπ/4}, G(a) + G(−a) = √π e^{−iπ/4}.
  const Complex full = std::polar(std::sqrt(kPi), -0.25 * kPi);
  EXPECT_NEAR(std::abs(dr::sommerfeldG(0.0) - 0.5 * full), 0.0, 1e-15);
  for (double a : {0.3, 1.7, 12.0})
    EXPECT_NEAR(std::abs(dr::sommerfeldG(a) + dr::sommerfeldG(-a) - full), 0.0, 1e-14) << a;
}

// ---- Fresnel slit ----------------------------------------------------------------------------------------

// ∫_0^w e^{iπt²/2} dt by Simpson's rule on 40000 panels (|w| ≤ 6 here: error below 1e-12), the tests' own
// Fresnel integral for the check values below.
static Complex fresnelBySimpson(double w) {
  return simpson<Complex>([](double t) { return std::polar(1.0, 0.5 * kPi * t * t); }, 0.0, w, 40000);
}

TEST(FresnelSlit, MatchesCheckValues) {
  // A plane wave through a slit of width a, intensity at x on a screen at z, re the incident (Born & Wolf,
  // §8.7.3): I/I0 = ½·|F(u₂) − F(u₁)|², u₁,₂ = √(2/λz)·(∓a/2 − x), F = C + iS, F by quadrature here.
  // λ = 0.01 m, a = 0.2 m, z = 1 m; the integrals are known to 1e-12, so 1e-9 is rounding plus margin.
  const double a = 0.2, lambda = 0.01, z = 1.0, s = std::sqrt(2.0 / (lambda * z));
  for (double x : {0.0, 0.05, 0.1, 0.15, 0.3}) {
    const Complex d = fresnelBySimpson(s * (0.5 * a - x)) - fresnelBySimpson(s * (-0.5 * a - x));
    const double expected = 0.5 * std::norm(d);
    EXPECT_NEAR(dr::fresnelSlitIntensity(x, a, lambda, z), expected, 1e-9) << x;
    EXPECT_DOUBLE_EQ(dr::fresnelSlitIntensity(-x, a, lambda, z), dr::fresnelSlitIntensity(x, a, lambda, z));
  }
  // The on-axis value by hand, as a check of the formula above: 2·(C(√2)² + S(√2)²) = 1.57896…
  EXPECT_NEAR(dr::fresnelSlitIntensity(0.0, a, lambda, z), 1.578965, 1e-6);
}

TEST(FresnelSlit, LimitsNearAndFar) {
  // Close behind a wide slit: the incident intensity inside (edge ripple ~ 2√2/(πw), w = √(2/λz)·a/2 ≈ 224),
  // darkness outside.
  EXPECT_NEAR(dr::fresnelSlitIntensity(0.0, 1.0, 1e-3, 1e-2), 1.0, 5e-3);
  EXPECT_NEAR(dr::fresnelSlitIntensity(0.8, 1.0, 1e-3, 1e-2), 0.0, 1e-4);
  // Far field (z = 2000 a²/λ): I/I0 → |T(x/λz)|²/(λz) = (a²/λz) sinc²(ax/λz).
  const double a = 0.1, lambda = 0.01, z = 2000.0 * a * a / lambda;
  for (double ua : {0.0, 0.4, 1.5, 2.5}) {
    const double x = ua * lambda * z / a;
    const double fraunhofer = dr::slitFraunhofer(ua / a, a) / (lambda * z);
    EXPECT_NEAR(dr::fresnelSlitIntensity(x, a, lambda, z) / fraunhofer, 1.0, 1e-3) << ua;
  }
}

TEST(FresnelSlit, RejectsBadInput) {
  EXPECT_THROW(dr::fresnelSlitIntensity(0.0, 0.0, 0.01, 1.0), diffray::core::InputError);
  EXPECT_THROW(dr::fresnelSlitIntensity(0.0, 0.2, -0.01, 1.0), diffray::core::InputError);
  EXPECT_THROW(dr::fresnelSlitIntensity(NAN, 0.2, 0.01, 1.0), diffray::core::InputError);
}

// ---- Sommerfeld half-plane -------------------------------------------------------------------------------

TEST(SommerfeldHalfPlane, MatchesCheckValues) {
  // Sommerfeld's solution for a plane wave from direction φ0 on the half-plane φ = 0 (Born & Wolf, §11.5):
  // u = U(φ − φ0) ± U(φ + φ0) (+ rigid, − soft), U(θ) = e^{−ikρ·cos θ}·F(√(2kρ)·cos(θ/2)),
  // F(v) = (e^{−iπ/4}/√π)·∫_{−∞}^v e^{iτ²} dτ = ½ + (e^{−iπ/4}/√π)·∫_0^v e^{iτ²} dτ, and
  // ∫_0^v e^{iτ²} dτ = √(π/2)·∫_0^{v√(2/π)} e^{iπt²/2} dt by the quadrature above. The magnitudes do not
  // depend on the sign convention of time. λ = 1 m, ρ = 3 m, φ0 = 60°, φ = 260° (in the shadow).
  const double k = 2.0 * kPi, rho = 3.0, phi0 = degrees(60), phi = degrees(260);
  const auto part = [&](double theta) {
    const double v = std::sqrt(2.0 * k * rho) * std::cos(0.5 * theta);
    const Complex f = 0.5 + std::polar(1.0 / std::sqrt(kPi), -0.25 * kPi) * std::sqrt(0.5 * kPi) *
                                fresnelBySimpson(v * std::sqrt(2.0 / kPi));
    return std::polar(1.0, -k * rho * std::cos(theta)) * f;
  };
  const double rigid = std::abs(part(phi - phi0) + part(phi + phi0));
  const double soft = std::abs(part(phi - phi0) - part(phi + phi0));
  EXPECT_NEAR(std::abs(dr::sommerfeldHalfPlane(1.0, rho, phi, phi0, true)), rigid, 1e-9);
  EXPECT_NEAR(std::abs(dr::sommerfeldHalfPlane(1.0, rho, phi, phi0, false)), soft, 1e-9);
  EXPECT_NEAR(rigid, 0.27525, 5e-6);  // the same two figures to 5 digits, as readable anchors
  EXPECT_NEAR(soft, 0.18061, 5e-6);
}

TEST(SommerfeldHalfPlane, GeometricalOpticsFarFromTheEdge) {
  const double lambda = 1.0, rho = 2.0e4, k = 2 * kPi / lambda, phi0 = degrees(60);
  const auto incident = [&](double phi) { return std::polar(1.0, k * rho * std::cos(phi - phi0)); };
  const auto reflected = [&](double phi) { return std::polar(1.0, k * rho * std::cos(phi + phi0)); };
  // Edge-diffracted amplitude ~ 1/√(kρ) ≈ 3e-3 here.
  const double tol = 0.01;
  for (bool rigid : {true, false}) {
    const double sign = rigid ? 1.0 : -1.0;
    const double phi_reflect = degrees(90);  // < π − φ0: incident + reflected
    const double phi_lit = degrees(180);     // between π − φ0 and π + φ0: incident only
    const double phi_shadow = degrees(300);  // > π + φ0: shadow
    EXPECT_NEAR(std::abs(dr::sommerfeldHalfPlane(lambda, rho, phi_reflect, phi0, rigid) -
                         (incident(phi_reflect) + sign * reflected(phi_reflect))),
                0.0, tol);
    EXPECT_NEAR(std::abs(dr::sommerfeldHalfPlane(lambda, rho, phi_lit, phi0, rigid) - incident(phi_lit)), 0.0,
                tol);
    EXPECT_NEAR(std::abs(dr::sommerfeldHalfPlane(lambda, rho, phi_shadow, phi0, rigid)), 0.0, tol);
    // On the shadow boundary the field is half the geometric one.
    EXPECT_NEAR(std::abs(dr::sommerfeldHalfPlane(lambda, rho, kPi + phi0, phi0, rigid)), 0.5, tol);
  }
}

TEST(SommerfeldHalfPlane, SatisfiesBoundaryConditionsOnBothFaces) {
  const double lambda = 0.7, phi0 = degrees(35), h = 1e-6;
  for (double rho : {0.05, 0.9, 4.2}) {
    for (double face : {0.0, 2 * kPi}) {
      // Soft (Dirichlet): u = 0 on the screen.
      EXPECT_NEAR(std::abs(dr::sommerfeldHalfPlane(lambda, rho, face, phi0, false)), 0.0, 1e-12);
      // Rigid (Neumann): ∂u/∂φ = 0 on the screen (one-sided difference, second order).
      const double step = face == 0.0 ? h : -h;
      const Complex u0 = dr::sommerfeldHalfPlane(lambda, rho, face, phi0, true);
      const Complex u1 = dr::sommerfeldHalfPlane(lambda, rho, face + step, phi0, true);
      const Complex u2 = dr::sommerfeldHalfPlane(lambda, rho, face + 2 * step, phi0, true);
      const Complex derivative = (-3.0 * u0 + 4.0 * u1 - u2) / (2.0 * h);
      EXPECT_NEAR(std::abs(derivative), 0.0, 1e-5) << rho << " " << face;
    }
  }
  // Reciprocity: swapping source and receiver directions leaves the field unchanged.
  const Complex forward = dr::sommerfeldHalfPlane(1.0, 2.5, degrees(250), degrees(40), true);
  const Complex backward = dr::sommerfeldHalfPlane(1.0, 2.5, degrees(40), degrees(250), true);
  EXPECT_NEAR(std::abs(forward - backward), 0.0, 1e-14);
  EXPECT_THROW(dr::sommerfeldHalfPlane(1.0, 1.0, degrees(400), degrees(40), true), diffray::core::InputError);
  EXPECT_THROW(dr::sommerfeldHalfPlane(1.0, -1.0, degrees(90), degrees(40), true), diffray::core::InputError);
}

// ---- Fraunhofer transforms -------------------------------------------------------------------------------

TEST(Fraunhofer, SlitCentreZerosAndParseval) {
  const double a = 0.3;
  EXPECT_DOUBLE_EQ(dr::slitFraunhofer(0.0, a), a * a);
  for (int m : {1, 2, 5}) EXPECT_NEAR(dr::slitFraunhofer(m / a, a), 0.0, 1e-28);
  EXPECT_DOUBLE_EQ(dr::slitFraunhofer(-1.3, a), dr::slitFraunhofer(1.3, a));
  // ∫|T|² du = ∫|t|² dx = a; the tail beyond |u| = U holds ≈ 1/(π² U).
  const double U = 2000.0;
  const double power = simpson<double>([&](double u) { return dr::slitFraunhofer(u, a); }, -U, U, 4000000);
  EXPECT_NEAR(power + 1.0 / (kPi * kPi * U), a, 1e-6);
}

TEST(Fraunhofer, DoubleAndMultiSlitMatchBruteForceTransform) {
  const double a = 0.1, d = 0.35;
  // T(u) = ∫ t(x) e^{−i2πux} dx by brute force over the openings.
  const auto brute = [](double u, const Openings& openings) {
    Complex t(0.0, 0.0);
    for (const auto& [begin, end] : openings)
      t += simpson<Complex>([u](double x) { return std::polar(1.0, -2 * kPi * u * x); }, begin, end, 2000);
    return std::norm(t);
  };
  const Openings pair = {{-d / 2 - a / 2, -d / 2 + a / 2}, {d / 2 - a / 2, d / 2 + a / 2}};
  Openings triple = pair;
  triple.push_back({-a / 2, a / 2});
  for (double u : {0.0, 0.7, 1.43, 4.0, 11.9}) {
    EXPECT_NEAR(dr::doubleSlitFraunhofer(u, a, d), brute(u, pair), 1e-12) << u;
    EXPECT_NEAR(dr::nSlitFraunhofer(u, a, d, 2), dr::doubleSlitFraunhofer(u, a, d), 1e-14) << u;
    EXPECT_NEAR(dr::nSlitFraunhofer(u, a, d / 2, 3), brute(u, triple), 1e-12) << u;
    EXPECT_DOUBLE_EQ(dr::nSlitFraunhofer(u, a, d, 1), dr::slitFraunhofer(u, a));
  }
  // Double-slit zeros at u = (2j + 1)/(2d); n-slit principal maxima n²a² sinc²(a q/d) at u = q/d.
  EXPECT_NEAR(dr::doubleSlitFraunhofer(1.0 / (2 * d), a, d), 0.0, 1e-30);
  const int n = 7;
  const double z = a * 2 / d;
  const double envelope = std::sin(kPi * z) / (kPi * z);
  EXPECT_NEAR(dr::nSlitFraunhofer(2 / d, a, d, n), n * n * a * a * envelope * envelope, 1e-12);
  // Closed form sin(nπdu)/sin(πdu) away from the maxima.
  const double u = 1.234, ratio = std::sin(n * kPi * d * u) / std::sin(kPi * d * u);
  EXPECT_NEAR(dr::nSlitFraunhofer(u, a, d, n), dr::slitFraunhofer(u, a) * ratio * ratio, 1e-12);
  EXPECT_THROW(dr::nSlitFraunhofer(0.1, a, d, 0), diffray::core::InputError);
}

TEST(Fraunhofer, RectangleIsSeparable) {
  const double a = 0.2, b = 0.05;
  EXPECT_DOUBLE_EQ(dr::rectFraunhofer(0.0, 0.0, a, b), a * a * b * b);
  for (double u : {0.0, 3.3, -7.1})
    for (double v : {0.0, 12.0, 25.5})
      EXPECT_NEAR(dr::rectFraunhofer(u, v, a, b), dr::slitFraunhofer(u, a) * dr::slitFraunhofer(v, b), 1e-18);
  EXPECT_NEAR(dr::rectFraunhofer(1.0 / a, 0.0, a, b), 0.0, 1e-30);
  EXPECT_THROW(dr::rectFraunhofer(0.0, 0.0, a, -b), diffray::core::InputError);
}

TEST(Fraunhofer, ScreenIntensityConservesPowerAndIsParaxialNearAxis) {
  const double a = 0.02, lambda = 0.005, z = 3.0;
  EXPECT_NEAR(dr::screenU(0.4, 0.3, 0.1), 0.8 / 0.1, 1e-12);
  // Paraxial: I ≈ |T(x/λz)|²/(λz) (the Fresnel slit's far field).
  const double x_small = 0.05;
  EXPECT_NEAR(
      dr::farFieldScreenIntensity2D(x_small, z, lambda, dr::slitFraunhofer(x_small / (lambda * z), a)) /
          (dr::slitFraunhofer(x_small / (lambda * z), a) / (lambda * z)),
      1.0, 1e-3);
  // ∫ I dx over the whole line (x = z tanθ) equals the propagating part of ∫|T|² du.
  const auto on_line = [&](double theta) {
    const double x = z * std::tan(theta);
    const double i =
        dr::farFieldScreenIntensity2D(x, z, lambda, dr::slitFraunhofer(dr::screenU(x, z, lambda), a));
    return i * z / (std::cos(theta) * std::cos(theta));
  };
  const double line_power = simpson<double>(on_line, -0.5 * kPi + 1e-9, 0.5 * kPi - 1e-9, 200000);
  const double propagating = simpson<double>([&](double u) { return dr::slitFraunhofer(u, a); },
                                             -1.0 / lambda, 1.0 / lambda, 200000);
  EXPECT_NEAR(line_power / propagating, 1.0, 1e-6);
}

// ---- Sinusoidal phase grating ----------------------------------------------------------------------------

TEST(PhaseGrating, OrderEfficienciesMatchFourierSeriesOfTransmittance) {
  for (double m : {0.0, 0.8, 2.0, 3.7, -2.0}) {
    double total = 0.0;
    for (int q = -40; q <= 40; ++q) {
      // c_q = (1/Λ)∫_0^Λ t(x) e^{−i2πqx/Λ} dx; the trapezoid rule on a period is exact to rounding here.
      const int samples = 256;
      Complex c(0.0, 0.0);
      for (int s = 0; s < samples; ++s) {
        const double phase = 2 * kPi * s / samples;
        c += std::polar(1.0, 0.5 * m * std::sin(phase) - q * phase);
      }
      c /= static_cast<double>(samples);
      EXPECT_NEAR(dr::phaseGratingOrderEfficiency(q, m), std::norm(c), 1e-13) << "m=" << m << " q=" << q;
      EXPECT_DOUBLE_EQ(dr::phaseGratingOrderEfficiency(-q, m), dr::phaseGratingOrderEfficiency(q, m));
      total += dr::phaseGratingOrderEfficiency(q, m);
    }
    EXPECT_NEAR(total, 1.0, 1e-13) << m;  // energy conservation of a pure phase grating
  }
  EXPECT_NEAR(dr::phaseGratingOrderEfficiency(1, 2.0), 0.4400505857449335 * 0.4400505857449335, 1e-15);
}

// ---- 2D Rayleigh–Sommerfeld ------------------------------------------------------------------------------

TEST(RayleighSommerfeld2D, FarFieldMatchesFraunhofer) {
  // Property (a): at z = 2000 a²/λ, |U|² = |T(sinθ/λ)|²·cos²θ/(λr) within 0.1 % (observed: ~1e-7).
  const double lambda = 1.0, a = 10.0, z = 2000.0 * a * a / lambda;
  const Openings slit = {{-a / 2, a / 2}};
  for (double ua : {0.0, 0.3, 0.7, 1.5, 2.4}) {
    const double sin_theta = ua * lambda / a;
    const double x = z * sin_theta / std::sqrt(1.0 - sin_theta * sin_theta);
    const double far =
        dr::farFieldScreenIntensity2D(x, z, lambda, dr::slitFraunhofer(dr::screenU(x, z, lambda), a));
    EXPECT_NEAR(dr::rayleighSommerfeldIntensity2D(slit, x, z, lambda) / far, 1.0, 1e-5) << ua;
  }
  // Double slit, oblique incidence: the pattern shifts to u = (sinθ − sinθi)/λ.
  const double d = 25.0, sin_i = 0.2, z2 = 2000.0 * (d + a) * (d + a) / lambda;
  const Openings pair = {{-d / 2 - a / 2, -d / 2 + a / 2}, {d / 2 - a / 2, d / 2 + a / 2}};
  for (double offset_u : {0.0, 0.01, 0.07}) {
    const double sin_theta = sin_i + offset_u * lambda;
    const double x = z2 * sin_theta / std::sqrt(1.0 - sin_theta * sin_theta);
    const double far = dr::farFieldScreenIntensity2D(x, z2, lambda, dr::doubleSlitFraunhofer(offset_u, a, d));
    EXPECT_NEAR(dr::rayleighSommerfeldIntensity2D(pair, x, z2, lambda, sin_i) / far, 1.0, 1e-5) << offset_u;
  }
}

TEST(RayleighSommerfeld2D, WideOpeningTransmitsThePlaneWave) {
  // Property (b): 200 λ wide, X = 0, z = 5 λ: |U|² ≈ 1 up to the Fresnel-edge ripple; the phase is e^{ikz}.
  const double lambda = 1.0, z = 5.0, k = 2 * kPi / lambda;
  const Openings wide = {{-100.0, 100.0}};
  EXPECT_NEAR(dr::rayleighSommerfeldIntensity2D(wide, 0.0, z, lambda), 1.0, 0.1);
  EXPECT_NEAR(std::abs(dr::rayleighSommerfeld2D(wide, 0.0, z, lambda) - std::polar(1.0, k * z)), 0.0, 0.05);
  // Oblique incidence: U ≈ the incident wave exp(ik(X sinθi + z cosθi)).
  const double sin_i = 0.5, X = 7.3;
  const Complex incident = std::polar(1.0, k * (X * sin_i + z * std::sqrt(1.0 - sin_i * sin_i)));
  EXPECT_NEAR(std::abs(dr::rayleighSommerfeld2D(wide, X, z, lambda, sin_i) - incident), 0.0, 0.05);
}

TEST(RayleighSommerfeld2D, ReproducesTheApertureFieldAtTheScreen) {
  // z → 0: U → U0(X) (1 inside an opening, 0 on the opaque part); the kernel is then a Poisson kernel of
  // width z, so this exercises the graded panels around the foot point.
  const double lambda = 1.0, z = 1e-4;
  const Openings slit = {{-3.0, 3.0}};
  EXPECT_NEAR(std::abs(dr::rayleighSommerfeld2D(slit, 0.4, z, lambda) - 1.0), 0.0, 2e-3);
  EXPECT_NEAR(std::abs(dr::rayleighSommerfeld2D(slit, 4.0, z, lambda)), 0.0, 2e-3);
  EXPECT_NEAR(std::abs(dr::rayleighSommerfeld2D(slit, 3.0, z, lambda)), 0.5, 2e-3);  // edge: half
}

TEST(RayleighSommerfeld2D, QuadratureIsConvergedAndSymmetric) {
  // Splitting an opening at arbitrary points changes every panel; the sum must not move.
  const double lambda = 0.37, z = 1.9;
  const Openings whole = {{-2.0, 3.1}};
  const Openings split = {{-2.0, -0.713}, {-0.713, 1.2345}, {1.2345, 3.1}};
  for (double X : {-4.0, 0.0, 0.5, 2.9, 6.0}) {
    const Complex u_whole = dr::rayleighSommerfeld2D(whole, X, z, lambda, 0.3);
    const Complex u_split = dr::rayleighSommerfeld2D(split, X, z, lambda, 0.3);
    EXPECT_NEAR(std::abs(u_whole - u_split) / std::abs(u_whole), 0.0, 1e-9) << X;
  }
  // A symmetric opening at normal incidence gives a symmetric field.
  const Openings slit = {{-1.5, 1.5}};
  EXPECT_NEAR(std::abs(dr::rayleighSommerfeld2D(slit, 0.8, z, lambda) -
                       dr::rayleighSommerfeld2D(slit, -0.8, z, lambda)),
              0.0, 1e-12);
}

TEST(RayleighSommerfeld2D, AgreesWithFresnelSlitInTheParaxialRegime) {
  // a = 20 λ, z = 100 λ: Fresnel number 4, paraxial phase error k a⁴/(128 z³) ≈ 0.008 rad.
  const double lambda = 1.0, a = 20.0, z = 100.0;
  const Openings slit = {{-a / 2, a / 2}};
  for (double x : {0.0, 4.0, 9.0, 12.0}) {
    EXPECT_NEAR(dr::rayleighSommerfeldIntensity2D(slit, x, z, lambda),
                dr::fresnelSlitIntensity(x, a, lambda, z), 0.02)
        << x;
  }
}

TEST(RayleighSommerfeld2D, ConservesPowerCloseBehindAWideOpening) {
  // Property (c): ∫|U|² dX across a long line at small z ≈ the opening width (power through the opening).
  const double lambda = 1.0, a = 20.0, z = 2.0;
  const Openings slit = {{-a / 2, a / 2}};
  const double half_line = a / 2 + 60.0;  // reaches θ ≈ 88° from the edges
  const double step = lambda / 4;         // the trapezoid sum of this smooth pattern has converged here
  double flux = 0.0;
  for (int i = 0; i * step <= 2 * half_line + 1e-9; ++i) {
    const double weight = (i == 0 || i * step > 2 * half_line - 1e-9) ? 0.5 * step : step;
    flux += weight * dr::rayleighSommerfeldIntensity2D(slit, -half_line + i * step, z, lambda);
  }
  EXPECT_NEAR(flux / a, 1.0, 0.03);
  // Sharper: what is missing is the evanescent part |u| > 1/λ of ∫|T|² du (≈ 1/π² for a wide slit), so the
  // flux matches the propagating power of the Fraunhofer pattern.
  const double propagating =
      simpson<double>([&](double u) { return dr::slitFraunhofer(u, a); }, -1.0 / lambda, 1.0 / lambda, 20000);
  EXPECT_NEAR(flux / propagating, 1.0, 2e-3);
}

TEST(RayleighSommerfeld2D, RejectsBadInput) {
  const Openings slit = {{-1.0, 1.0}};
  EXPECT_THROW(dr::rayleighSommerfeld2D(slit, 0.0, 0.0, 1.0), diffray::core::InputError);
  EXPECT_THROW(dr::rayleighSommerfeld2D(slit, 0.0, -1.0, 1.0), diffray::core::InputError);
  EXPECT_THROW(dr::rayleighSommerfeld2D(slit, 0.0, 1.0, 0.0), diffray::core::InputError);
  EXPECT_THROW(dr::rayleighSommerfeld2D({{1.0, -1.0}}, 0.0, 1.0, 1.0), diffray::core::InputError);
  EXPECT_THROW(dr::rayleighSommerfeld2D(slit, 0.0, 1.0, 1.0, 1.5), diffray::core::InputError);
  EXPECT_EQ(dr::rayleighSommerfeld2D({}, 0.0, 1.0, 1.0), Complex(0.0, 0.0));
}

// ---- Propagating field (angular spectrum) -------------------------------------------------------------------
// Far from the screen the evanescent part has died out, so |U_p|² must equal the Rayleigh–Sommerfeld
// |U|² (an independent quadrature over the aperture with Hankel functions). Near the screen they differ:
// the value at 125 Hz, 2 m behind a 0.9 m opening, was computed separately by a 40000-point midpoint rule
// of the same angular-spectrum integral (Python, double precision): 0.15906 at X = 0.
TEST(PropagatingField, EqualsRayleighSommerfeldFarFromTheScreen) {
  const std::vector<std::pair<double, double>> door{{-0.45, 0.45}};
  const double lambda = 0.05;
  for (double x : {0.0, 0.3, 0.8, 2.0}) {
    const double rs = diffray::reference::rayleighSommerfeldIntensity2D(door, x, 60.0 * lambda, lambda);
    const double prop = diffray::reference::propagatingIntensity2D(door, x, 60.0 * lambda, lambda);
    EXPECT_NEAR(prop, rs, 2e-4 * std::max(rs, 0.05)) << "x = " << x;
  }
}

TEST(PropagatingField, MissesTheEvanescentNearFieldWithinAWavelength) {
  const std::vector<std::pair<double, double>> door{{-0.45, 0.45}};
  const double lambda = 331.3 * std::sqrt(1.0 + 20.0 / 273.15) / 125.0;
  const double prop = diffray::reference::propagatingIntensity2D(door, 0.0, 2.0, lambda);
  const double rs = diffray::reference::rayleighSommerfeldIntensity2D(door, 0.0, 2.0, lambda);
  EXPECT_NEAR(prop, 0.15906, 2e-4);
  EXPECT_GT(std::abs(prop - rs), 0.05 * rs);  // z = 0.73 λ: the evanescent part matters here
}
