#include "diffray/transport/room_simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/ir/metrics.h"
#include "diffray/room/air.h"
#include "diffray/room/checks.h"
#include "diffray/transport/image_sources.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/transport/room_tracer.h"
#include "diffray/utd/paths.h"

namespace diffray::transport {

namespace {

// Per band, Σ area·α and Σ area·τ over the room's triangles, and the total area (m²).
struct SurfaceSums {
  core::BandArray absorbed = core::bandFill(0.0), transmitted = core::bandFill(0.0);
  double area = 0.0;
};

SurfaceSums surfaceSums(const room::Room& room) {
  SurfaceSums sums;
  const auto& mesh = room.mesh;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const double a = 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
    sums.area += a;
    const room::Material& m = room.materials[mesh.object_of_triangle[i]];
    for (int b = 0; b < room.bands.size(); ++b) {
      sums.absorbed[b] += a * m.absorption[b];
      sums.transmitted[b] += a * m.transmission[b];
    }
  }
  return sums;
}

}  // namespace

core::BandArray eyringT60(const room::Room& room, double speed_of_sound_m_s, const core::BandArray& air_m_per_m) {
  const int nb = room.bands.size();
  const SurfaceSums sums = surfaceSums(room);
  const core::BandArray& absorbed = sums.absorbed;
  const double area = sums.area;
  const double volume = room.volume();
  core::BandArray t60 = core::bandFill(0.0);
  for (int b = 0; b < nb; ++b) {
    const double mean_alpha = std::min(absorbed[b] / area, 1.0 - 1e-12);
    const double denom = speed_of_sound_m_s * (-area * std::log(1.0 - mean_alpha) + 4.0 * air_m_per_m[b] * volume);
    t60[b] = denom > 0.0 ? 24.0 * std::log(10.0) * volume / denom : 0.0;
  }
  return t60;
}

namespace {

constexpr double kPilotBinS = 0.01;  ///< the pilot's histogram bins

// When the room's energy has fallen by 60 dB, the latest over the bands, from a short pilot trace (rays
// alone, 10 ms bins, up to max_length_s): the energy still in flight in the room, whose level is read
// where it first drops below −60 dB of its peak, or else extrapolated to −60 dB from a least-squares
// line through its last 20 dB (a non-diffuse room's late decay is its slowest). NaN if no band decayed.
// With the WBSDF's occluders, as the trace will have them: an opening that returns what it does not carry
// lets a room behind it ring longer than an open door would.
double pilotT60(const room::Room& room, const RoomGeometry& geometry, const RoomSimulation& sim, std::uint64_t seed,
                std::uint64_t rays, const RoomOccluders* occluders, const RoomSimulationOptions& options) {
  RoomTraceOptions to;
  to.occluders = occluders;
  to.max_diffractions = options.max_diffractions;
  to.portal = options.portal;
  to.rays = rays;
  to.seed = seed ^ 0x5eedf00dull;
  to.length_s = room.output.max_length_s;
  to.bin_s = kPilotBinS;
  to.skip_order = -1;
  to.speed_of_sound_m_s = sim.speed_of_sound_m_s;
  to.air_m_per_m = sim.air_m_per_m;
  to.in_flight = true;
  to.batches = 0;  // the pilot needs no standard errors
  const RoomTraceResult res = traceRoom(room, geometry, 0, to);
  double latest = std::numeric_limits<double>::quiet_NaN();
  for (int b = 0; b < room.bands.size(); ++b) {
    const std::vector<double> e = res.in_flight.band(b);
    const double peak = *std::max_element(e.begin(), e.end());
    if (!(peak > 0.0)) continue;
    std::vector<double> level(e.size());
    for (std::size_t k = 0; k < e.size(); ++k) level[k] = e[k] > 0.0 ? 10.0 * std::log10(e[k] / peak) : -1e300;
    const auto time = [&](std::size_t k) { return (static_cast<double>(k) + 0.5) * to.bin_s; };
    const std::size_t peak_k = static_cast<std::size_t>(std::max_element(e.begin(), e.end()) - e.begin());
    std::size_t below = peak_k;  // first bin past the peak below −60 dB
    while (below < e.size() && level[below] >= -60.0) ++below;
    double t = below < e.size() ? time(below) : std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(t)) {
      // Not reached in max_length_s: extrapolate the last 20 dB above the pilot's floor.
      double lowest = 0.0;
      for (std::size_t k = peak_k; k < e.size(); ++k) lowest = std::min(lowest, std::max(level[k], -60.0));
      const double hi = std::min(-5.0, lowest + 20.0);
      double n = 0, st = 0, sl = 0, stt = 0, stl = 0, t_last = 0, l_last = 0;
      for (std::size_t k = peak_k; k < e.size(); ++k) {
        if (level[k] > hi || level[k] < lowest) continue;
        n += 1;
        st += time(k);
        sl += level[k];
        stt += time(k) * time(k);
        stl += time(k) * level[k];
        t_last = time(k);
        l_last = level[k];
      }
      const double slope = n >= 3 ? (n * stl - st * sl) / (n * stt - st * st) : 0.0;  // dB per second
      if (slope < 0.0) t = t_last + (60.0 + l_last) / -slope;
    }
    if (std::isfinite(t) && !(t <= latest)) latest = t;
  }
  return latest;
}

// Rays of the pilot run: 20,000, fewer in rooms whose rays bounce very often (at most 1e8 wall hits).
double pilotRays(double bounces_per_ray) { return std::clamp(1e8 / bounces_per_ray, 500.0, 20000.0); }

// Wall hits a ray makes on average, at most: the path over the mean free path 4V/S, or the bounces until
// Russian roulette (−60 dB, roulette_level) ends it at the least absorbing band's mean absorption.
double bouncesPerRay(const room::Room& room, double length_s, double c) {
  const double volume = room.volume(), area = room.surfaceArea();
  if (!(volume > 0.0) || !(area > 0.0)) return length_s * c;  // no enclosure: a 1 m free path as the bound
  // An enclosure that holds no source (a closed object in the open, such as a cupboard): its volume says
  // nothing about the rays' paths, which leave into free space; the 1 m free path again.
  const bool enclosed = std::any_of(room.sources.begin(), room.sources.end(),
                                    [&](const room::Source& s) { return room::insideRoom(room, s.position_m); });
  double free_path = enclosed ? 4.0 * volume / area : 1.0;
  // A mesh with open edges has a volume only as good as its gaps allow (walls standing in free field can
  // sum to almost nothing, and a source beside them can test inside): its free path is at least 1 m.
  if (enclosed && room::openEdgeCount(room) > 0) free_path = std::max(free_path, 1.0);
  const double by_length = length_s * c / free_path;
  const SurfaceSums sums = surfaceSums(room);
  double least = 1.0;  // the smallest mean fraction that leaves the room for good at a hit: α − τ
  for (int b = 0; b < room.bands.size(); ++b) least = std::min(least, (sums.absorbed[b] - sums.transmitted[b]) / area);
  const double by_roulette = least > 0.0 ? std::log(1e6) / -std::log1p(-std::min(least, 1.0 - 1e-12)) : 1e300;
  return std::min(by_length, by_roulette);
}

void checkWorkload(const room::Room& room, const RoomSimulation& sim, double length_s, std::uint64_t rays,
                   bool pilot) {
  constexpr double kMaxQueries = 5e9;  // ~8 min at the ~10M wall hits per second of 2 cores
  const double per_ray = bouncesPerRay(room, length_s, sim.speed_of_sound_m_s);
  const double queries =
      per_ray * (static_cast<double>(rays) * static_cast<double>(room.sources.size()) + (pilot ? pilotRays(per_ray) : 0.0));
  if (queries > kMaxQueries) {
    std::ostringstream msg;
    msg.precision(3);
    msg << "about " << queries << " wall hits (" << per_ray << " per ray over " << length_s
        << " s): the room absorbs too little or is too small for that length; set output.ir_length_s or "
           "output.max_length_s shorter, or use fewer rays";
    throw core::InputError(room.file.empty() ? "room" : room.file, msg.str());
  }
}

}  // namespace

RoomSimulation simulateRoom(const room::Room& room, const RoomSimulationOptions& options) {
  if (room.sources.empty()) throw core::InputError(room.file, "sources: at least one source is needed");
  if (room.listeners.empty()) throw core::InputError(room.file, "listeners: at least one listener is needed");
  RoomSimulation sim;
  sim.speed_of_sound_m_s = room::speedOfSound(room.air);
  sim.air_m_per_m = room::airAttenuationPerM(room.air, room.bands);
  sim.ism_order = options.ism_order == -2 ? room.output.ism_order : options.ism_order;
  const std::uint64_t rays = options.rays ? options.rays : room.output.rays;
  const int nb = room.bands.size();

  // The IR length: given, or auto from Eyring (see the header).
  const core::BandArray t60 = eyringT60(room, sim.speed_of_sound_m_s, sim.air_m_per_m);
  sim.eyring_t60_s = *std::max_element(t60.begin(), t60.begin() + nb);
  double direct = 0.0;
  for (const auto& s : room.sources)
    for (const auto& l : room.listeners) direct = std::max(direct, (s.position_m - l.position_m).norm() / sim.speed_of_sound_m_s);
  const RoomGeometry geometry(room, options.brute_force);
  if (options.diffraction != "none" && options.diffraction != "wbsdf" && options.diffraction != "utd")
    throw core::InputError("--diffraction", "must be none, wbsdf or utd, got " + options.diffraction);
  std::unique_ptr<RoomOccluders> occluders;
  if (options.diffraction == "wbsdf") {
    if (room.occluders.empty())
      sim.warnings.push_back("--diffraction wbsdf: the room has no occluders (rooms/README.md, \"occluders\"); "
                             "nothing diffracts");
    else
      occluders = std::make_unique<RoomOccluders>(room, sim.speed_of_sound_m_s / room.bands.upperHz(nb - 1));
  }
  sim.length_s = options.length_s > 0 ? options.length_s : room.output.ir_length_s;
  const bool automatic = !(sim.length_s > 0);
  // Refuse work that would not end in reasonable time, before any of it starts: a lossless or tiny room
  // followed for max_length_s makes every ray bounce length·c / (mean free path) times.
  checkWorkload(room, sim, automatic ? room.output.max_length_s : sim.length_s, rays, automatic);
  if (!automatic) {
    histogramBins(sim.length_s, room.output.histogram_bin_s, nb, room.listeners.size());
  } else {
    // The pilot histograms max_length_s in its own bins for every listener. Past the limit, histogramBins
    // names output.histogram_bin_s and the pilot's 10 ms, neither of which the user set: name what they did.
    try {
      histogramBins(room.output.max_length_s, kPilotBinS, nb, room.listeners.size());
    } catch (const core::InputError& e) {
      const std::string what = e.what(), reason = e.where().empty() ? what : what.substr(e.where().size() + 2);
      throw core::InputError((room.file.empty() ? std::string("room") : room.file) + ": output.max_length_s",
                             "with no IR length set, a pilot trace over max_length_s measures the length, and " +
                                 reason.substr(0, reason.find("; use")) +
                                 "; set output.ir_length_s (or ir's --length), or a shorter output.max_length_s");
    }
  }
  if (options.on_start) options.on_start();
  if (automatic) {
    // "auto": a pilot run measures the decay (Eyring misjudges non-diffuse rooms: a shoebox with an
    // absorbing floor and ceiling rings on between its hard walls for twice as long).
    const double per_ray = bouncesPerRay(room, room.output.max_length_s, sim.speed_of_sound_m_s);
    sim.pilot_t60_s = pilotT60(room, geometry, sim, options.seed, static_cast<std::uint64_t>(pilotRays(per_ray)),
                              occluders.get(), options);
    const double decay_s = std::isfinite(sim.pilot_t60_s) ? sim.pilot_t60_s : 1.5 * sim.eyring_t60_s + direct;
    sim.length_s = std::min(room.output.max_length_s, decay_s + 0.05);
  }
  // Refuse histograms too large for memory now, not after the image sources.
  histogramBins(sim.length_s, room.output.histogram_bin_s, nb, room.listeners.size(), options.directions);
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    ir::EnergyResponse r;
    r.bands = room.bands;
    r.bin_s = room.output.histogram_bin_s;
    sim.listeners.push_back(r);
  }
  // Image sources: exact arrivals per source–listener pair.
  const auto t_ism = std::chrono::steady_clock::now();
  if (sim.ism_order >= 0) {
    ImageSourceOptions io;
    io.max_order = sim.ism_order;
    io.length_s = sim.length_s;
    io.speed_of_sound_m_s = sim.speed_of_sound_m_s;
    io.air_m_per_m = sim.air_m_per_m;
    if (occluders) io.blocking_triangles = &occluders->triangleMask();
    for (int s = 0; s < static_cast<int>(room.sources.size()); ++s)
      for (int l = 0; l < static_cast<int>(room.listeners.size()); ++l) {
        auto arrivals = imageSources(room, geometry, s, l, io);
        sim.image_sources += arrivals.size();
        auto& dst = sim.listeners[l].arrivals;
        dst.insert(dst.end(), arrivals.begin(), arrivals.end());
      }
    for (auto& r : sim.listeners)
      std::sort(r.arrivals.begin(), r.arrivals.end(),
                [](const ir::Arrival& a, const ir::Arrival& b) { return a.delay_s < b.delay_s; });
  }
  // UTD: the first- and second-order edge-diffraction paths of every source–listener pair, added at their
  // exact delays as arrivals; the geometric part stays with the image sources and the rays (openings pass
  // them straight).
  if (options.diffraction == "utd") {
    utd::UtdOptions uo;
    uo.material_reflection = true;
    const utd::UtdModel model(room, geometry, uo);
    for (int s = 0; s < static_cast<int>(room.sources.size()); ++s)
      for (int l = 0; l < static_cast<int>(room.listeners.size()); ++l) {
        const room::Source& src = room.sources[s];
        const std::vector<utd::Path> paths = model.paths(src.position_m, room.listeners[l].position_m);
        for (const utd::PathEnergy& pe : model.bandEnergies(paths, sim.speed_of_sound_m_s, 16, true)) {
          if (pe.delay_s > sim.length_s) continue;
          const utd::Path& path = paths[pe.path];
          const core::Vec3 first_leg = (path.points[1] - path.points[0]).normalized();
          const double gain = src.power_w * directivityGain(src.directivity, first_leg.dot(src.directivity.axis.normalized()));
          ir::Arrival a;
          a.delay_s = pe.delay_s;
          a.order = path.order;
          a.direction = (path.points[path.points.size() - 2] - path.points.back()).normalized();
          for (int b = 0; b < nb; ++b) a.energy[b] = pe.energy[b] * gain * std::exp(-sim.air_m_per_m[b] * path.length_m);
          sim.listeners[l].arrivals.push_back(a);
          ++sim.diffraction_paths;
        }
      }
    for (auto& r : sim.listeners)
      std::sort(r.arrivals.begin(), r.arrivals.end(),
                [](const ir::Arrival& a, const ir::Arrival& b) { return a.delay_s < b.delay_s; });
  }
  sim.ism_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_ism).count();

  // Rays: each source in turn, histograms summed per listener.
  RoomTraceOptions to;
  to.rays = rays;
  to.length_s = sim.length_s;
  to.bin_s = room.output.histogram_bin_s;
  to.skip_order = sim.ism_order;
  to.speed_of_sound_m_s = sim.speed_of_sound_m_s;
  to.air_m_per_m = sim.air_m_per_m;
  to.on_progress = options.on_progress;
  to.occluders = occluders.get();
  to.max_diffractions = options.max_diffractions;
  to.portal = options.portal;
  to.directions = options.directions;
  std::vector<std::uint64_t> crossings;
  std::vector<receiver::DirectionHistogram> directions;
  for (int s = 0; s < static_cast<int>(room.sources.size()); ++s) {
    to.seed = options.seed + 1000003ull * static_cast<std::uint64_t>(s);  // independent streams per source
    RoomTraceResult res = traceRoom(room, geometry, s, to);
    crossings.resize(res.crossings.size(), 0);
    for (std::size_t l = 0; l < res.crossings.size(); ++l) crossings[l] += res.crossings[l];
    if (sim.traced.empty()) {
      sim.traced = res.listeners;
      directions = res.directions;
    } else {
      for (std::size_t l = 0; l < sim.traced.size(); ++l) sim.traced[l].merge(res.listeners[l]);
      for (std::size_t l = 0; l < directions.size() && l < res.directions.size(); ++l)
        directions[l].merge(res.directions[l]);
    }
    sim.rays += res.rays;
    sim.segments += res.segments;
    sim.escaped += res.escaped;
    sim.roulette_killed += res.roulette_killed;
    sim.timed_out += res.timed_out;
    sim.occluder_events += res.occluder_events;
    sim.evanescent += res.evanescent;
    sim.trace_seconds += res.seconds;
    // A closed mesh loses up to about one ray in 100,000 where a hit lands within float rounding of a
    // corner; a real gap or a source outside loses far more. Warn above 1e-4 (the count is in the stats).
    if (static_cast<double>(res.escaped) > 1e-4 * static_cast<double>(res.rays)) {
      std::ostringstream w;
      w << "source " << room.sources[s].name << ": " << res.escaped << " of " << res.rays << " rays ("
        << 100.0 * static_cast<double>(res.escaped) / static_cast<double>(res.rays)
        << " %) left the room: a gap in the mesh, or the source is outside the room";
      sim.warnings.push_back(w.str());
    }
  }
  for (std::size_t l = 0; l < crossings.size(); ++l)
    if (crossings[l] < 100) {
      std::ostringstream w;
      w << "listener " << room.listeners[l].name << " was crossed by " << crossings[l]
        << " ray segments only: its traced (late) part is mostly noise; use a larger radius_m or more rays";
      sim.warnings.push_back(w.str());
    }
  for (std::size_t l = 0; l < sim.listeners.size(); ++l) {
    auto& r = sim.listeners[l];
    r.traced.assign(nb, std::vector<double>(sim.traced[l].bins(), 0.0));
    for (int b = 0; b < nb; ++b)
      for (int i = 0; i < sim.traced[l].bins(); ++i) r.traced[b][i] = sim.traced[l].value(b, i);
    const receiver::EnergyHistogram& h = sim.traced[l];
    if (l < directions.size()) {
      r.directions.assign(nb, std::vector<core::Vec3>(static_cast<std::size_t>(h.bins()), core::Vec3(0, 0, 0)));
      for (int b = 0; b < nb; ++b)
        for (int i = 0; i < h.bins(); ++i) r.directions[b][i] = directions[l].value(b, i);
    }
    for (int k = 0; k < h.batches(); ++k) {
      if (!(h.batchWeight(k) > 0.0)) continue;
      r.batch_weights.push_back(h.batchWeight(k));
      r.batches.emplace_back(nb, std::vector<double>(static_cast<std::size_t>(h.bins()), 0.0));
      for (int b = 0; b < nb; ++b)
        for (int i = 0; i < h.bins(); ++i) r.batches.back()[b][i] = h.batchValue(k, b, i);
    }
  }
  return sim;
}

}  // namespace diffray::transport
