// The angle-impact WBSDF (wbsdf/angle_impact.h). Oracles written here:
//  * its u-marginal: ∫ W̃(x₀,u) dx₀ = cosθ·|T(u)|², the z-directed power of each plane wave, with
//    T(u) = a·sinc(au) for a slit (closed form);
//  * paraxial limit: for a slit many wavelengths wide, near u = 0 the rows approach the slit's Wigner
//    distribution 2(a − 2|x|)·sinc(2u(a − 2|x|)) averaged over the cell (wbsdf_fixtures.h quadrature);
//  * traced through the real transport (door-rs, --model angle-impact), the screen matches the
//    propagating-field oracle of diffray::reference (angular-spectrum quadrature) within 5 chunk standard
//    errors per bin plus 1e-3 of the peak (the table's cell blur, as in validate_cases_test.cpp).
// Tolerances of the deterministic checks: the table drops the band-limited field's tails beyond a 4λ margin
// (amplitude ≲ 1/(8π²) there, so ≲ 1e-3 of the power) and interpolates W_AI linearly on a b grid of
// λ/(16 cos θ): 2e-3 of the column peak covers both.
#include <gtest/gtest.h>

#include <cmath>

#include "diffray/validate/case.h"
#include "diffray/wbsdf/angle_impact.h"
#include "diffray/wbsdf/microstructure.h"
#include "wbsdf_fixtures.h"

namespace dw = diffray::wbsdf;

namespace {
double sincPi(double z) { return std::abs(z) < 1e-12 ? 1.0 : std::sin(M_PI * z) / (M_PI * z); }
}  // namespace

TEST(AngleImpactTable, ColumnsCarryTheZDirectedPowerOfEachPlaneWave) {
  const double a = 0.9, lambda = 0.343;
  const auto slit = dw::Openings::slit(a);
  dw::AngleImpactOptions o;
  o.wavelength_m = lambda;
  o.x_lo_m = -0.5 * a;
  o.x_hi_m = 0.5 * a;
  o.nu = 64;
  o.nx = 128;
  const auto table = dw::angleImpactTable([&](double u) { return dw::openingsSpectrum(*slit, u); }, o);
  const auto& L = table->layout();
  double peak = 0.0;
  std::vector<double> expected(L.nu), got(L.nu, 0.0);
  for (int k = 0; k < L.nu; ++k) {
    // ∫_cell cosθ·a²sinc²(au) du by a 64-point midpoint rule.
    double e = 0.0;
    for (int m = 0; m < 64; ++m) {
      const double u = L.u0_per_m + (k + (m + 0.5) / 64.0) * L.du_per_m;
      e += std::sqrt(std::max(0.0, 1.0 - lambda * lambda * u * u)) * a * a * std::pow(sincPi(a * u), 2) *
           L.du_per_m / 64.0;
    }
    expected[k] = e;
    for (int j = 0; j < L.nx; ++j) got[k] += table->mass(j, k) * L.dx_m;
    peak = std::max(peak, e);
  }
  for (int k = 0; k < L.nu; ++k) EXPECT_NEAR(got[k], expected[k], 2e-3 * peak) << "column " << k;
}

TEST(AngleImpactTable, ApproachesTheWignerDistributionParaxially) {
  const double a = 0.02, lambda = 1e-4;  // a = 200 λ: near u = 0 the field is paraxial
  const auto slit = dw::Openings::slit(a);
  dw::AngleImpactOptions o;
  o.wavelength_m = lambda;
  o.x_lo_m = -0.5 * a;
  o.x_hi_m = 0.5 * a;
  o.u_half_range_per_m = 40.0 / a;
  o.nu = 320;
  o.nx = 64;
  const auto table = dw::angleImpactTable([&](double u) { return dw::openingsSpectrum(*slit, u); }, o);
  const auto& L = table->layout();
  for (int j : {L.nx / 4, L.nx / 2, 3 * L.nx / 4}) {
    const double x1 = L.x0_m + j * L.dx_m;
    for (int k = L.nu / 2 - 20; k < L.nu / 2 + 20; ++k) {
      const double u1 = L.u0_per_m + k * L.du_per_m;
      // The rect's closed-form WDF, x-averaged and u-integrated by the tests' own Gauss–Legendre rule.
      const double wigner =
          diffray::testing::quad(
              [&](double x) {
                return diffray::testing::quad([&](double u) { return diffray::testing::rectWdf(x, u, a); }, u1,
                                              u1 + L.du_per_m, 2);
              },
              x1, x1 + L.dx_m, 4) /
          L.dx_m;
      EXPECT_NEAR(table->mass(j, k), wigner, 2e-3 * 2.0 * a * L.du_per_m) << "row " << j << " col " << k;
    }
  }
}

TEST(StatAngleImpact, DoorMatchesThePropagatingFieldExactly) {
  const auto* info = diffray::validate::findCase("door-rs");
  ASSERT_NE(info, nullptr);
  diffray::validate::RunOptions ro;
  ro.rays = 2'000'000;
  ro.seed = 99;
  ro.model = "angle-impact";
  const auto r = info->run(diffray::validate::resolveParams(*info, {{"freq", {125, 1000}}}), ro);
  std::map<std::string, double> peak;
  for (const auto& row : r.rows) peak[row.label] = std::max(peak[row.label], row.alt_reference);
  for (const auto& row : r.rows)
    EXPECT_LE(std::abs(row.traced - row.alt_reference), 5.0 * row.std_error + 1e-3 * peak[row.label])
        << row.label << " x = " << row.x_m;
}
