// Tests of the exact point-source half-plane reference (reference/half_plane_point.h). The
// oracles share nothing with the closed form under test: Sommerfeld's plane-wave solution and its
// check values (the far-source limit), the Helmholtz equation and the boundary conditions by finite
// differences, geometrical acoustics far from the edge, and the frequency-domain edge-source (BTM)
// integral of Svensson et al. evaluated by quadrature here.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "diffray/core/error.h"
#include "diffray/reference/fresnel.h"
#include "diffray/reference/half_plane_point.h"
#include "reference_fixtures.h"

namespace dr = diffray::reference;
using Complex = std::complex<double>;
using dr::CylindricalPoint;
using diffray_test::gauss8;

namespace {

constexpr double kPi = 3.14159265358979323846;

double degrees(double deg) { return deg * kPi / 180.0; }

double distance(const CylindricalPoint& a, const CylindricalPoint& b) {
  return std::hypot(a.rho_m * std::cos(a.phi_rad) - b.rho_m * std::cos(b.phi_rad),
                    a.rho_m * std::sin(a.phi_rad) - b.rho_m * std::sin(b.phi_rad), a.z_m - b.z_m);
}

Complex freeField(double k, double r) { return std::polar(1.0 / r, -k * r); }

// Geometrical field of the half-plane (the frame of half_plane_point.h): the direct wave where the source
// is visible (|φ − φ0| < π) and the wave reflected by the face φ = 0 (φ + φ0 < π) or φ = 2π
// (φ + φ0 > 3π), with the reflection coefficient +1 (rigid) or −1 (soft).
Complex geometricField(double k, const CylindricalPoint& s, const CylindricalPoint& r, bool rigid) {
  Complex u(0.0, 0.0);
  if (std::abs(r.phi_rad - s.phi_rad) < kPi) u += freeField(k, distance(s, r));
  const double sum = r.phi_rad + s.phi_rad;
  if (sum < kPi || sum > 3.0 * kPi) {
    const CylindricalPoint image{s.rho_m, -s.phi_rad, s.z_m};
    u += (rigid ? 1.0 : -1.0) * freeField(k, distance(image, r));
  }
  return u;
}

// Edge-diffracted field of an infinite wedge with exterior angle θ_W = π/ν, frequency-domain edge-source
// integral (Svensson, Andersson & Vanderkooy 1999; Svensson, Calamia & Nakamura 2009), time factor e^{+iωt}:
//   u_d = −(ν/4π) ∫ β(z) e^{−ik(m + l)}/(m·l) dz,  β = Σ_i s_i sin(νθ_i)/(cosh(νη) − cos(νθ_i)),
//   θ_i = π ± θ_S ± θ_R,  cosh η = ((z − z_S)(z − z_R) + m·l)/(ρ_S ρ_R),
// m, l the distances from the edge point (0, 0, z) to the source and the receiver. s_i = +1 for a rigid
// wedge; a soft one flips the two terms with θ_S + θ_R (the image terms). Here ν = ½ (half-plane),
// integrated over |z − z_apex| < 60 m in 8-point panels of λ/8 (the tail beyond, ~√(ρ_Sρ_R)/(2kZ³), is
// ~1e-6 of the free field here).
Complex edgeSourceDiffraction(double wavelength, const CylindricalPoint& s, const CylindricalPoint& r,
                              bool rigid) {
  const double nu = 0.5, k = 2.0 * kPi / wavelength;
  const double theta[4] = {kPi + s.phi_rad + r.phi_rad, kPi + s.phi_rad - r.phi_rad,
                           kPi - s.phi_rad + r.phi_rad, kPi - s.phi_rad - r.phi_rad};
  const double sign[4] = {rigid ? 1.0 : -1.0, 1.0, 1.0, rigid ? 1.0 : -1.0};
  auto integrand = [&](double z) {
    const double m = std::hypot(s.rho_m, z - s.z_m), l = std::hypot(r.rho_m, z - r.z_m);
    const double cosh_eta = ((z - s.z_m) * (z - r.z_m) + m * l) / (s.rho_m * r.rho_m);
    const double eta = std::acosh(std::max(1.0, cosh_eta));
    double beta = 0.0;
    for (int i = 0; i < 4; ++i)
      beta += sign[i] * std::sin(nu * theta[i]) / (std::cosh(nu * eta) - std::cos(nu * theta[i]));
    return beta * std::polar(1.0 / (m * l), -k * (m + l));
  };
  const double apex = s.z_m + (r.z_m - s.z_m) * s.rho_m / (s.rho_m + r.rho_m);
  const double half_span = 60.0, panel = wavelength / 8.0;
  const int panels = static_cast<int>(std::ceil(half_span / panel));
  Complex sum(0.0, 0.0);
  for (int j = 0; j < panels; ++j) {
    sum += gauss8(integrand, apex + j * panel, apex + (j + 1) * panel);
    sum += gauss8(integrand, apex - (j + 1) * panel, apex - j * panel);
  }
  return -nu / (4.0 * kPi) * sum;
}

}  // namespace

TEST(HalfPlanePointSource, FarSourceTendsToSommerfeldPlaneWave) {
  // Source at ρ0 = 1e6 m: u·ρ0·e^{ikρ0} → Sommerfeld's plane-wave field, up to O(ρ/ρ0) = 3e-6.
  const double lambda = 1.0, k = 2.0 * kPi / lambda, rho0 = 1e6;
  const CylindricalPoint source{rho0, degrees(60.0), 0.0};
  const CylindricalPoint receiver{3.0, degrees(260.0), 0.0};
  for (bool rigid : {true, false}) {
    const Complex u = dr::halfPlanePointSource(lambda, source, receiver, rigid) * std::polar(rho0, k * rho0);
    const Complex plane = dr::sommerfeldHalfPlane(lambda, 3.0, degrees(260.0), degrees(60.0), rigid);
    EXPECT_NEAR(std::abs(u - plane), 0.0, 2e-5) << rigid;
    EXPECT_NEAR(std::abs(u), rigid ? 0.27525 : 0.18061, 1e-5) << "Sommerfeld half-plane check value, rigid " << rigid;
  }
  // A sweep across both boundaries, and a receiver off the source's z: the plane wave then travels at
  // elevation, which this limit does not cover, so z stays 0 here.
  for (double phi_deg : {10.0, 100.0, 119.0, 121.0, 200.0, 239.0, 241.0, 300.0, 355.0}) {
    const CylindricalPoint r{2.0, degrees(phi_deg), 0.0};
    for (bool rigid : {true, false}) {
      const Complex u = dr::halfPlanePointSource(lambda, source, r, rigid) * std::polar(rho0, k * rho0);
      const Complex plane = dr::sommerfeldHalfPlane(lambda, 2.0, degrees(phi_deg), degrees(60.0), rigid);
      EXPECT_NEAR(std::abs(u - plane), 0.0, 2e-5) << phi_deg << " rigid " << rigid;
    }
  }
}

TEST(HalfPlanePointSource, MatchesTheEdgeSourceIntegral) {
  // Total = geometrical field + BTM edge diffraction, at points in the reflection zone, the lit zone and
  // the shadow, source and receiver at different heights along the edge.
  const double lambda = 0.5;
  const CylindricalPoint source{1.5, degrees(40.0), 0.2};
  for (double phi_deg : {100.0, 190.0, 250.0, 320.0}) {
    const CylindricalPoint receiver{2.0, degrees(phi_deg), -0.7};
    for (bool rigid : {true, false}) {
      const double k = 2.0 * kPi / lambda;
      const Complex exact = dr::halfPlanePointSource(lambda, source, receiver, rigid);
      const Complex oracle =
          geometricField(k, source, receiver, rigid) + edgeSourceDiffraction(lambda, source, receiver, rigid);
      const double free = 1.0 / distance(source, receiver);
      EXPECT_NEAR(std::abs(exact - oracle) / free, 0.0, 2e-6) << phi_deg << "° rigid " << rigid;
    }
  }
}

TEST(HalfPlanePointSource, SatisfiesHelmholtzAndTheBoundaryConditions) {
  const double lambda = 0.7, k = 2.0 * kPi / lambda;
  const CylindricalPoint source{1.2, degrees(75.0), 0.3};
  // ∇²u + k²u = 0 by a fourth-order Cartesian stencil, h = λ/100 (truncation ~ (kh)⁴/90 = 2e-7).
  const double h = lambda / 100.0;
  for (double phi_deg : {30.0, 150.0, 254.0, 300.0}) {
    const double x = 1.7 * std::cos(degrees(phi_deg)), y = 1.7 * std::sin(degrees(phi_deg)), z = -0.4;
    auto u = [&](double dx, double dy, double dz) {
      return dr::halfPlanePointSource(lambda, dr::halfPlaneFrameFromCartesian(x + dx, y + dy, z + dz), source,
                                      true);
    };
    const Complex centre = u(0, 0, 0);
    Complex laplacian = -3.0 * 30.0 * centre;
    for (int axis = 0; axis < 3; ++axis) {
      auto at = [&](double t) { return u(axis == 0 ? t : 0, axis == 1 ? t : 0, axis == 2 ? t : 0); };
      laplacian += -(at(2 * h) + at(-2 * h)) + 16.0 * (at(h) + at(-h));
    }
    laplacian /= 12.0 * h * h;
    EXPECT_LT(std::abs(laplacian + k * k * centre) / (k * k * std::abs(centre)), 1e-5) << phi_deg;
  }
  // Soft: u = 0 on both faces. Rigid: ∂u/∂φ = 0 there, so u(δ) − u(0) = O(δ²): quartering with δ halved.
  for (double face_rad : {0.0, 2.0 * kPi}) {
    const double inward = face_rad == 0.0 ? 1.0 : -1.0;
    const CylindricalPoint on{1.1, face_rad, -0.2};
    EXPECT_LT(std::abs(dr::halfPlanePointSource(lambda, source, on, false)), 1e-13);
    auto step = [&](double delta) {
      const CylindricalPoint off{1.1, face_rad + inward * delta, -0.2};
      return std::abs(dr::halfPlanePointSource(lambda, source, off, true) -
                      dr::halfPlanePointSource(lambda, source, on, true));
    };
    EXPECT_NEAR(step(1e-3) / step(2e-3), 0.25, 0.01) << face_rad;
  }
}

TEST(HalfPlanePointSource, ReciprocityAndContinuityAcrossBoundaries) {
  const double lambda = 0.3;
  const CylindricalPoint a{0.8, degrees(50.0), 1.0}, b{2.5, degrees(280.0), -0.5};
  for (bool rigid : {true, false})
    EXPECT_NEAR(std::abs(dr::halfPlanePointSource(lambda, a, b, rigid) -
                         dr::halfPlanePointSource(lambda, b, a, rigid)),
                0.0, 1e-15);
  // The shadow boundary φ = π + φ0 and the reflection boundary φ = π − φ0: the total field is continuous
  // (the geometrical field jumps by a whole free-field wave there).
  for (double boundary_deg : {230.0, 130.0}) {
    for (bool rigid : {true, false}) {
      const double eps = 1e-9;
      const CylindricalPoint before{2.5, degrees(boundary_deg) - eps, -0.5};
      const CylindricalPoint after{2.5, degrees(boundary_deg) + eps, -0.5};
      const Complex jump = dr::halfPlanePointSource(lambda, a, before, rigid) -
                           dr::halfPlanePointSource(lambda, a, after, rigid);
      EXPECT_LT(std::abs(jump) * distance(a, before), 1e-5) << boundary_deg;
    }
  }
}

TEST(HalfPlanePointSource, GeometricalAcousticsFarFromTheEdgeAndHalfAtTheShadowBoundary) {
  // kρ ~ 1e4: the diffracted wave is O(1/σ) with σ = √(k(R1 − R)) the Fresnel parameter; its asymptotic
  // amplitude (1/(2√π|σ|))/R per branch, computed here from Cartesian distances, bounds the deviation.
  const double lambda = 1e-3, k = 2.0 * kPi / lambda;
  const CylindricalPoint source{2.0, degrees(40.0), 0.1};
  auto diffractionBound = [&](const CylindricalPoint& r, bool direct_branch) {
    const CylindricalPoint image{source.rho_m, -source.phi_rad, source.z_m};
    const double via_edge = std::hypot(source.rho_m + r.rho_m, source.z_m - r.z_m);
    double bound = 0.0;
    for (int branch = direct_branch ? 0 : 1; branch < 2; ++branch) {
      const double d = distance(branch == 0 ? source : image, r);
      bound += 1.0 / (2.0 * std::sqrt(kPi) * std::sqrt(k * (via_edge - d)) * d);
    }
    return 1.5 * bound;
  };
  for (double phi_deg : {60.0, 110.0, 180.0, 200.0, 260.0, 330.0}) {  // reflection, lit, shadow zones
    const CylindricalPoint r{3.0, degrees(phi_deg), -0.3};
    for (bool rigid : {true, false}) {
      const Complex u = dr::halfPlanePointSource(lambda, source, r, rigid);
      EXPECT_LT(std::abs(u - geometricField(k, source, r, rigid)), diffractionBound(r, true)) << phi_deg;
    }
  }
  // On the shadow boundary φ = π + φ0 the direct branch is exactly half the free field (σ = 0), so the
  // diffracted field is −½ of the geometric field on the lit side; the image branch adds O(1/σ₊).
  const CylindricalPoint boundary{3.0, degrees(220.0), -0.3};
  for (bool rigid : {true, false}) {
    const Complex u = dr::halfPlanePointSource(lambda, source, boundary, rigid);
    const Complex half = 0.5 * freeField(k, distance(source, boundary));
    EXPECT_LT(std::abs(u - half), diffractionBound(boundary, false)) << rigid;
  }
}

TEST(HalfPlanePointSource, LevelsAndBandAverage) {
  const CylindricalPoint source{1.0, degrees(30.0), 0.0}, receiver{2.0, degrees(250.0), 0.5};
  const double c = 343.0, lambda = c / 1000.0;
  const double r = distance(source, receiver);
  const Complex u = dr::halfPlanePointSource(lambda, source, receiver, true);
  EXPECT_NEAR(dr::halfPlaneLevelDb(lambda, source, receiver, true), 20.0 * std::log10(std::abs(u) * r),
              1e-12);
  // Band average by hand over the midpoint grid.
  const double lo = 707.0, hi = 1414.0;
  const int n = 7;
  const double by_hand = diffray_test::bandLevelByHandDb(
      lo, hi, n, [&](double f) {
        return std::norm(dr::halfPlanePointSource(c / f, source, receiver, true) * r);
      });
  EXPECT_NEAR(dr::halfPlaneBandLevelDb(lo, hi, n, c, source, receiver, true), by_hand, 1e-12);
  EXPECT_NEAR(dr::halfPlaneBandLevelDb(1000.0, 1000.0, 1, c, source, receiver, true),
              dr::halfPlaneLevelDb(lambda, source, receiver, true), 1e-12);
}

TEST(HalfPlanePointSource, FrameFromCartesian) {
  const CylindricalPoint p = dr::halfPlaneFrameFromCartesian(0.0, -2.0, 1.5);
  EXPECT_NEAR(p.rho_m, 2.0, 1e-15);
  EXPECT_NEAR(p.phi_rad, 1.5 * kPi, 1e-15);
  EXPECT_EQ(p.z_m, 1.5);
  EXPECT_EQ(dr::halfPlaneFrameFromCartesian(1.0, 0.0, 0.0).phi_rad, 0.0);
  EXPECT_NEAR(dr::halfPlaneFrameFromCartesian(1.0, -0.0, 0.0).phi_rad, 2.0 * kPi, 1e-15);
  EXPECT_NEAR(dr::halfPlaneFrameFromCartesian(-1.0, 0.0, 0.0).phi_rad, kPi, 1e-15);
}

TEST(HalfPlanePointSource, RejectsBadInput) {
  using diffray::core::InputError;
  const CylindricalPoint ok{1.0, 1.0, 0.0}, other{2.0, 4.0, 0.0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(dr::halfPlanePointSource(0.0, ok, other, true), InputError);
  EXPECT_THROW(dr::halfPlanePointSource(nan, ok, other, true), InputError);
  EXPECT_THROW(dr::halfPlanePointSource(1.0, {-1.0, 1.0, 0.0}, other, true), InputError);
  EXPECT_THROW(dr::halfPlanePointSource(1.0, ok, {1.0, 7.0, 0.0}, true), InputError);
  EXPECT_THROW(dr::halfPlanePointSource(1.0, ok, {1.0, nan, 0.0}, true), InputError);
  EXPECT_THROW(dr::halfPlanePointSource(1.0, ok, ok, true), InputError);
  EXPECT_THROW(dr::halfPlaneBandLevelDb(500.0, 250.0, 10, 343.0, ok, other, true), InputError);
  EXPECT_THROW(dr::halfPlaneBandLevelDb(250.0, 500.0, 0, 343.0, ok, other, true), InputError);
  EXPECT_THROW(dr::halfPlaneBandLevelDb(250.0, 500.0, 10, -1.0, ok, other, true), InputError);
  EXPECT_THROW(dr::halfPlaneFrameFromCartesian(nan, 0.0, 0.0), InputError);
}

TEST(HalfPlanePointSource, FarFromTheBoundariesMatchesKellerDiffraction) {
  // Keller's GTD for a point source, source and receiver in one plane normal to the edge (Kouyoumjian–Pathak
  // UTD with the transition function 1): u_d = D·e^{−ik(ρ + ρ0)}/√(ρρ0(ρ + ρ0)),
  // D = −e^{−iπ/4}/(2√(2πk))·[sec((φ − φ0)/2) ± sec((φ + φ0)/2)]. Its error is O(1/(kρ·cos²)) relative to
  // u_d, < 2e-3 at these angles for λ = 1 mm. (The popular Fresnel-integral form with √(k(R1 − R)), exact
  // only for a plane wave, misses this amplitude by a factor √(R1(R1 + R)/2)/R: 3–4 dB in a barrier's
  // deep shadow.)
  const double lambda = 1e-3, k = 2.0 * kPi / lambda;
  const CylindricalPoint source{2.0, degrees(80.0), 0.0};
  for (double phi_deg : {30.0, 200.0, 290.0, 330.0}) {
    const CylindricalPoint receiver{3.0, degrees(phi_deg), 0.0};
    for (bool rigid : {true, false}) {
      const double secants = 1.0 / std::cos(0.5 * (receiver.phi_rad - source.phi_rad)) +
                             (rigid ? 1.0 : -1.0) / std::cos(0.5 * (receiver.phi_rad + source.phi_rad));
      const Complex d = -std::polar(1.0, -0.25 * kPi) / (2.0 * std::sqrt(2.0 * kPi * k)) * secants;
      const double rho = receiver.rho_m, rho0 = source.rho_m;
      const Complex keller = d * std::polar(1.0 / std::sqrt(rho * rho0 * (rho + rho0)), -k * (rho + rho0));
      const Complex total = dr::halfPlanePointSource(lambda, source, receiver, rigid);
      const Complex diffracted = total - geometricField(k, source, receiver, rigid);
      EXPECT_LT(std::abs(diffracted - keller), 5e-3 * std::abs(keller)) << phi_deg << " rigid " << rigid;
    }
  }
}

TEST(HalfPlanePointSource, QuadratureMatchesMpmathValues) {
  // The rigid field at ρ = 2 m, z = −0.7 m for a source at (1.5 m, 40°, 0.2 m): mpmath (30 digits,
  // tanh-sinh quadrature of the same contour integral) at the shadow boundary + 1e-6 rad and − 0.1°, just
  // inside the reflection boundary, in the shadow, at λ = 1 mm and 20 m, and on the face φ = 0.
  const CylindricalPoint source{1.5, degrees(40.0), 0.2};
  const double table[][4] = {
      {0.5, 3.8397253543875250692, 0.0046944052023261473, -0.15898878551062039},
      {0.5, 3.8379790251355307397, 0.0051785539983321105, -0.15939109240167611},
      {0.5, 2.4433609527920614077, -0.090137273306049598, 0.2136583701535275},
      {0.5, 5.2359877559829887308, -0.024649615205840739, -0.036110474479990283},
      {0.001, 4.3633231299858239423, 0.0038731442632247728, 0.00031438007519583263},
      {20.0, 4.3633231299858239423, 0.050757391730120269, -0.18925516093249815},
      {0.5, 0.0, 0.8377464424373939, -0.94832719438419588},
  };
  for (const auto& row : table) {
    const Complex u = dr::halfPlanePointSource(row[0], source, {2.0, row[1], -0.7}, true);
    EXPECT_LT(std::abs(u - Complex(row[2], row[3])), 1e-13) << row[0] << " " << row[1];
  }
}
