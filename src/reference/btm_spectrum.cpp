// The thin plate's field at many frequencies from one set of quadrature nodes (see btm_spectrum.h).
#include "diffray/reference/btm_spectrum.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "btm_plate_paths.h"
#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

using namespace btm_detail;
using core::Vec3;
using Complex = std::complex<double>;

// Amplitudes spread onto the uniform grid L₀ + n·h with φ(x) = e^{−x²/4} over 24 points (btm_spectrum.h).
class PathGrid {
 public:
  static constexpr int kBelow = 11, kAbove = 12;  // taps n0 − 11 … n0 + 12 around n0 = ⌊x⌋

  PathGrid(double lo_m, double hi_m, double step_m)
      : origin_(lo_m - (kBelow + 1) * step_m), step_(step_m),
        values_(static_cast<std::size_t>(std::ceil((hi_m - lo_m) / step_m)) + kBelow + kAbove + 4, 0.0) {
    for (int j = 0; j <= kBelow + 1; ++j) tap_[static_cast<std::size_t>(j)] = std::exp(-0.25 * j * j);
  }

  // e^{−(j − d)²/4} = e^{−j²/4}·(e^{d/2})^j·e^{−d²/4} (fast Gaussian gridding: two exponentials per node).
  void add(double path_m, double amplitude) {
    const double x = (path_m - origin_) / step_;
    const double n0 = std::floor(x), d = x - n0;
    double* v = values_.data() + static_cast<std::ptrdiff_t>(n0);
    const double grow = std::exp(0.5 * d), base = amplitude * std::exp(-0.25 * d * d);
    double p = base;
    for (int j = 0; j <= kAbove; ++j, p *= grow) v[j] += p * tap_[static_cast<std::size_t>(j)];
    p = base / grow;
    for (int j = 1; j <= kBelow; ++j, p /= grow) v[-j] += p * tap_[static_cast<std::size_t>(j)];
  }

  void merge(const PathGrid& other) {
    for (std::size_t i = 0; i < values_.size(); ++i) values_[i] += other.values_[i];
  }

  // Σ_q a_q·e^{−ik·L_q}: the grid's transform divided by the Gaussian's, φ̂(kh) = √(4π)·e^{−(kh)²}.
  Complex sum(double k) const {
    Complex s(0.0, 0.0);
    for (std::size_t n = 0; n < values_.size(); ++n)
      if (values_[n] != 0.0) s += std::polar(values_[n], -k * (origin_ + static_cast<double>(n) * step_));
    const double xi = k * step_;
    return s / (std::sqrt(4.0 * kPi) * std::exp(-xi * xi));
  }

 private:
  double origin_, step_;
  std::vector<double> values_;
  std::array<double, kBelow + 2> tap_{};
};

// One source–plate pair's share of the work: the plate (the union on a ground), its frame and edges.
struct Scene {
  BtmPlate plate;
  PlateFrame frame;
  std::vector<EdgeFrame> edges;
  Vec3 source;
  GeometricPaths paths;
};

// A task: first order of scene `scene` (pair_i < 0), or the edge pair (pair_i, pair_j).
struct Task {
  std::size_t scene;
  int pair_i, pair_j;
};

}  // namespace

std::vector<BtmPlateField> btmPlateSpectrum(const std::vector<double>& wavenumbers_rad_m, const BtmPlate& plate,
                                            double ground_z_m, const Vec3& source, const Vec3& receiver, int order) {
  if (order != 1 && order != 2) throw core::InputError("order", "must be 1 or 2, got " + std::to_string(order));
  if (wavenumbers_rad_m.empty()) throw core::InputError("wavenumbers", "needs at least one");
  for (double k : wavenumbers_rad_m) {
    core::requireFinite("wavenumber", k);
    if (!(k > 0.0)) throw core::InputError("wavenumber", "must be > 0, got " + std::to_string(k));
  }
  std::vector<Scene> scenes;
  const auto addScene = [&](const BtmPlate& p, const Vec3& s) {
    Scene sc{p, checkPlate(p), {}, s, {}};
    sc.edges = edgeFrames(p, sc.frame);
    sc.paths = geometricPaths(p, sc.frame, s, receiver);
    scenes.push_back(sc);
  };
  if (std::isnan(ground_z_m)) {
    addScene(plate, source);
  } else {
    const BtmPlate both = groundUnion(plate, ground_z_m, source, receiver);
    addScene(both, source);
    addScene(both, Vec3(source.x(), source.y(), 2.0 * ground_z_m - source.z()));
  }
  const double k_max = *std::max_element(wavenumbers_rad_m.begin(), wavenumbers_rad_m.end());
  const double wavelength = 2.0 * kPi / k_max, step = wavelength / 8.0;
  // Panels up to two shortest wavelengths h (the node builders cap panels at half the length they are
  // given): a path's length changes at most twice as fast as the point along the edge, so e^{−ikL} turns by
  // at most 2kh = 8π over a panel, and the 16-point rule's error term, (2kh)^32·(16!)^4/(33·(32!)^3) of the
  // panel's integral, is below 2e-10 at worst. Measured against panels of half a wavelength: within 1e-14
  // of the free field.
  const double panel_wavelength = 4.0 * wavelength;

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
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    tasks.push_back({s, -1, -1});
    if (order < 2) continue;
    const int n = static_cast<int>(scenes[s].edges.size());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (i != j) tasks.push_back({s, i, j});
  }
  std::vector<PathGrid> grids(tasks.size(), PathGrid(lo, hi, step));
  tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t t) {
    const Task& task = tasks[t];
    const Scene& sc = scenes[task.scene];
    PathGrid& grid = grids[t];
    if (task.pair_i < 0) {
      for (const BtmNode& q : firstOrderNodes(sc.edges, sc.source, receiver, panel_wavelength)) grid.add(q.path_m, q.amplitude);
      return;
    }
    edgePairNodes(sc.edges[static_cast<std::size_t>(task.pair_i)], sc.edges[static_cast<std::size_t>(task.pair_j)],
                  sc.source, receiver, pairScale(sc.frame, sc.source, receiver), panel_wavelength,
                  [&grid](double path, double amplitude) { grid.add(path, amplitude); });
  });
  // Merged in task order, so the sums do not depend on the threads.
  PathGrid first(lo, hi, step), second(lo, hi, step);
  for (std::size_t t = 0; t < tasks.size(); ++t) (tasks[t].pair_i < 0 ? first : second).merge(grids[t]);

  std::vector<BtmPlateField> out(wavenumbers_rad_m.size());
  tbb::parallel_for(std::size_t{0}, out.size(), [&](std::size_t i) {
    const double k = wavenumbers_rad_m[i];
    BtmPlateField& u = out[i];
    for (const Scene& sc : scenes) {
      if (!std::isnan(sc.paths.direct_m)) u.direct += std::polar(1.0 / sc.paths.direct_m, -k * sc.paths.direct_m);
      if (!std::isnan(sc.paths.specular_m)) u.specular += std::polar(1.0 / sc.paths.specular_m, -k * sc.paths.specular_m);
    }
    u.diffracted = first.sum(k);
    if (order >= 2) u.second_order = second.sum(k);
  });
  return out;
}

}  // namespace diffray::reference
