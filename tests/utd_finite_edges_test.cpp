// UTD on finite edges (utd/paths.h, "Finite edges"). Oracles, sharing no code with utd/: the BTM edge-source
// integral of one finite edge of a half-plane (reference/btm_edge.h) for the wave through a plate's top edge,
// with its apex on the edge, near an end and beyond it (the corner's wave); and the BTM reference of the
// whole 4 × 2 m plate to second order, alone and standing on a rigid ground (reference/btm_spectrum.h), at the
// listeners of rooms/screen.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "diffray/reference/btm_edge.h"
#include "diffray/reference/btm_spectrum.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/paths.h"
#include "utd_fixtures.h"

namespace {

using namespace utd_fixtures;

constexpr double kTwoPi = 6.28318530717958647692;

// The 4 × 2 m plate y = 0, x in [−2, 2], z in [0, 2], optionally on a 60 × 60 m rigid ground z = 0.
dr::Room plateScene(bool ground) {
  dr::Room room;
  const int m = rigidMaterial(room);
  if (ground) addPlate(room, Vec3(-30, -30, 0), Vec3(60, 0, 0), Vec3(0, 60, 0), m);
  addPlate(room, Vec3(-2, 0, 0), Vec3(4, 0, 0), Vec3(0, 0, 2), m);
  room.sources.push_back({"S", Vec3(0, -2, 0.5), 1.0, {}});
  return room;
}

// 10·log10 of the mean of |p|² over `points` frequencies at the midpoints of equal parts of the octave.
template <class Pressure>
double octaveEnergy(double centre_hz, int points, Pressure p) {
  const double lo = centre_hz / std::sqrt(2.0), hi = centre_hz * std::sqrt(2.0);
  double sum = 0.0;
  for (int j = 0; j < points; ++j) sum += std::norm(p(lo + (j + 0.5) * (hi - lo) / points));
  return sum / points;
}

}  // namespace

TEST(UtdFiniteEdges, TopEdgeOfAPlateIsTheBtmIntegralOverTheFiniteEdge) {
  // The wave through the top edge (y = 0, z = 2, x in [−2, 2]) of the free plate, source (0, −2, 0.5),
  // listeners (x, 2, 1) deep in its shadow: the apex x·2.5/(2.5 + √5) moves from the middle of the edge
  // past its end at x = 2 (listener x = 3.79) to 1.2 m beyond it. BTM frame of the edge: z along +x, the face
  // θ = 0 towards −z (into the plate), θ from it towards +y. Octave-band levels 125 Hz–4 kHz within 1 dB;
  // without the finite-edge factor the wave near the end is up to 6 dB high and beyond it missing.
  const Vec3 s(0, -2, 0.5);
  const auto frame = [](const Vec3& p) {
    const double u = 2.0 - p.z(), v = p.y();  // along the face, and across it
    double theta = std::atan2(v, u);
    if (theta < 0.0) theta += kTwoPi;
    return ref::CylindricalPoint{std::hypot(u, v), theta, p.x()};
  };
  const ref::BtmWedge edge{kTwoPi, -2.0, 2.0};
  const dr::Room room = plateScene(false);
  const diffray::transport::RoomGeometry geometry(room);
  double worst = 0.0, worst_infinite = 0.0;
  for (bool finite : {true, false}) {
    utd::UtdOptions o;
    o.max_order = 1;
    o.finite_edges = finite;
    const utd::UtdModel model(room, geometry, o);
    for (double x : {0.0, 1.5, 3.0, 3.6, 4.0, 4.6}) {
      const Vec3 r(x, 2.0, 1.0);
      std::vector<utd::Path> top;
      for (const auto& p : model.paths(s, r))
        if (p.kind == utd::PathKind::Diffraction && std::abs(model.edges()[p.edges[0]].start.z() - 2.0) < 1e-9 &&
            std::abs(model.edges()[p.edges[0]].end.z() - 2.0) < 1e-9)
          top.push_back(p);
      for (double band : {125.0, 250.0, 500.0, 1000.0, 2000.0, 4000.0}) {
        const double e_utd = octaveEnergy(band, 16, [&](double f) { return model.total(top, f, kC); });
        const double e_btm = octaveEnergy(band, 16, [&](double f) {
          return ref::btmEdgeDiffraction(kTwoPi * f / kC, edge, frame(s), frame(r));
        });
        const double diff = 10.0 * std::log10(e_utd / e_btm);
        if (finite) {
          worst = std::max(worst, std::abs(diff));
          EXPECT_NEAR(diff, 0.0, 1.0) << "x " << x << " band " << band;
        } else {
          worst_infinite = std::max(worst_infinite, std::abs(diff));
        }
      }
    }
  }
  std::printf("top edge of a 4 x 2 m plate vs the BTM finite-edge integral, 125 Hz-4 kHz: worst %.2f dB (%.2f dB "
              "as an edge without end)\n", worst, worst_infinite);
  EXPECT_GT(worst_infinite, 3.0);
}

TEST(UtdFiniteEdges, PlateAloneAndOnAGroundMatchTheBtmReference) {
  // The four listeners of rooms/screen.json behind the 4 × 2 m plate (source 2 m before it at 0.5 m), the
  // plate alone and standing on a rigid ground: UTD (every path, the reflections around second-order paths
  // in every combination) against the BTM reference to second order, octave bands 250 Hz–1 kHz (where the
  // edges are within a few wavelengths of one another) within 1 dB. At 125 Hz the plate is 1.5 wavelengths
  // wide and UTD's first-order waves read 0.2–1.8 dB high against BTM's (its second-order ones low): within
  // 1.5 dB there (measured −0.7 to +1.01 dB).
  const Vec3 s(0, -2, 0.5);
  const std::vector<Vec3> listeners = {Vec3(0, 2, 0.5), Vec3(0, 2, 1.5), Vec3(1.5, 2, 0.5), Vec3(2.5, 2, 0.5)};
  const ref::BtmPlate plate{{Vec3(-2, 0, 0), Vec3(2, 0, 0), Vec3(2, 0, 2), Vec3(-2, 0, 2)}};
  const std::vector<double> bands = {125.0, 250.0, 500.0, 1000.0};
  const int points = 16;
  for (bool ground : {false, true}) {
    const dr::Room room = plateScene(ground);
    const diffray::transport::RoomGeometry geometry(room);
    utd::UtdOptions o;
    o.second_order_reflections = 3;
    const utd::UtdModel model(room, geometry, o);
    for (const Vec3& r : listeners) {
      const std::vector<double> f = octaveGrid(bands, points);
      std::vector<double> k;
      for (double fi : f) k.push_back(kTwoPi * fi / kC);
      const auto exact = ref::btmPlateSpectrum(k, plate, ground ? 0.0 : std::nan(""), s, r, 2);
      const auto paths = model.paths(s, r);
      std::printf("plate%s, listener (%.1f, %.1f, %.1f), UTD - BTM:", ground ? " on a ground" : "", r.x(), r.y(), r.z());
      const std::vector<double> diffs = utdMinusBtmDb(model, paths, f, exact, points);
      for (std::size_t b = 0; b < bands.size(); ++b) {
        const double diff = diffs[b];
        std::printf(" %g Hz %+.2f", bands[b], diff);
        EXPECT_NEAR(diff, 0.0, bands[b] < 200.0 ? 1.5 : 1.0)
            << "ground " << ground << " listener " << r.transpose() << " band " << bands[b];
      }
      std::printf(" dB\n");
    }
  }
}
