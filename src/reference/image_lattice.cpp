// Shoebox image sources by the closed-form lattice (see the header for the cell indexing and the hit
// counts). Self-contained: no code shared with the tracer.
#include "diffray/reference/image_lattice.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxCellsPerAxis = 1e7;
constexpr double kMaxImages = 5e8;  // about a minute of enumeration: beyond it the request is a mistake

// Reflections on the lower (x = 0) and upper (x = L) wall of the image in cell n, and its coordinate.
int lowerHits(int n) { return n > 0 ? n / 2 : (1 - n) / 2; }
int upperHits(int n) { return n > 0 ? (n + 1) / 2 : -n / 2; }
double imageCoordinate(int n, double length_m, double source_m) {
  return n % 2 == 0 ? n * length_m + source_m : (n + 1) * length_m - source_m;
}

// One axis of the lattice: the cells that can hold an image within the limits, with each cell's image
// coordinate, its offset from the receiver and its wall-reflection factor per band.
struct Axis {
  int lo = 0, hi = -1;
  std::vector<double> position, delta;
  std::vector<double> factor;  // [(n − lo)·bands + b]
};

Axis makeAxis(const Shoebox& box, int a, long long max_order, double max_distance_m, int bands) {
  const double length = box.dims_m[a], s = box.source_m[a], r = box.receiver_m[a];
  double lo = -static_cast<double>(max_order), hi = static_cast<double>(max_order);
  if (std::isfinite(max_distance_m)) {
    // The image in cell n lies in [nL, (n+1)L]: it can be within D of r only for these n.
    lo = std::max(lo, std::floor((r - max_distance_m) / length) - 1.0);
    hi = std::min(hi, std::floor((r + max_distance_m) / length) + 1.0);
  }
  core::checkedCount("shoebox images: cells along axis " + std::to_string(a), hi - lo + 1.0, kMaxCellsPerAxis);
  Axis ax;
  ax.lo = static_cast<int>(lo);
  ax.hi = static_cast<int>(hi);
  const std::vector<double>& beta_lo = box.reflection_energy[2 * a];
  const std::vector<double>& beta_hi = box.reflection_energy[2 * a + 1];
  for (int n = ax.lo; n <= ax.hi; ++n) {
    const double x = imageCoordinate(n, length, s);
    ax.position.push_back(x);
    ax.delta.push_back(x - r);
    for (int b = 0; b < bands; ++b)
      ax.factor.push_back(std::pow(beta_lo[b], lowerHits(n)) * std::pow(beta_hi[b], upperHits(n)));
  }
  return ax;
}

int checkBox(const Shoebox& box) {
  const char* axis_name[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const std::string axis = axis_name[a];
    core::requirePositive("shoebox: dimension " + axis, box.dims_m[a]);
    for (const auto& [what, v] : {std::pair{"source", box.source_m[a]}, std::pair{"receiver", box.receiver_m[a]}}) {
      if (!(v > 0.0 && v < box.dims_m[a])) {
        std::ostringstream s;
        s << "must lie strictly inside the box (0 … " << box.dims_m[a] << " m), got " << v;
        throw core::InputError(std::string("shoebox: ") + what + " " + axis, s.str());
      }
    }
  }
  if (box.source_m == box.receiver_m) throw core::InputError("shoebox: receiver", "coincides with the source");
  core::requirePositive("shoebox: c_m_s", box.c_m_s);
  const std::size_t bands = box.air_m_per_m.size();
  if (bands == 0) throw core::InputError("shoebox: air_m_per_m", "needs one entry per band, got none");
  for (double m : box.air_m_per_m)
    if (!(std::isfinite(m) && m >= 0.0)) throw core::InputError("shoebox: air_m_per_m", "must be finite and >= 0");
  const char* wall_name[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
  for (int w = 0; w < 6; ++w) {
    const std::string where = std::string("shoebox: reflection_energy ") + wall_name[w];
    if (box.reflection_energy[w].size() != bands)
      throw core::InputError(where, "needs " + std::to_string(bands) + " bands (as air_m_per_m), got " +
                                        std::to_string(box.reflection_energy[w].size()));
    for (double beta : box.reflection_energy[w])
      if (!(beta >= 0.0 && beta <= 1.0)) throw core::InputError(where, "must be within 0 … 1");
  }
  return static_cast<int>(bands);
}

// Calls visit(n, d, energy) for every image within both limits; `energy` holds one value per band.
template <class Visit>
void forEachImage(const Shoebox& box, int max_order_in, double max_distance_m, Visit&& visit) {
  const int bands = checkBox(box);
  if (max_order_in < 0) throw core::InputError("shoebox images: max_order", "must be >= 0");
  if (!(max_distance_m > 0.0)) throw core::InputError("shoebox images: max_distance_m", "must be > 0");
  const long long max_order = max_order_in;
  if (max_order_in == kAnyOrder && !std::isfinite(max_distance_m))
    throw core::InputError("shoebox images", "give a finite max_order or max_distance_m: the image set is infinite");
  // Cost guard: lattice points within the distance ball (cells of volume V), or within the order octahedron.
  const double n = static_cast<double>(max_order);
  double estimate = (2.0 * n + 1.0) * (2.0 * n * n + 2.0 * n + 3.0) / 3.0;
  if (std::isfinite(max_distance_m)) {
    const double r = max_distance_m + box.dims_m[0] + box.dims_m[1] + box.dims_m[2];
    estimate = std::min(estimate, 4.0 / 3.0 * kPi * r * r * r / (box.dims_m[0] * box.dims_m[1] * box.dims_m[2]));
  }
  core::checkedCount("shoebox images: image count", estimate, kMaxImages);

  const Axis ax = makeAxis(box, 0, max_order, max_distance_m, bands);
  const Axis ay = makeAxis(box, 1, max_order, max_distance_m, bands);
  const Axis az = makeAxis(box, 2, max_order, max_distance_m, bands);
  const double d2_max = max_distance_m * max_distance_m;  // may be +inf
  std::vector<double> fxy(bands), energy(bands);
  for (int nx = ax.lo; nx <= ax.hi; ++nx) {
    const double dx = ax.delta[nx - ax.lo];
    const long long ox = std::llabs(nx);
    if (dx * dx > d2_max || ox > max_order) continue;
    for (int ny = ay.lo; ny <= ay.hi; ++ny) {
      const double dy = ay.delta[ny - ay.lo];
      const double dxy2 = dx * dx + dy * dy;
      const long long budget = max_order - ox - std::llabs(ny);  // order left for z
      if (dxy2 > d2_max || budget < 0) continue;
      const double* fx = &ax.factor[std::size_t(nx - ax.lo) * bands];
      const double* fy = &ay.factor[std::size_t(ny - ay.lo) * bands];
      for (int b = 0; b < bands; ++b) fxy[b] = fx[b] * fy[b];
      long long z_lo = std::max<long long>(az.lo, -budget), z_hi = std::min<long long>(az.hi, budget);
      if (std::isfinite(d2_max)) {  // only the z cells that can reach within the distance
        const double reach = std::sqrt(d2_max - dxy2), zr = box.receiver_m[2], lz = box.dims_m[2];
        z_lo = std::max(z_lo, static_cast<long long>(std::floor((zr - reach) / lz)) - 1);
        z_hi = std::min(z_hi, static_cast<long long>(std::floor((zr + reach) / lz)) + 1);
      }
      for (long long nz = z_lo; nz <= z_hi; ++nz) {
        const double dz = az.delta[std::size_t(nz - az.lo)];
        const double d2 = dxy2 + dz * dz;
        if (d2 > d2_max) continue;
        const double d = std::sqrt(d2);
        const double* fz = &az.factor[std::size_t(nz - az.lo) * bands];
        for (int b = 0; b < bands; ++b) energy[b] = fxy[b] * fz[b] * std::exp(-box.air_m_per_m[b] * d) / d2;
        visit(std::array<int, 3>{nx, ny, static_cast<int>(nz)}, d, energy);
      }
    }
  }
}

}  // namespace

std::vector<ImageArrival> shoeboxImages(const Shoebox& box, int max_order, double max_distance_m) {
  std::vector<ImageArrival> out;
  forEachImage(box, max_order, max_distance_m,
               [&](const std::array<int, 3>& n, double d, const std::vector<double>& energy) {
                 ImageArrival a;
                 a.distance_m = d;
                 a.delay_s = d / box.c_m_s;
                 a.lattice = n;
                 for (int k = 0; k < 3; ++k) {
                   a.order += std::abs(n[k]);
                   a.hits[2 * k] = lowerHits(n[k]);
                   a.hits[2 * k + 1] = upperHits(n[k]);
                   a.position_m[k] = imageCoordinate(n[k], box.dims_m[k], box.source_m[k]);
                 }
                 a.energy = energy;
                 out.push_back(std::move(a));
               });
  std::sort(out.begin(), out.end(), [](const ImageArrival& a, const ImageArrival& b) {
    return a.distance_m != b.distance_m ? a.distance_m < b.distance_m : a.lattice < b.lattice;
  });
  return out;
}

std::vector<std::vector<double>> shoeboxEnergyHistogram(const Shoebox& box, double bin_s, double length_s,
                                                        int max_order) {
  core::requirePositive("shoeboxEnergyHistogram: bin_s", bin_s);
  core::requirePositive("shoeboxEnergyHistogram: length_s", length_s);
  const int bins = core::checkedCount("shoeboxEnergyHistogram: bins", length_s / bin_s, 1e8);
  std::vector<std::vector<double>> hist(box.air_m_per_m.size(), std::vector<double>(bins, 0.0));
  forEachImage(box, max_order, box.c_m_s * bins * bin_s,
               [&](const std::array<int, 3>&, double d, const std::vector<double>& energy) {
                 const double bin = std::floor(d / box.c_m_s / bin_s);
                 if (bin >= bins) return;  // exactly at the end of the last bin
                 for (std::size_t b = 0; b < energy.size(); ++b) hist[b][static_cast<std::size_t>(bin)] += energy[b];
               });
  return hist;
}

}  // namespace diffray::reference
