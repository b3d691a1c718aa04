// Energy bookkeeping of the signed-energy tracer: every ray's energy ends in exactly one fate, and the
// expected screen, evanescent and absorbed energies equal sums over the WBSDF table's own cell masses
// (transport_fixtures.h), within tolerances derived from the estimator's variance.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "chi2.h"
#include "transport_fixtures.h"
#include "diffray/core/math.h"
#include "diffray/core/parallel.h"
#include "diffray/geometry/frame.h"
#include "diffray/receiver/screen.h"
#include "diffray/transport/scene.h"
#include "diffray/transport/tracer.h"
#include "diffray/wbsdf/microstructure.h"
#include "diffray/wbsdf/table.h"

namespace dw = diffray::wbsdf;
namespace dtr = diffray::transport;
namespace dg = diffray::geometry;
namespace dt = diffray::testing;
using namespace diffray::testing;  // fixtures

// ---- Energy ------------------------------------------------------------------------------------------------

// A fully open occluder (W = δ(u): one line of mass 1 at u' = 0, so every ray keeps weight 1) with a source
// window smaller than the opening, and a screen catching the straight beam: the screen holds exactly the
// source power (power = intensity·area·cosθ = 3·(4 mm)²), nothing is lost, and every fate adds up (1e-9
// relative: summation round-off only).
TEST(TransportEnergy, FullyOpenOccluderDeliversThePowerExactly) {
  dtr::Scene scene;
  dtr::Occluder occ;
  occ.frame = frameAt(Vec3(0, 0, 0));
  occ.half_x_m = occ.half_y_m = 1e-2;
  occ.table_x = deltaTable(-5e-3, 5e-3, 0.0);
  scene.addOccluder(occ);
  diffray::receiver::Screen screen;
  screen.frame = frameAt(Vec3(0, 0, 0.1));
  screen.half_x_m = screen.half_y_m = 1e-2;
  scene.addScreen(screen);
  scene.build();
  dtr::CollimatedSource src;
  src.frame = frameAt(Vec3(0, 0, -0.05));
  src.half_x_m = src.half_y_m = 2e-3;
  src.wavelength_m = 0.5e-6;
  src.intensity = 3.0;
  const double power = 3.0 * 4e-3 * 4e-3;
  ASSERT_NEAR(src.power(), power, 1e-15 * power);
  dtr::TraceOptions opt;
  opt.rays = 50000;
  opt.seed = 5;
  const dtr::TraceResult r = dtr::trace(scene, src, opt);
  EXPECT_EQ(r.rays, opt.rays);
  EXPECT_NEAR(r.emitted, power, 1e-12 * power);
  EXPECT_NEAR(total(r.screens[0]), power, 1e-9 * power);
  EXPECT_EQ(r.absorbed, 0.0);
  EXPECT_EQ(r.evanescent, 0.0);
  EXPECT_EQ(r.escaped, 0.0);
  EXPECT_EQ(r.on_absorbers, 0.0);
  EXPECT_EQ(r.bounce_limit, 0.0);
  EXPECT_NEAR(fates(r), r.emitted, 1e-9 * power);
  EXPECT_EQ(r.segments, 2 * opt.rays);  // occluder, then screen
}

// Two facing mirrors (reflecting δ occluders at z = ±0.1) around the source trap every ray: after
// max_bounces segments its whole energy goes to bounce_limit, and the progress callback saw every ray.
TEST(TransportEnergy, TrappedRaysEndAtTheBounceLimit) {
  dtr::Scene scene;
  for (double z : {-0.1, 0.1}) {
    dtr::Occluder mirror;
    mirror.frame = frameAt(Vec3(0, 0, z));
    mirror.half_x_m = mirror.half_y_m = 0.05;
    mirror.table_x = deltaTable(-0.05, 0.05, 0.0);
    mirror.reflect = true;
    scene.addOccluder(mirror);
  }
  scene.build();
  dtr::CollimatedSource src;
  src.frame = frameAt(Vec3(0, 0, 0));
  src.half_x_m = src.half_y_m = 0.01;
  src.wavelength_m = 1e-6;
  const double power = src.power();
  std::atomic<std::uint64_t> progress{0};
  dtr::TraceOptions opt;
  opt.rays = 5000;
  opt.max_bounces = 7;
  opt.on_progress = [&](std::uint64_t n) { progress += n; };
  const dtr::TraceResult r = dtr::trace(scene, src, opt);
  EXPECT_NEAR(r.bounce_limit, power, 1e-9 * power);
  EXPECT_NEAR(fates(r), r.emitted, 1e-9 * power);
  EXPECT_EQ(r.escaped, 0.0);
  EXPECT_EQ(r.segments, 7 * opt.rays);
  EXPECT_EQ(progress.load(), opt.rays);
}

// The same δ occluder with weight-1 rays, but the window (x ∈ [−2, 2] mm) is wider than the open row
// (x ∈ [−1, 1] mm: the rest is opaque), an absorber covers x ∈ [0.5, 1.5] mm behind it and the screen
// x ∈ [−2, 0] mm: fractions 1/2 absorbed, 1/8 on the absorber, 1/4 on the screen, 1/8 escaped (x ∈ [0,
// 0.5] mm). Every ray is weight 1, so each fate's total is power·(binomial fraction): standard error
// power·√(p(1−p)/N) for plain Monte Carlo; 5 of them (two-sided normal tail 6e-7). Randomised QMC
// (the default) is unbiased and its error for these interval indicators in the first coordinate is
// O(log N/N), far inside the same bound. The fates sum to the emitted power exactly (1e-9).
TEST(StatTransportEnergy, FatesSplitByGeometry) {
  dtr::Scene scene;
  dtr::Occluder occ;
  occ.frame = frameAt(Vec3(0, 0, 0));
  occ.half_x_m = occ.half_y_m = 5e-3;
  occ.table_x = deltaTable(-1e-3, 1e-3, 0.0);
  scene.addOccluder(occ);
  dtr::Absorber ab;
  ab.frame = frameAt(Vec3(1e-3, 0, 0.05));
  ab.half_x_m = 0.5e-3;
  ab.half_y_m = 5e-3;
  scene.addAbsorber(ab);
  diffray::receiver::Screen screen;
  screen.frame = frameAt(Vec3(-1e-3, 0, 0.1));
  screen.half_x_m = 1e-3;
  screen.half_y_m = 5e-3;
  scene.addScreen(screen);
  scene.build();
  dtr::CollimatedSource src;
  src.frame = frameAt(Vec3(0, 0, -0.1));
  src.half_x_m = 2e-3;
  src.half_y_m = 1e-3;
  src.wavelength_m = 1e-6;
  const double power = src.power();
  for (bool qmc : {false, true}) {
    dtr::TraceOptions opt;
    opt.rays = 200000;
    opt.seed = qmc ? 77 : 78;
    opt.qmc = qmc;
    const dtr::TraceResult r = dtr::trace(scene, src, opt);
    const double n = static_cast<double>(opt.rays);
    const auto check = [&](double got, double p, const char* what) {
      const double se = power * std::sqrt(p * (1 - p) / n);
      EXPECT_NEAR(got, p * power, 5 * se) << what << " qmc=" << qmc;
    };
    check(r.absorbed, 0.5, "absorbed");
    check(r.on_absorbers, 0.125, "on absorbers");
    check(total(r.screens[0]), 0.25, "screen");
    check(r.escaped, 0.125, "escaped");
    EXPECT_EQ(r.evanescent, 0.0);
    EXPECT_NEAR(fates(r), r.emitted, 1e-9 * power);
    EXPECT_NEAR(r.emitted, power, 1e-12 * power);
  }
}

// A wide slit (a = 200λ, TableOptions{λ}: signed sinc-shaped rows) lit at normal incidence through a window
// smaller than the opening, a one-bin screen 1 mm behind and 1 m wide (it catches every propagating shift up
// to sinθ_max = 1/√(1 + z²) ≈ 1 − 5e-7; the rays between that and grazing escape. sinθ_max moves by ~1e-10
// over the window, which shifts < 1e-10 of the power: neglected). Expected screen energy and evanescent energy
// come from the table's masses (fateMoments: independent sums over cells, propagating iff |λu'| < sinθ_max),
// standard errors from the per-ray second moments (plain Monte Carlo: Var(total) = N(E[X²] − E[X]²)),
// tolerance 5 standard errors. The screen then holds the source power within those errors plus the small
// signed mass the table puts outside the propagating range.
TEST(StatTransportEnergy, WideSlitScreenAndEvanescentMatchTableMasses) {
  const double lambda = 1e-6, a = 200 * lambda, z = 1e-3;
  const auto table = dw::WbsdfTable::build(*dw::Openings::slit(a), optionsFor(lambda));
  dtr::Scene scene;
  dtr::Occluder occ;
  occ.frame = frameAt(Vec3(0, 0, 0));
  occ.half_x_m = 2 * a;
  occ.half_y_m = 1.0;
  occ.table_x = table;
  scene.addOccluder(occ);
  diffray::receiver::Screen screen;
  screen.frame = frameAt(Vec3(0, 0, z));
  screen.half_x_m = 1.0;
  screen.half_y_m = 1.0;
  scene.addScreen(screen);
  scene.build();
  dtr::CollimatedSource src;
  src.frame = frameAt(Vec3(0, 0, -0.01));
  src.half_x_m = 0.4 * a;
  src.half_y_m = 1e-3;
  src.wavelength_m = lambda;
  const double power = src.power();
  dtr::TraceOptions opt;
  opt.rays = 400000;
  opt.seed = 11;
  opt.qmc = false;
  const dtr::TraceResult r = dtr::trace(scene, src, opt);
  const double n = static_cast<double>(opt.rays), e0 = power / n;

  const double s_max = 1.0 / std::sqrt(1.0 + z * z);  // landing within 1 m of the axis
  const auto onScreen = [&](double u1, double u2) {
    return overlap(u1, u2, -s_max / lambda, s_max / lambda) / (u2 - u1);
  };
  const auto evanescent = [&](double u1, double u2) {
    return (overlap(u1, u2, 1.0 / lambda, 1e300) + overlap(u1, u2, -1e300, -1.0 / lambda)) / (u2 - u1);
  };
  const auto all = [](double, double) { return 1.0; };
  const double w1 = -0.4 * a, w2 = 0.4 * a;
  const auto [m_scr, s_scr] = fateMoments(*table, w1, w2, onScreen);
  const auto [m_ev, s_ev] = fateMoments(*table, w1, w2, evanescent);
  const auto [m_all, s_all] = fateMoments(*table, w1, w2, all);
  const double se_scr = e0 * std::sqrt(n * (s_scr - m_scr * m_scr));
  const double se_ev = e0 * std::sqrt(n * (s_ev - m_ev * m_ev));
  const double se_all = e0 * std::sqrt(n * (s_all - m_all * m_all));
  EXPECT_NEAR(total(r.screens[0]), power * m_scr, 5 * se_scr);
  EXPECT_NEAR(r.evanescent, power * m_ev, 5 * se_ev);
  EXPECT_NEAR(fates(r), power * m_all, 5 * se_all);  // every ray's signed energy lands in some fate
  EXPECT_EQ(r.absorbed, 0.0);                           // the window lies inside the opening
  // The chunk-scatter standard error the tally reports agrees with the derived one. With K chunk totals
  // (sums of ≥ 10⁴ rays each, so nearly normal), (K − 1)·(SE_tally/SE)² ~ χ²_{K−1}: both tails at 5e-4.
  const double k_chunks = static_cast<double>(r.screens[0].chunks);
  ASSERT_GE(k_chunks, 8.0);
  const double ratio = r.screens[0].standardError(0) / se_scr;
  const double upper_tail = dt::chiSquareSurvival((k_chunks - 1) * ratio * ratio, static_cast<int>(k_chunks) - 1);
  EXPECT_GT(upper_tail, 0.5 * dt::kChi2Alpha) << "SE ratio " << ratio << " over " << k_chunks << " chunks";
  EXPECT_LT(upper_tail, 1.0 - 0.5 * dt::kChi2Alpha) << "SE ratio " << ratio << " over " << k_chunks << " chunks";
  // Energy is conserved on average: the screen holds the power up to the table's non-propagating mass.
  EXPECT_NEAR(total(r.screens[0]), power, 5 * se_scr + power * std::abs(1.0 - m_scr));
  EXPECT_LT(std::abs(1.0 - m_scr), 0.02);
}

// ---- Evanescent energy -------------------------------------------------------------------------------------
// A slit of width λ/2 at normal and oblique incidence (sinθ_i = 0.3, u_i = 0.3/λ): the traced evanescent energy over
// the emitted energy must be the table's signed mass with |u_i + u'| > 1/λ, averaged over where the rays hit
// (the window covers [−a, a]; rows outside the slit absorb), computed here cell by cell (fateMoments).
// Plain Monte Carlo: standard error from the per-ray second moment. Randomised QMC (the default): 16
// independent replicates (seeds), standard error from their scatter; 5 standard errors (Student t, 15 dof:
// two-sided tail 1.6e-4).
TEST(StatTransportEnergy, EvanescentFractionMatchesTableMass) {
  const double lambda = 1e-6, a = 0.5 * lambda;
  const auto table = dw::WbsdfTable::build(*dw::Openings::slit(a), optionsFor(lambda));
  dtr::Scene scene;
  dtr::Occluder occ;
  occ.frame = frameAt(Vec3(0, 0, 0));
  occ.half_x_m = 1e-3;
  occ.half_y_m = 1e-2;
  occ.table_x = table;
  scene.addOccluder(occ);
  diffray::receiver::Screen screen;
  screen.frame = frameAt(Vec3(0, 0, 0.01));
  screen.half_x_m = screen.half_y_m = 1.0;
  scene.addScreen(screen);
  scene.build();
  std::uint64_t seed = 21;
  for (double sin_i : {0.0, 0.3}) {
    const Vec3 dir(sin_i, 0.0, std::sqrt(1.0 - sin_i * sin_i));
    const double gap = 1e-4;  // source plane to occluder
    dtr::CollimatedSource src;
    src.frame = frameAt(Vec3(-gap * dir.x() / dir.z(), 0, -gap));  // hits centred on x = 0
    src.half_x_m = a;
    src.half_y_m = 1e-3;
    src.dir = dir;
    src.wavelength_m = lambda;
    const double power = src.power();
    const double u_i = sin_i / lambda;
    const auto evanescent = [&](double u1, double u2) {
      return (overlap(u1, u2, 1.0 / lambda - u_i, 1e300) + overlap(u1, u2, -1e300, -1.0 / lambda - u_i)) /
             (u2 - u1);
    };
    const auto [m_ev, s_ev] = fateMoments(*table, -a, a, evanescent);
    ASSERT_GT(m_ev, 0.05) << sin_i;  // a λ/2 slit sends a good part of its energy into evanescent waves

    // Plain Monte Carlo.
    {
      dtr::TraceOptions opt;
      opt.rays = 400000;
      opt.seed = seed++;
      opt.qmc = false;
      const dtr::TraceResult r = dtr::trace(scene, src, opt);
      const double n = static_cast<double>(opt.rays);
      const double se = std::sqrt((s_ev - m_ev * m_ev) / n);  // of the fraction evanescent/emitted
      EXPECT_NEAR(r.evanescent / r.emitted, m_ev, 5 * se) << "sinθ_i=" << sin_i;
      EXPECT_NEAR(r.emitted, power, 1e-12 * power);
    }
    // Randomised QMC replicates.
    {
      const int reps = 16;
      std::vector<double> frac;
      for (int k = 0; k < reps; ++k) {
        dtr::TraceOptions opt;
        opt.rays = 40000;
        opt.seed = seed++;
        const dtr::TraceResult r = dtr::trace(scene, src, opt);
        frac.push_back(r.evanescent / r.emitted);
      }
      double mean = 0.0;
      for (double f : frac) mean += f / reps;
      double var = 0.0;
      for (double f : frac) var += (f - mean) * (f - mean) / (reps - 1);
      EXPECT_NEAR(mean, m_ev, 5 * std::sqrt(var / reps)) << "sinθ_i=" << sin_i << " (QMC)";
    }
  }
}

