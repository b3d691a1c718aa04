// The FDTD voxel grid (fdtd_grid.h): domain, wall links by grid-line stabbing, flood fill of the air.
#include "diffray/reference/fdtd_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "diffray/core/error.h"

namespace diffray::reference {

FdtdGrid::FdtdGrid(const core::Vec3& origin_m, double h_m, int nx_, int ny_, int nz_)
    : origin(origin_m), h(h_m), nx(nx_), ny(ny_), nz(nz_) {
  DIFFRAY_CHECK(nx >= 3 && ny >= 3 && nz >= 3 && h > 0.0);
  DIFFRAY_CHECK(nodes() < std::numeric_limits<std::uint32_t>::max());
  flags.assign(nodes(), 0);
  // The outward links of the outer layer: blocked, material kAbsorbing (no link_material entry).
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::uint8_t f = 0;
        if (i == 0) f |= 1u << 0;
        if (i == nx - 1) f |= 1u << 1;
        if (j == 0) f |= 1u << 2;
        if (j == ny - 1) f |= 1u << 3;
        if (k == 0) f |= 1u << 4;
        if (k == nz - 1) f |= 1u << 5;
        flags[index(i, j, k)] = f;
      }
}

std::ptrdiff_t FdtdGrid::offset(int d) const {
  const std::ptrdiff_t step[3] = {1, nx, static_cast<std::ptrdiff_t>(nx) * ny};
  return (d & 1) ? step[d / 2] : -step[d / 2];
}

core::Vec3 FdtdGrid::position(std::size_t node) const {
  const std::size_t nxy = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  const double i = static_cast<double>(node % static_cast<std::size_t>(nx));
  const double j = static_cast<double>((node % nxy) / static_cast<std::size_t>(nx));
  const double k = static_cast<double>(node / nxy);
  return origin + h * core::Vec3(i, j, k);
}

long FdtdGrid::nearestNode(const core::Vec3& p) const {
  const int n[3] = {nx, ny, nz};
  int c[3];
  for (int a = 0; a < 3; ++a) {
    const double x = std::round((p[a] - origin[a]) / h);
    if (!(x >= 0.0 && x <= n[a] - 1)) return -1;
    c[a] = static_cast<int>(x);
  }
  return static_cast<long>(index(c[0], c[1], c[2]));
}

int FdtdGrid::materialOf(std::size_t node, int d) const {
  const std::uint64_t key = static_cast<std::uint64_t>(node) * kFdtdDirections + static_cast<std::uint64_t>(d);
  const auto it = std::lower_bound(link_material.begin(), link_material.end(), std::make_pair(key, std::numeric_limits<int>::min()));
  return it != link_material.end() && it->first == key ? it->second : kAbsorbing;
}

void FdtdGrid::blockWalls(const room::Room& room) {
  const int n[3] = {nx, ny, nz};
  const auto& mesh = room.mesh;
  std::vector<std::pair<std::uint64_t, int>> links;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int material = mesh.object_of_triangle[t];
    if (room.isOpening(material)) continue;
    const core::Vec3 A = mesh.vertices[mesh.triangles[t][0]], B = mesh.vertices[mesh.triangles[t][1]],
                     C = mesh.vertices[mesh.triangles[t][2]];
    const core::Vec3 nrm = (B - A).cross(C - A);
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      const double na = nrm[a];
      if (!(std::abs(na) > 1e-12 * nrm.norm())) continue;  // the triangle is parallel to axis a
      const double tol = 1e-9 * (std::abs(na) + h * h);
      const std::array<core::Vec3, 3> P = {A, B, C};
      const double lo_u = std::min({A[u], B[u], C[u]}), hi_u = std::max({A[u], B[u], C[u]});
      const double lo_v = std::min({A[v], B[v], C[v]}), hi_v = std::max({A[v], B[v], C[v]});
      const int j0 = std::max(0, static_cast<int>(std::ceil((lo_u - origin[u]) / h - 1e-9)));
      const int j1 = std::min(n[u] - 1, static_cast<int>(std::floor((hi_u - origin[u]) / h + 1e-9)));
      const int k0 = std::max(0, static_cast<int>(std::ceil((lo_v - origin[v]) / h - 1e-9)));
      const int k1 = std::min(n[v] - 1, static_cast<int>(std::floor((hi_v - origin[v]) / h + 1e-9)));
      for (int k = k0; k <= k1; ++k)
        for (int j = j0; j <= j1; ++j) {
          const double pu = origin[u] + h * j, pv = origin[v] + h * k;
          bool inside = true;
          for (int e = 0; e < 3 && inside; ++e) {  // 2D edge functions, signed like na; edges inclusive
            const core::Vec3& p0 = P[e];
            const core::Vec3& p1 = P[(e + 1) % 3];
            const double f = (p1[u] - p0[u]) * (pv - p0[v]) - (p1[v] - p0[v]) * (pu - p0[u]);
            inside = (na > 0 ? f : -f) >= -tol;
          }
          if (!inside) continue;
          const double xa = A[a] - (nrm[u] * (pu - A[u]) + nrm[v] * (pv - A[v])) / na;
          const double s = std::floor((xa - origin[a]) / h);
          if (!(s >= 0.0 && s <= n[a] - 2)) continue;
          int c[3];
          c[a] = static_cast<int>(s);
          c[u] = j;
          c[v] = k;
          const std::size_t lo = index(c[0], c[1], c[2]);
          const std::size_t hi = lo + static_cast<std::size_t>(offset(2 * a + 1));
          flags[lo] |= static_cast<std::uint8_t>(1u << (2 * a + 1));
          flags[hi] |= static_cast<std::uint8_t>(1u << (2 * a));
          links.emplace_back(static_cast<std::uint64_t>(lo) * kFdtdDirections + static_cast<std::uint64_t>(2 * a + 1), material);
          links.emplace_back(static_cast<std::uint64_t>(hi) * kFdtdDirections + static_cast<std::uint64_t>(2 * a), material);
        }
    }
  }
  // Sorted by key, the first triangle's material kept where several block one link (stable sort).
  std::stable_sort(links.begin(), links.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  links.erase(std::unique(links.begin(), links.end(), [](const auto& x, const auto& y) { return x.first == y.first; }),
              links.end());
  link_material = std::move(links);
}

void FdtdGrid::floodFill(const std::vector<std::size_t>& seeds) {
  std::vector<std::uint32_t> stack;
  for (std::size_t s : seeds)
    if (s < nodes() && !isAir(s)) {
      flags[s] |= kAir;
      stack.push_back(static_cast<std::uint32_t>(s));
    }
  while (!stack.empty()) {
    const std::size_t i = stack.back();
    stack.pop_back();
    for (int d = 0; d < kFdtdDirections; ++d) {
      if (flags[i] & (1u << d)) continue;
      const std::size_t j = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + offset(d));
      if (isAir(j)) continue;
      flags[j] |= kAir;
      stack.push_back(static_cast<std::uint32_t>(j));
    }
  }
  air_nodes = 0;
  air_reaches_edge = false;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!isAir(index(i, j, k))) continue;
        ++air_nodes;
        if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) air_reaches_edge = true;
      }
}

FdtdGridSize fdtdGridSize(const room::Room& room, double h, int margin) {
  if (room.mesh.vertices.empty()) throw core::InputError(room.file, "the scene has no geometry to voxelise");
  core::Vec3 lo = room.mesh.vertices[0], hi = lo;
  for (const auto& v : room.mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  for (const auto& src : room.sources) {
    lo = lo.cwiseMin(src.position_m);
    hi = hi.cwiseMax(src.position_m);
  }
  for (const auto& l : room.listeners) {
    lo = lo.cwiseMin(l.position_m - l.radius_m * core::Vec3(1, 1, 1));
    hi = hi.cwiseMax(l.position_m + l.radius_m * core::Vec3(1, 1, 1));
  }
  FdtdGridSize s;
  s.origin = lo - (margin + 0.5) * h * core::Vec3(1, 1, 1);
  int* n[3] = {&s.nx, &s.ny, &s.nz};
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil((hi[a] - lo[a]) / h - 1e-9) + 2.0 * margin + 2.0;
    if (!(cells < 1e6)) throw core::InputError(room.file, "the scene is too large for an FDTD grid of spacing " + std::to_string(h) + " m");
    *n[a] = static_cast<int>(cells);
  }
  return s;
}

FdtdGrid voxelise(const room::Room& room, double h, int margin) {
  const FdtdGridSize s = fdtdGridSize(room, h, margin);
  FdtdGrid grid(s.origin, h, s.nx, s.ny, s.nz);
  grid.blockWalls(room);
  return grid;
}

}  // namespace diffray::reference
