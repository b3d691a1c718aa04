// The FDTD wave reference: planning, checks, runs per band and source, recording and band energies (fdtd.h).
#include "diffray/reference/fdtd.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "diffray/core/error.h"
#include "diffray/core/memory.h"
#include "diffray/reference/fdtd_analysis.h"
#include "diffray/reference/fdtd_grid.h"
#include "diffray/reference/fdtd_scheme.h"
#include "diffray/reference/room_acoustics.h"
#include "diffray/room/air.h"
#include "diffray/room/checks.h"

namespace diffray::reference {
namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

std::string where(const room::Room& room) { return room.file.empty() ? std::string("room") : room.file; }

// 1.5 × the longest Eyring T60 of the bands (header), or 4 diagonals of the domain over c without a volume.
double defaultLength(const room::Room& room, const std::vector<int>& bands, double c) {
  const double volume = room.volume();
  const std::vector<char> enclosure = room.enclosure();
  double t60 = 0.0;
  if (volume > 0.0 && room::openEdgeCount(room) == 0) {
    for (int b : bands) {
      double area = 0.0, absorbed = 0.0;
      for (std::size_t i = 0; i < room.mesh.triangles.size(); ++i) {
        if (!enclosure[i]) continue;
        const auto& t = room.mesh.triangles[i];
        const auto& v = room.mesh.vertices;
        const double a = 0.5 * (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).norm();
        area += a;
        absorbed += a * room.materials[static_cast<std::size_t>(room.mesh.object_of_triangle[i])].absorption[b];
      }
      if (!(absorbed > 0.0)) return room.output.max_length_s;  // no absorption: as long as allowed
      t60 = std::max(t60, eyringT(volume, area, std::min(absorbed / area, 0.999), 0.0, c));
    }
    return std::min(1.5 * t60, room.output.max_length_s);
  }
  core::Vec3 lo = room.mesh.vertices.at(0), hi = lo;
  for (const auto& v : room.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return std::min(std::max(4.0 * (hi - lo).norm() / c, 0.2), room.output.max_length_s);
}

// Whether the segment a → b crosses a triangle that is not an opening.
bool segmentBlocked(const room::Room& room, const core::Vec3& a, const core::Vec3& b) {
  const auto& m = room.mesh;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    if (room.isOpening(m.object_of_triangle[i])) continue;
    const auto& t = m.triangles[i];
    if (room::crossesTriangle(a, b - a, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], 0.0, 1.0)) return true;
  }
  return false;
}

// The node of the cell around p nearest to p whose segment to p crosses no wall; −1 if none.
long sourceNode(const room::Room& room, const FdtdGrid& g, const core::Vec3& p) {
  long best = -1;
  double best_d = 1e300;
  const core::Vec3 rel = (p - g.origin) / g.h;
  for (int corner = 0; corner < 8; ++corner) {
    int c[3];
    const int n[3] = {g.nx, g.ny, g.nz};
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      c[a] = static_cast<int>(std::floor(rel[a])) + ((corner >> a) & 1);
      inside = inside && c[a] >= 0 && c[a] < n[a];
    }
    if (!inside) continue;
    const std::size_t node = g.index(c[0], c[1], c[2]);
    const double d = (g.position(node) - p).norm();
    if (d < best_d && !segmentBlocked(room, p, g.position(node))) best = static_cast<long>(node), best_d = d;
  }
  return best;
}

// A band's grid, flood-filled from the sources, with its source nodes and listener points; checks them.
struct BandGrid {
  FdtdGrid grid;
  std::vector<std::size_t> sources;
  std::vector<std::vector<std::size_t>> points;  // per listener
};

std::unique_ptr<BandGrid> buildBandGrid(const room::Room& room, const WaveOptions& o, const WaveBandPlan& bp) {
  auto bg = std::make_unique<BandGrid>();
  bg->grid = voxelise(room, bp.h_m, o.margin_cells);
  FdtdGrid& g = bg->grid;
  const std::string at = format(" at h = %.4g m", bp.h_m);
  for (const auto& s : room.sources) {
    const long node = sourceNode(room, g, s.position_m);
    if (g.nearestNode(s.position_m) < 0)
      throw core::InputError(where(room), "source " + s.name + " is outside the room: beyond the FDTD grid's domain");
    if (node < 0)
      throw core::InputError(where(room), "source " + s.name + ": no grid node near it" + at + " on its side of the walls");
    bg->sources.push_back(static_cast<std::size_t>(node));
  }
  g.floodFill(bg->sources);
  const double air_m3 = static_cast<double>(g.air_nodes) * bp.h_m * bp.h_m * bp.h_m, volume = room.volume();
  bool any_opening = false;
  for (std::size_t m = 0; m < room.materials.size(); ++m) any_opening = any_opening || room.isOpening(static_cast<int>(m));
  const bool closed = room::openEdgeCount(room) == 0;
  if (g.air_reaches_edge && closed && !any_opening)
    throw core::InputError(where(room), "a source is outside the room: its air reaches the FDTD grid's edge" + at +
                                            " and the scene is closed");
  if (!g.air_reaches_edge && volume > 0.0 && air_m3 < 0.5 * volume)
    throw core::InputError(where(room), format("a source is inside a wall or a closed part of the scene: the air "
                                               "around it is %.3g m³, the room's volume %.3g m³",
                                               air_m3, volume) + at);
  for (const auto& l : room.listeners) {
    std::vector<std::size_t> inside;
    const int reach = static_cast<int>(std::ceil(l.radius_m / g.h)) + 1;
    const core::Vec3 rel = (l.position_m - g.origin) / g.h;
    for (int k = -reach; k <= reach; ++k)
      for (int j = -reach; j <= reach; ++j)
        for (int i = -reach; i <= reach; ++i) {
          const int c[3] = {static_cast<int>(std::lround(rel[0])) + i, static_cast<int>(std::lround(rel[1])) + j,
                            static_cast<int>(std::lround(rel[2])) + k};
          if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= g.nx || c[1] >= g.ny || c[2] >= g.nz) continue;
          const std::size_t node = g.index(c[0], c[1], c[2]);
          if (g.isAir(node) && (g.position(node) - l.position_m).norm() <= l.radius_m) inside.push_back(node);
        }
    if (inside.empty())
      throw core::InputError(where(room), "listener " + l.name + ": no air node within its sphere (radius " +
                                              format("%g m)", l.radius_m) + at +
                                              ": it is inside a wall, outside the room or too small for the grid");
    std::sort(inside.begin(), inside.end());
    std::vector<std::size_t> chosen;
    const std::size_t n = inside.size(), want = std::min(n, static_cast<std::size_t>(o.max_points));
    for (std::size_t q = 0; q < want; ++q) chosen.push_back(inside[q * n / want]);
    bg->points.push_back(std::move(chosen));
  }
  return bg;
}

}  // namespace

WavePlan planWave(const room::Room& room, const WaveOptions& o) {
  if (!(o.ppw >= 4.0 && o.ppw <= 100.0)) throw core::InputError("--ppw", "must lie between 4 and 100");
  if (!(o.max_h_m > 0.0 && o.max_h_m <= 10.0)) throw core::InputError("--max-h", "must lie in (0, 10] m");
  if (!(o.courant_factor > 0.0 && o.courant_factor <= 1.0)) throw core::InputError("courant factor", "must lie in (0, 1]");
  if (!(o.length_s >= 0.0 && o.length_s <= 120.0)) throw core::InputError("--length", "must lie in (0, 120] s");
  if (room.sources.empty()) throw core::InputError(where(room), "no source to simulate");
  if (room.listeners.empty()) throw core::InputError(where(room), "no listener to record");
  WavePlan plan;
  plan.speed_of_sound_m_s = room::speedOfSound(room.air);
  plan.bin_s = room.output.histogram_bin_s;
  plan.physical_bytes = core::physicalMemoryBytes();
  const double c = plan.speed_of_sound_m_s;
  std::vector<int> bands;
  if (o.bands_hz.empty()) {
    for (int b = 0; b < room.bands.size(); ++b)
      if (room.bands.nominalHz(b) <= 500.0 * 1.01) bands.push_back(b);
  } else {
    for (double f : o.bands_hz) {
      const int b = room.bands.find(f);
      if (b < 0) throw core::InputError("--bands", format("%g Hz is not one of the room's band centres", f));
      if (std::find(bands.begin(), bands.end(), b) == bands.end()) bands.push_back(b);
    }
  }
  if (bands.empty()) throw core::InputError("--bands", "the room has no band at or below 500 Hz");
  plan.length_s = o.length_s > 0.0 ? o.length_s
                  : room.output.ir_length_s > 0.0 ? room.output.ir_length_s
                                                  : defaultLength(room, bands, c);
  double surface = 0.0;
  for (std::size_t i = 0; i < room.mesh.triangles.size(); ++i) {
    const auto& t = room.mesh.triangles[i];
    const auto& v = room.mesh.vertices;
    surface += 0.5 * (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).norm();
  }
  for (int b : bands) {
    WaveBandPlan bp;
    bp.band = b;
    bp.h_m = std::min(c / (o.ppw * room.bands.upperHz(b)), o.max_h_m);
    bp.courant = o.courant_factor * kSrlCourantLimit;
    bp.dt_s = bp.courant * bp.h_m / c;
    const FdtdGridSize size = fdtdGridSize(room, bp.h_m, o.margin_cells);
    bp.nx = size.nx, bp.ny = size.ny, bp.nz = size.nz;
    const RickerPulse pulse{room.bands.centreHz(b)};
    bp.steps = static_cast<long>(std::ceil((plan.length_s + pulse.delay()) / bp.dt_s)) + 1;
    bp.phase_error_top = srlAxialPhaseVelocityRatio(room.bands.upperHz(b), bp.h_m, bp.dt_s, c) - 1.0;
    // Fields (2 floats), flags (1 byte), the flood fill's stack (4 bytes, worst case), blocked links (≤ √3·S/h²
    // per side, 16 bytes, twice while sorting) and boundary nodes (16 bytes), recordings (4 bytes per sample and
    // point) and the analysis (a few doubles per sample).
    const double links = 2.0 * std::sqrt(3.0) * surface / (bp.h_m * bp.h_m);
    const double samples = static_cast<double>(bp.steps + 1);
    bp.bytes = size.nodes() * (FdtdScheme::kBytesPerNode + 1.0 + 4.0) + links * (32.0 + 16.0) +
               samples * (4.0 * o.max_points * static_cast<double>(room.listeners.size()) + 64.0);
    const std::string band = room.bands.label(b) + " Hz";
    if (size.nodes() >= 4.0e9 || (plan.physical_bytes > 0.0 && bp.bytes > 0.5 * plan.physical_bytes))
      throw core::InputError(o.bands_hz.empty() ? where(room) : "--bands",
                             "cannot resolve the " + band +
                                 format(" band: its grid (h = %.4g m, %.3g nodes) needs about %.1f GB, more than half of "
                                        "this machine's %.1f GB (lower --ppw or leave the band out)",
                                        bp.h_m, size.nodes(), bp.bytes / 1e9, plan.physical_bytes / 1e9));
    plan.total_steps += static_cast<std::uint64_t>(bp.steps) * room.sources.size();
    plan.bands.push_back(bp);
  }
  for (const auto& s : room.sources)
    if (s.directivity.a != 1.0)
      plan.warnings.push_back("source " + s.name + ": the FDTD source is omnidirectional; its " + s.directivity.pattern +
                              " pattern is ignored");
  return plan;
}

WaveResult simulateWave(const room::Room& room, const WaveOptions& o) {
  WaveResult result;
  result.plan = planWave(room, o);
  const WavePlan& plan = result.plan;
  result.warnings = plan.warnings;
  const double c = plan.speed_of_sound_m_s;
  for (const auto& bp : plan.bands) buildBandGrid(room, o, bp);  // every check before the first time step
  if (o.on_start) o.on_start();
  const int bins = static_cast<int>(std::ceil(plan.length_s / plan.bin_s - 1e-9));
  result.listeners.resize(room.listeners.size());
  double power = 0.0;
  for (const auto& s : room.sources) power += s.power_w;
  std::uint64_t reported = 0;
  for (const auto& bp : plan.bands) {
    const auto t0 = std::chrono::steady_clock::now();
    const int b = bp.band;
    std::unique_ptr<BandGrid> bg = buildBandGrid(room, o, bp);
    std::vector<double> beta;
    for (std::size_t mi = 0; mi < room.materials.size(); ++mi) {
      const auto& m = room.materials[mi];
      bool clamped = false;
      if (room.isOpening(static_cast<int>(mi))) {  // transparent: blocks no link
        beta.push_back(0.0);
        continue;
      }
      beta.push_back(admittanceForAbsorption(m.absorption[b], &clamped));
      if (clamped)
        result.warnings.push_back("material " + m.name + ": absorption " + format("%.3g", m.absorption[b]) + " in the " +
                                  room.bands.label(b) + format(" Hz band is above a real impedance's maximum %.4f; clamped",
                                                               maxParisAbsorption()));
    }
    const RickerPulse pulse{room.bands.centreHz(b)};
    const std::size_t samples = static_cast<std::size_t>(bp.steps) + 1;
    // Calibration: the band energy of the free field at 10 m of one source of power P is P/100 (header).
    std::vector<double> s(samples);
    for (std::size_t n = 0; n < samples; ++n) s[n] = pulse(static_cast<double>(n) * bp.dt_s);
    const std::vector<double> s_band = bandPass(s, bp.dt_s, room.bands.lowerHz(b), room.bands.upperHz(b));
    double pulse_energy = 0.0;
    for (double v : s_band) pulse_energy += v * v * bp.dt_s;
    const double ff = freeFieldFactor(bp.h_m, bp.dt_s, c);
    const double e_ff10 = (ff / 10.0) * (ff / 10.0) * pulse_energy;

    std::vector<std::vector<double>> energy(room.listeners.size(), std::vector<double>(static_cast<std::size_t>(bins), 0.0));
    for (std::size_t si = 0; si < room.sources.size(); ++si) {
      FdtdScheme scheme(bg->grid, bp.courant, beta);
      std::vector<std::vector<std::vector<float>>> rec(room.listeners.size());
      for (std::size_t l = 0; l < rec.size(); ++l)
        rec[l].assign(bg->points[l].size(), std::vector<float>(samples, 0.0f));
      for (long n = 0; n < bp.steps; ++n) {
        scheme.step();
        scheme.inject(bg->sources[si], static_cast<float>(s[static_cast<std::size_t>(n)]));
        const float* p = scheme.current();
        for (std::size_t l = 0; l < rec.size(); ++l)
          for (std::size_t q = 0; q < rec[l].size(); ++q) rec[l][q][static_cast<std::size_t>(n) + 1] = p[bg->points[l][q]];
        if (o.on_progress && (n % 64 == 63 || n + 1 == bp.steps)) {
          o.on_progress(static_cast<std::uint64_t>(n + 1) - reported);
          reported = static_cast<std::uint64_t>(n + 1);
        }
      }
      reported = 0;
      const double scale = (room.sources[si].power_w / 100.0) / e_ff10;
      for (std::size_t l = 0; l < rec.size(); ++l)
        for (const auto& r : rec[l]) {
          const std::vector<double> x = bandPass(std::vector<double>(r.begin(), r.end()), bp.dt_s, room.bands.lowerHz(b),
                                                 room.bands.upperHz(b));
          const std::vector<double> e = energyHistogram(x, bp.dt_s, pulse.delay(), plan.bin_s, bins);
          for (int k = 0; k < bins; ++k)
            energy[l][static_cast<std::size_t>(k)] += scale * e[static_cast<std::size_t>(k)] / static_cast<double>(rec[l].size());
        }
    }
    for (std::size_t l = 0; l < room.listeners.size(); ++l) {
      double total = 0.0;
      for (double e : energy[l]) total += e;
      result.listeners[l].g_db.push_back(10.0 * std::log10(100.0 * total / power));
      result.listeners[l].energy.push_back(std::move(energy[l]));
      result.listeners[l].points.push_back(static_cast<int>(bg->points[l].size()));
    }
    result.air_nodes.push_back(bg->grid.air_nodes);
    result.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  for (auto& l : result.listeners) l.metrics = ir::metricsFromHistograms(l.energy, plan.bin_s);
  return result;
}

}  // namespace diffray::reference
