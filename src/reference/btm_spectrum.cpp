// The thin plate's field at many frequencies from one set of quadrature nodes (see btm_spectrum.h), and the
// spectrum's settings and read-out shared with the box (btm_paths.h).
#include "diffray/reference/btm_spectrum.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "btm_plate_paths.h"
#include "diffray/core/error.h"

namespace diffray::reference {
namespace btm_detail {

SpectrumAxis::SpectrumAxis(const std::vector<double>& wavenumbers, int order) {
  if (order != 1 && order != 2) throw core::InputError("order", "must be 1 or 2, got " + std::to_string(order));
  if (wavenumbers.empty()) throw core::InputError("wavenumbers", "needs at least one");
  for (double k : wavenumbers) {
    core::requireFinite("wavenumber", k);
    if (!(k > 0.0)) throw core::InputError("wavenumber", "must be > 0, got " + std::to_string(k));
  }
  const double k_max = *std::max_element(wavenumbers.begin(), wavenumbers.end());
  const double wavelength = 2.0 * kPi / k_max;
  step_m = wavelength / 8.0;
  // Panels up to two shortest wavelengths h (the node builders cap panels at half the length they are
  // given): a path's length changes at most twice as fast as the point along the edge, so e^{−ikL} turns by
  // at most 2kh = 8π over a panel, and the 16-point rule's error term, (2kh)^32·(16!)^4/(33·(32!)^3) of the
  // panel's integral, is below 2e-10 at worst. Measured against panels of half a wavelength: within 1e-14
  // of the free field.
  panel_wavelength_m = 4.0 * wavelength;
}

std::vector<BtmField> spectrumFields(const std::vector<double>& wavenumbers, const GeometricWaves& waves,
                                     const PathGrid& first, const PathGrid* second) {
  std::vector<BtmField> out(wavenumbers.size());
  tbb::parallel_for(std::size_t{0}, out.size(), [&](std::size_t i) {
    const double k = wavenumbers[i];
    BtmField& u = out[i];
    for (const GeometricWave& w : waves.direct) u.direct += std::polar(w.weight / w.path_m, -k * w.path_m);
    for (const GeometricWave& w : waves.specular) u.specular += std::polar(w.weight / w.path_m, -k * w.path_m);
    u.diffracted = first.sum(k);
    if (second != nullptr) u.second_order = second->sum(k);
  });
  return out;
}

}  // namespace btm_detail

namespace {

using namespace btm_detail;
using core::Vec3;

// One source–plate pair's share of the work: the plate (the union on a ground), its frame and edges.
struct Scene {
  BtmPlate plate;
  PlateFrame frame;
  std::vector<EdgeFrame> edges;
  Vec3 source;
};

// A task: first order of scene `scene` (pair_i < 0), or the edge pair (pair_i, pair_j).
struct Task {
  std::size_t scene;
  int pair_i, pair_j;
};

}  // namespace

std::vector<BtmPlateField> btmPlateSpectrum(const std::vector<double>& wavenumbers_rad_m, const BtmPlate& plate,
                                            double ground_z_m, const Vec3& source, const Vec3& receiver, int order) {
  const SpectrumAxis axis(wavenumbers_rad_m, order);
  std::vector<Scene> scenes;
  GeometricWaves waves;
  const auto addScene = [&](const BtmPlate& p, const Vec3& s) {
    Scene sc{p, checkPlate(p), {}, s};
    sc.edges = edgeFrames(p, sc.frame);
    const GeometricPaths paths = geometricPaths(p, sc.frame, sc.edges, s, receiver);
    if (paths.direct.weight > 0.0) waves.direct.push_back(paths.direct);
    if (paths.specular.weight > 0.0) waves.specular.push_back(paths.specular);
    scenes.push_back(sc);
  };
  if (std::isnan(ground_z_m)) {
    addScene(plate, source);
  } else {
    const BtmPlate both = groundUnion(plate, ground_z_m, source, receiver);
    addScene(both, source);
    addScene(both, Vec3(source.x(), source.y(), 2.0 * ground_z_m - source.z()));
  }

  // Every path through the plate's edges is at least the straight distance and at most the longest way
  // from the source to a vertex, across the plate and on to the receiver (the plate is convex).
  double lo = 1e300, hi = 0.0;
  for (const Scene& sc : scenes) {
    double to_s = 0.0, to_r = 0.0, across = 0.0;
    for (const Vec3& v : sc.plate.vertices) {
      to_s = std::max(to_s, (v - sc.source).norm());
      to_r = std::max(to_r, (v - receiver).norm());
      for (const Vec3& w : sc.plate.vertices) across = std::max(across, (v - w).norm());
    }
    lo = std::min(lo, (receiver - sc.source).norm());
    hi = std::max(hi, to_s + across + to_r);
  }

  std::vector<Task> tasks;
  std::vector<bool> second;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    tasks.push_back({s, -1, -1});
    second.push_back(false);
    if (order < 2) continue;
    const int n = static_cast<int>(scenes[s].edges.size());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (i != j) tasks.push_back({s, i, j}), second.push_back(true);
  }
  const auto grids = gridTasks(second, lo, hi, axis.step_m, [&](std::size_t t, const auto& add) {
    const Task& task = tasks[t];
    const Scene& sc = scenes[task.scene];
    if (task.pair_i < 0) {
      for (const BtmNode& q : firstOrderNodes(sc.edges, sc.source, receiver, axis.panel_wavelength_m))
        add(q.path_m, q.amplitude);
      return;
    }
    const EdgeFrame& ei = sc.edges[static_cast<std::size_t>(task.pair_i)];
    edgePairNodes(ei, sc.edges[static_cast<std::size_t>(task.pair_j)], plateFaces(ei), sc.source, receiver,
                  pairScale(sc.frame, sc.source, receiver), axis.panel_wavelength_m, add);
  });
  return spectrumFields(wavenumbers_rad_m, waves, grids.first, order >= 2 ? &grids.second : nullptr);
}

}  // namespace diffray::reference
