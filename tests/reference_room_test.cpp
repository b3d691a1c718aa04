// Tests of the room-acoustics references (reference/room_acoustics.h, reference/image_lattice.h) against
// things independent of them: a brute-force recursive mirroring of the source across the six walls,
// distances worked out by hand, lattice counting, decay-metric values evaluated by hand, hand-computed Sabine
// and Eyring times, numerical quadrature, and the asymptotic density of image sources.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/image_lattice.h"
#include "diffray/reference/room_acoustics.h"

namespace dr = diffray::reference;

namespace {

constexpr double kPi = 3.14159265358979323846;

// An asymmetric room, source and receiver, 3 bands with different wall factors and air.
dr::Shoebox testBox() {
  dr::Shoebox box;
  box.dims_m = {5.1, 3.7, 2.9};
  box.source_m = {1.3, 2.2, 0.7};
  box.receiver_m = {3.9, 0.8, 2.1};
  box.reflection_energy = {std::vector<double>{0.9, 0.8, 0.7}, {0.95, 0.6, 0.5}, {0.85, 0.75, 0.65},
                           {0.99, 0.9, 0.4},                   {0.7, 0.5, 0.3},   {0.8, 0.85, 0.9}};
  box.air_m_per_m = {0.0, 0.002, 0.01};
  box.c_m_s = 343.0;
  return box;
}

// Brute force: mirror every image of order k across each of the six wall planes (x = 0 → −x,
// x = L → 2L − x), breadth first, keeping the first (lowest-order) copy of each position.
struct Mirrored {
  std::array<double, 3> position;
  std::array<int, 6> hits;
  int order;
};
std::vector<Mirrored> mirrorRecursively(const dr::Shoebox& box, int max_order) {
  const auto key = [](const std::array<double, 3>& p) {
    return std::make_tuple(std::llround(p[0] * 1e6), std::llround(p[1] * 1e6), std::llround(p[2] * 1e6));
  };
  std::map<std::tuple<long long, long long, long long>, Mirrored> seen;
  std::vector<Mirrored> level{{box.source_m, {0, 0, 0, 0, 0, 0}, 0}};
  seen[key(box.source_m)] = level[0];
  for (int order = 1; order <= max_order; ++order) {
    std::vector<Mirrored> next;
    for (const Mirrored& m : level) {
      for (int wall = 0; wall < 6; ++wall) {
        const int axis = wall / 2;
        Mirrored r = m;
        r.position[axis] = wall % 2 == 0 ? -m.position[axis] : 2.0 * box.dims_m[axis] - m.position[axis];
        ++r.hits[wall];
        r.order = order;
        if (seen.emplace(key(r.position), r).second) next.push_back(r);
      }
    }
    level = next;
  }
  std::vector<Mirrored> out;
  for (const auto& kv : seen) out.push_back(kv.second);
  return out;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Lattice points with |l| + |m| + |n| <= N, counted one by one.
long long latticePointsWithin(int n_max) {
  long long count = 0;
  for (int l = -n_max; l <= n_max; ++l)
    for (int m = -n_max; m <= n_max; ++m)
      for (int n = -n_max; n <= n_max; ++n) count += std::abs(l) + std::abs(m) + std::abs(n) <= n_max;
  return count;
}

}  // namespace

// ---- image sources ---------------------------------------------------------------------------------------

TEST(ShoeboxImages, MatchRecursiveMirroringUpToOrderFour) {
  const dr::Shoebox box = testBox();
  const std::vector<Mirrored> brute = mirrorRecursively(box, 4);
  const std::vector<dr::ImageArrival> images = dr::shoeboxImages(box, 4, dr::kAnyDistance);
  ASSERT_EQ(images.size(), brute.size());
  // Match every brute-force image to the lattice image at the same position (each exactly once).
  std::vector<bool> used(images.size(), false);
  for (const Mirrored& m : brute) {
    int found = -1;
    for (std::size_t i = 0; i < images.size(); ++i)
      if (distance(images[i].position_m, m.position) < 1e-9) found = static_cast<int>(i);
    ASSERT_GE(found, 0) << "no lattice image at " << m.position[0] << ", " << m.position[1] << ", " << m.position[2];
    ASSERT_FALSE(used[found]);
    used[found] = true;
    const dr::ImageArrival& a = images[found];
    EXPECT_EQ(a.order, m.order);
    EXPECT_EQ(a.hits, m.hits);
    const double d = distance(m.position, box.receiver_m);
    EXPECT_NEAR(a.distance_m, d, 1e-12 * d);
    EXPECT_NEAR(a.delay_s, d / box.c_m_s, 1e-15);
    for (int b = 0; b < 3; ++b) {
      double e = std::exp(-box.air_m_per_m[b] * d) / (d * d);
      for (int w = 0; w < 6; ++w) e *= std::pow(box.reflection_energy[w][b], m.hits[w]);
      EXPECT_NEAR(a.energy[b], e, 1e-13 * e);
    }
  }
}

TEST(ShoeboxImages, CountIsTheOctahedralNumber) {
  // Images of order <= N are the lattice points with |l| + |m| + |n| <= N: 1 + Σ_{k=1..N} (4k² + 2)
  // = (2N + 1)(2N² + 2N + 3)/3 (k: 4k² + 2 points on the surface |·|₁ = k). Checked against counting.
  const dr::Shoebox box = testBox();
  for (int n = 0; n <= 10; ++n) {
    const long long closed = (2LL * n + 1) * (2LL * n * n + 2LL * n + 3) / 3;
    EXPECT_EQ(closed, latticePointsWithin(n)) << n;
    const std::vector<dr::ImageArrival> images = dr::shoeboxImages(box, n, dr::kAnyDistance);
    EXPECT_EQ(static_cast<long long>(images.size()), closed) << n;
    // No image twice.
    std::vector<std::array<int, 3>> cells;
    for (const auto& a : images) cells.push_back(a.lattice);
    std::sort(cells.begin(), cells.end());
    EXPECT_EQ(std::adjacent_find(cells.begin(), cells.end()), cells.end()) << n;
  }
}

TEST(ShoeboxImages, FirstOrderDistancesByHand) {
  // 10 × 7 × 3 m, source (2, 3, 1.5), receiver (7, 3, 1.5): direct 5 m; images at x = −2 (9 m), x = 18
  // (11 m), y = −3 (√(25 + 36)), y = 11 (√(25 + 64)), z = −1.5 and z = 4.5 (√(25 + 9) each).
  dr::Shoebox box;
  box.dims_m = {10, 7, 3};
  box.source_m = {2, 3, 1.5};
  box.receiver_m = {7, 3, 1.5};
  const double beta[6] = {0.9, 0.8, 0.7, 0.6, 0.5, 0.4};
  for (int w = 0; w < 6; ++w) box.reflection_energy[w] = {beta[w]};
  box.air_m_per_m = {0.001};
  box.c_m_s = 340.0;
  const std::vector<dr::ImageArrival> images = dr::shoeboxImages(box, 1, dr::kAnyDistance);
  ASSERT_EQ(images.size(), 7u);
  const double expected[7] = {5.0, 9.0, 11.0, std::sqrt(61.0), std::sqrt(89.0), std::sqrt(34.0), std::sqrt(34.0)};
  for (const auto& a : images) {
    int slot = 0;  // 0 direct, 1 + wall index otherwise
    for (int w = 0; w < 6; ++w)
      if (a.hits[w] == 1) slot = 1 + w;
    EXPECT_NEAR(a.distance_m, expected[slot], 1e-12) << slot;
    const double d = expected[slot];
    const double e = (slot == 0 ? 1.0 : beta[slot - 1]) * std::exp(-0.001 * d) / (d * d);
    EXPECT_NEAR(a.energy[0], e, 1e-15) << slot;
  }
  // Order 0 is the direct sound: 1 W → e^{−m r}/r² at r, arriving at r/c; sorted first.
  EXPECT_EQ(images[0].order, 0);
  EXPECT_NEAR(images[0].energy[0], std::exp(-0.005) / 25.0, 1e-16);
  EXPECT_NEAR(images[0].delay_s, 5.0 / 340.0, 1e-16);
  EXPECT_DOUBLE_EQ(images[0].energy[0], dr::freeFieldEnergy(5.0, 0.001));
}

TEST(ShoeboxImages, DistanceLimitKeepsExactlyTheImagesWithin) {
  // Both limits at once and each alone: the distance-limited set is the order-limited set (taken large
  // enough to hold every image within D) filtered by distance.
  const dr::Shoebox box = testBox();
  const double d_max = 20.0;
  const auto by_distance = dr::shoeboxImages(box, dr::kAnyOrder, d_max);
  const auto by_order = dr::shoeboxImages(box, 12, dr::kAnyDistance);  // order 12 images are > 20 m away
  std::vector<std::array<int, 3>> a, b;
  for (const auto& i : by_distance) a.push_back(i.lattice);
  for (const auto& i : by_order)
    if (i.distance_m <= d_max) b.push_back(i.lattice);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  const auto both = dr::shoeboxImages(box, 3, d_max);
  for (const auto& i : both) EXPECT_TRUE(i.order <= 3 && i.distance_m <= d_max);
  std::size_t expected = 0;
  for (const auto& i : by_distance) expected += i.order <= 3;
  EXPECT_EQ(both.size(), expected);
}

TEST(ShoeboxHistogram, TotalsEqualTheImageSumBinByBin) {
  const dr::Shoebox box = testBox();
  const double bin_s = 0.001, length_s = 0.1;
  const auto hist = dr::shoeboxEnergyHistogram(box, bin_s, length_s);
  ASSERT_EQ(hist.size(), 3u);
  ASSERT_EQ(hist[0].size(), 100u);
  const auto images = dr::shoeboxImages(box, dr::kAnyOrder, box.c_m_s * length_s);
  std::vector<std::vector<double>> expected(3, std::vector<double>(100, 0.0));
  for (const auto& a : images) {
    const auto bin = static_cast<std::size_t>(a.delay_s / bin_s);
    if (bin < 100)
      for (int b = 0; b < 3; ++b) expected[b][bin] += a.energy[b];
  }
  for (int b = 0; b < 3; ++b) {
    double total = 0.0, expected_total = 0.0;
    for (std::size_t i = 0; i < 100; ++i) {
      EXPECT_NEAR(hist[b][i], expected[b][i], 1e-12 * expected[b][i]) << b << " " << i;
      total += hist[b][i];
      expected_total += expected[b][i];
    }
    EXPECT_NEAR(total, expected_total, 1e-12 * expected_total);
  }
  // The order limit of the histogram drops exactly the higher orders.
  const auto hist2 = dr::shoeboxEnergyHistogram(box, bin_s, length_s, 2);
  double sum2 = 0.0, expected2 = 0.0;
  for (double e : hist2[1]) sum2 += e;
  for (const auto& a : images) expected2 += a.order <= 2 ? a.energy[1] : 0.0;
  EXPECT_NEAR(sum2, expected2, 1e-12 * expected2);
}

TEST(ShoeboxHistogram, RigidRoomTendsToTheImageDensity) {
  // Rigid walls, no air: images fill space with density 1/V (one per copy of the room), each giving
  // 1/d², so a bin [t, t + Δ] receives on average 4π(ct)²·cΔ/V · 1/(ct)² = 4πcΔ/V. Over 100 ms late
  // windows the lattice's graininess averages out to well under 1 % (shell volume ≫ cell volume).
  dr::Shoebox box = testBox();
  for (auto& beta : box.reflection_energy) beta = {1.0};
  box.air_m_per_m = {0.0};
  const double volume = box.dims_m[0] * box.dims_m[1] * box.dims_m[2];
  const double bin_s = 0.001;
  const auto hist = dr::shoeboxEnergyHistogram(box, bin_s, 0.4);
  double late = 0.0;
  for (std::size_t i = 300; i < 400; ++i) late += hist[0][i];
  const double expected = 100 * 4.0 * kPi * box.c_m_s * bin_s / volume;
  EXPECT_NEAR(late / expected, 1.0, 0.01);
}

TEST(ShoeboxHistogram, CompleteShoeboxSetIsFast) {
  // design: 10 × 7 × 3 m, 1.5 s, 8 bands, 1 ms bins, every image within c·1.5 s (≈ 2.7e6 images).
  dr::Shoebox box;
  box.dims_m = {10, 7, 3};
  box.source_m = {2.0, 3.5, 1.2};
  box.receiver_m = {7.5, 2.0, 1.6};
  for (auto& beta : box.reflection_energy) beta.assign(8, 0.9);
  box.air_m_per_m.assign(8, 0.001);
  const auto start = std::chrono::steady_clock::now();
  const auto hist = dr::shoeboxEnergyHistogram(box, 0.001, 1.5);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("10 x 7 x 3 m shoebox, 1.5 s, 8 bands: %.3f s\n", seconds);
  RecordProperty("seconds", std::to_string(seconds));
  ASSERT_EQ(hist.size(), 8u);
  EXPECT_GT(hist[7][1499], 0.0);
  EXPECT_LT(seconds, 5.0);  // ~0.2 s on the 2-core machine; generous for a loaded one
}

TEST(ShoeboxImages, RejectsBadInput) {
  dr::Shoebox box = testBox();
  EXPECT_THROW(dr::shoeboxImages(box, dr::kAnyOrder, dr::kAnyDistance), diffray::core::InputError);
  EXPECT_THROW(dr::shoeboxImages(box, -1, 10.0), diffray::core::InputError);
  dr::Shoebox outside = box;
  outside.receiver_m[1] = 3.7;  // on the wall
  EXPECT_THROW(dr::shoeboxImages(outside, 2, dr::kAnyDistance), diffray::core::InputError);
  dr::Shoebox same = box;
  same.receiver_m = same.source_m;
  EXPECT_THROW(dr::shoeboxImages(same, 2, dr::kAnyDistance), diffray::core::InputError);
  dr::Shoebox bands = box;
  bands.reflection_energy[4].pop_back();
  EXPECT_THROW(dr::shoeboxImages(bands, 2, dr::kAnyDistance), diffray::core::InputError);
  dr::Shoebox beta = box;
  beta.reflection_energy[0][0] = 1.5;
  EXPECT_THROW(dr::shoeboxImages(beta, 2, dr::kAnyDistance), diffray::core::InputError);
  EXPECT_THROW(dr::shoeboxEnergyHistogram(box, 0.001, 1e6), diffray::core::InputError);  // ~1e17 images
}

// ---- closed forms ----------------------------------------------------------------------------------------

TEST(RoomAcoustics, SabineAndEyringByHand) {
  // 10 × 7 × 3 m: V = 210 m³, S = 242 m², ᾱ = 0.1 (A = 24.2 m²). By hand (Python):
  // Sabine 0.161·210/24.2 = 1.3971074; with m = 0.001/m (4mV = 0.84) 1.3502396;
  // Eyring 0.161·210/(242·(−ln 0.9)) = 1.3260256; with air 1.2837334;
  // exact constant 24 ln10/343 = 0.16111383: Sabine 1.3980952, Eyring 1.3269631.
  const auto areas = dr::shoeboxWallAreas({10, 7, 3});
  double surface = 0.0;
  for (double a : areas) surface += a;
  EXPECT_DOUBLE_EQ(surface, 242.0);
  EXPECT_DOUBLE_EQ(areas[4], 70.0);  // floor
  EXPECT_NEAR(dr::sabineT(210, 24.2, 0.0), 1.3971074, 1e-7);
  EXPECT_NEAR(dr::sabineT(210, 24.2, 0.001), 1.3502396, 1e-7);
  EXPECT_NEAR(dr::eyringT(210, 242, 0.1, 0.0), 1.3260256, 1e-7);
  EXPECT_NEAR(dr::eyringT(210, 242, 0.1, 0.001), 1.2837334, 1e-7);
  EXPECT_NEAR(dr::sabineT(210, 24.2, 0.0, 343.0), 1.3980952, 1e-7);
  EXPECT_NEAR(dr::eyringT(210, 242, 0.1, 0.0, 343.0), 1.3269631, 1e-7);
  EXPECT_NEAR(dr::kSixtyDbConstant, 24.0 * std::log(10.0), 1e-13);
  EXPECT_EQ(dr::eyringT(210, 242, 1.0, 0.0), 0.0);
}

TEST(RoomAcoustics, EyringTendsToSabineForSmallAbsorption) {
  // T_E/T_S = ᾱ/(−ln(1 − ᾱ)) = 1 − ᾱ/2 − ᾱ²/12 − …
  for (double alpha : {1e-2, 1e-3, 1e-4}) {
    const double ratio = dr::eyringT(210, 242, alpha, 0.0) / dr::sabineT(210, 242 * alpha, 0.0);
    EXPECT_NEAR(ratio, 1.0 - alpha / 2.0 - alpha * alpha / 12.0, alpha * alpha * alpha) << alpha;
  }
}

TEST(RoomAcoustics, ExponentialDecayMetricsMatchHandValues) {
  // The closed forms evaluated by hand (values quoted to the digits given).
  const dr::ExponentialDecayMetrics one = dr::exponentialDecayMetrics(1.0);
  EXPECT_NEAR(one.c80_db, 3.0534, 0.5e-4);
  EXPECT_NEAR(one.c50_db, -0.0206, 0.5e-4);
  EXPECT_NEAR(one.d50, 0.49881, 0.5e-5);
  EXPECT_NEAR(one.ts_s, 0.07238, 0.5e-5);
  EXPECT_EQ(one.t30_s, 1.0);
  const dr::ExponentialDecayMetrics half = dr::exponentialDecayMetrics(0.5);
  EXPECT_NEAR(half.c80_db, 9.0956, 0.5e-4);
  EXPECT_NEAR(half.d50, 0.74881, 0.5e-5);
}

TEST(RoomAcoustics, ReceiverSphereReadings) {
  // Hit fraction by hand: R = 1, r = 2: (1 − √0.75)/2 = 0.0669872981; small spheres: R²/(4r²).
  EXPECT_NEAR(dr::sphereHitFraction(1.0, 2.0), 0.0669872981, 1e-10);
  EXPECT_NEAR(dr::sphereHitFraction(0.01, 10.0), 0.25e-6, 1e-13);
  EXPECT_NEAR(dr::sphereCrossSectionReading(0.01, 10.0), 1e-2 * (1.0 + 0.25e-6), 1e-12);
  // Volume mean of 1/d² by brute-force quadrature over the ball (ρ, μ = cos θ about the sphere's centre,
  // source on the axis at distance r): (3/(4πR³))·∫∫ 2π ρ² / (r² + ρ² − 2rρμ) dμ dρ, midpoint rule.
  for (const auto& [R, r] : {std::pair{0.3, 2.0}, std::pair{1.0, 1.9}, std::pair{0.5, 1.0}}) {
    const int n = 2000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double rho = (i + 0.5) * R / n;
      for (int j = 0; j < n; ++j) {
        const double mu = -1.0 + (j + 0.5) * 2.0 / n;
        sum += 2.0 * kPi * rho * rho / (r * r + rho * rho - 2.0 * r * rho * mu);
      }
    }
    const double quadrature = sum * (R / n) * (2.0 / n) * 3.0 / (4.0 * kPi * R * R * R);
    EXPECT_NEAR(dr::sphereMeanInverseSquare(R, r), quadrature, 2e-4 * quadrature) << R << " " << r;
  }
  // Continuity where the implementation changes from the series to the closed form (q = R/r = 0.5).
  EXPECT_NEAR(dr::sphereMeanInverseSquare(0.5 - 1e-9, 1.0), dr::sphereMeanInverseSquare(0.5 + 1e-9, 1.0), 1e-7);
  EXPECT_THROW(dr::sphereHitFraction(2.0, 1.0), diffray::core::InputError);
}
