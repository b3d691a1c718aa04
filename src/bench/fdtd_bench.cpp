// The FDTD benchmark: cell updates per second of the wave reference's SRL step (reference/fdtd_scheme.h) on
// a shipped room's grid, beside the memory bandwidth of a STREAM-like triad a[i] = b[i] + s·c[i] over float
// arrays of the grid's node count, on the same threads and in the same run. The update is memory-bound: per
// node it must read p^n (4 bytes; its six neighbours come from cache), read and write p^{n−1} (8 bytes) and
// read the node's flags (1 byte), 13 bytes, so updates/s × 13 over the triad's bytes/s says how close to
// the machine's bandwidth it runs (1 = as fast as streaming allows).
#include "fdtd_bench.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "diffray/core/parallel.h"
#include "diffray/reference/fdtd_grid.h"
#include "diffray/reference/fdtd_scheme.h"
#include "diffray/room/air.h"

namespace diffray::bench {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Bytes per second of a[i] = b[i] + s·c[i] (12 bytes per element: two reads, one write), the best of `reps`.
double triadBytesPerSecond(std::size_t n, int reps) {
  std::vector<float> a(n, 0.0f), b(n, 1.0f), c(n, 2.0f);
  double best = 0.0;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 65536), [&](const tbb::blocked_range<std::size_t>& br) {
      for (std::size_t i = br.begin(); i != br.end(); ++i) a[i] = b[i] + 0.5f * c[i];
    });
    best = std::max(best, 12.0 * static_cast<double>(n) / secondsSince(t0));
  }
  if (a[n / 2] != 2.0f) std::cerr << "bench: triad result wrong\n";
  return best;
}

}  // namespace

void benchFdtd(const room::Room& room, const std::string& label, int steps) {
  const double c = room::speedOfSound(room.air);
  const double h = c / (10.0 * 707.1);  // 10 points per wavelength at the 500 Hz octave's upper edge
  reference::FdtdGrid grid = reference::voxelise(room, h, 3);
  grid.floodFill({static_cast<std::size_t>(grid.nearestNode(room.sources.at(0).position_m))});
  std::vector<double> beta(room.materials.size(), 0.01);
  reference::FdtdScheme scheme(grid, reference::kSrlCourantLimit, beta);
  const std::size_t src = static_cast<std::size_t>(grid.nearestNode(room.sources.at(0).position_m));
  scheme.inject(src, 1.0f);
  for (int n = 0; n < 10; ++n) scheme.step();  // warm-up
  const auto t0 = Clock::now();
  for (int n = 0; n < steps; ++n) scheme.step();
  const double s = secondsSince(t0);
  const double nodes = static_cast<double>(grid.nodes());
  const double updates_per_s = nodes * steps / s;  // every node is swept (air or not)
  const double triad = triadBytesPerSecond(grid.nodes(), 10);
  const double bytes_per_update = 13.0;
  nlohmann::ordered_json j{{"bench", "fdtd"},
                           {"room", label},
                           {"h_m", h},
                           {"grid", {grid.nx, grid.ny, grid.nz}},
                           {"nodes", nodes},
                           {"air_nodes", grid.air_nodes},
                           {"boundary_nodes", scheme.boundary().size()},
                           {"steps", steps},
                           {"threads", core::ThreadLimit::current()},
                           {"cell_updates_per_s", updates_per_s},
                           {"air_updates_per_s", static_cast<double>(grid.air_nodes) * steps / s},
                           {"bytes_per_update", bytes_per_update},
                           {"implied_bytes_per_s", updates_per_s * bytes_per_update},
                           {"triad_bytes_per_s", triad},
                           {"fraction_of_triad", updates_per_s * bytes_per_update / triad}};
  std::cout << j.dump() << std::endl;
}

}  // namespace diffray::bench
