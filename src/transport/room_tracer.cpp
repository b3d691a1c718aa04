#include "diffray/transport/room_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/rng.h"
#include "diffray/geometry/embree_scene.h"
#include "diffray/transport/room_lanes.h"
#include "diffray/transport/room_materials.h"
#include "diffray/transport/room_tracer_core.h"

namespace diffray::transport {

using core::Vec3;

namespace {

// The emission direction is the only quasi-random part of a path (a 2D R2 lattice, core::ChunkSampler):
// it decides the early reflections, where QMC pays; bounces use the chunk's Rng.
constexpr double kGenerators[2] = {0.7548776662466927, 0.5698402909980532};
// With occluders, the first WBSDF draw (the x shift's two uniforms) and the band choice are quasi-random
// too, paired with the emission (5D R-sequence, φ₅ the root of x⁶ = x + 1): the edge diffraction a listener
// hears is a small signed residue of many rays, and stratifying (emission point, shift, band) together
// lowers its noise, as the optical tracer does for its first scattering (transport/tracer.cpp).
constexpr double kGenerators5[5] = {0.8812714616335696, 0.7766393890897682, 0.6844301295853426,
                                    0.6031687406857283, 0.5315553977157913};


}  // namespace

namespace detail {

template <int NB, class Energy>
void Tracer::score(RoomTraceResult& acc, const Vec3& pos, const Vec3& dir, double t_end, double path_m,
                 const Energy& energy, double scale, bool skip, std::uint64_t skip_listeners) const {
  // Most segments miss every listener: first a branchless test over all of them, then one well-predicted
  // branch, and chordSpan only when some sphere may be near. A segment meets a sphere only if its line
  // passes within r of the centre and the centre projects within r of [0, t_end] on it: the largest of
  // the three signed excesses is then negative (each with a margin above its rounding, so that the test
  // never rejects a segment chordSpan would accept). Two spheres at a time (a Pair: one SSE2 register).
  if (pair_count == 0) return;
  const Pair px = {pos.x(), pos.x()}, py = {pos.y(), pos.y()}, pz = {pos.z(), pos.z()};
  const Pair dx = {dir.x(), dir.x()}, dy = {dir.y(), dir.y()}, dz = {dir.z(), dir.z()}, te = {t_end, t_end};
  const auto excessOf = [&](const ListenerPair& lp) {
    const Pair ox = px - lp.x, oy = py - lp.y, oz = pz - lp.z;
    const Pair b = ox * dx + oy * dy + oz * dz;
    const Pair off_line = ox * ox + oy * oy + oz * oz - b * b - lp.r2_plus_margin;
    const Pair behind = b - lp.r_slack, beyond = -b - te - lp.r_slack;
    const Pair outside = behind > beyond ? behind : beyond;
    return off_line > outside ? off_line : outside;
  };
  // The least excess per lane (a NaN excess is never taken: it fails the comparison).
  const Pair one = {1.0, 1.0};
  Pair closest = lesser(excessOf(listener_pairs[0]), one);
  for (int k = 1; k < pair_count; ++k) closest = lesser(excessOf(listener_pairs[k]), closest);
  if (!anySignBit(closest)) return;  // every excess ≥ 0 (a −0 goes on: chordSpan decides)
  // Some sphere may be near (one segment in ~20 on the shoebox): the pairs again, and chordSpan only for
  // the lanes whose excess is negative. Copies: chordSpan takes addresses, which would otherwise keep the
  // loop's pos and dir in memory.
  const double o[3] = {pos.x(), pos.y(), pos.z()}, d[3] = {dir.x(), dir.y(), dir.z()};
  for (int k = 0; k < pair_count; ++k) {
    const int near = signBits(excessOf(listener_pairs[k]));
    if (near & 1) scoreListener<NB>(acc, 2 * static_cast<std::size_t>(k), o, d, t_end, path_m, energy, scale, skip,
                                    skip_listeners);
    if (near & 2) scoreListener<NB>(acc, 2 * static_cast<std::size_t>(k) + 1, o, d, t_end, path_m, energy, scale,
                                    skip, skip_listeners);
  }
}

template <int NB, class Energy>
void Tracer::scoreListener(RoomTraceResult& acc, std::size_t l, const double* o, const double* d, double t_end,
                         double path_m, const Energy& energy, double scale, bool skip,
                         std::uint64_t skip_listeners) const {
  const int nb = NB > 0 ? NB : bands;
  double t_in, t_out;
  if (!spheres[l].chordSpan(o, d, 0.0, t_end, t_in, t_out)) return;
  ++acc.crossings[l];
  if (skip || (l < 64 && (skip_listeners >> l & 1u))) return;
  const double s_mid = path_m + 0.5 * (t_in + t_out);
  const int bin = acc.listeners[l].binOf(s_mid / opt.speed_of_sound_m_s);
  if (bin < 0) return;
  // Track-length estimator over the cross-section: fluence (receiver/sphere.h).
  const double w = scale * spheres[l].chordWeight(t_out - t_in) / spheres[l].crossSection();
  // Air: e^{−m s} = (tabulated e^{−m s_k} at the bin's centre s_k)·e^{−m (s − s_k)}, the second factor
  // by its Taylor series to x³/6 with x = m·(s − s_k), |x| ≤ m·c·bin/2 (< 0.005 at 8 kHz): relative
  // error below 2e-8, no exp per band in the hot loop.
  const double ds = s_mid - air_centre_m[bin];
  const double* att = &air_table[static_cast<std::size_t>(bin) * static_cast<std::size_t>(nb)];
  double* row = acc.listeners[l].openRow(bin);
  if (!opt.directions) {
    for (int b = 0; b < nb; ++b) {
      const double x = opt.air_m_per_m[b] * ds;
      row[b] += energy[b] * att[b] * (1.0 - x * (1.0 - x * (0.5 - x / 6.0))) * w;
    }
    return;
  }
  double* to = acc.directions[l].row(bin);  // the energy arrives from −d
  for (int b = 0; b < nb; ++b) {
    const double x = opt.air_m_per_m[b] * ds;
    const double e = energy[b] * att[b] * (1.0 - x * (1.0 - x * (0.5 - x / 6.0))) * w;
    row[b] += e;
    to[3 * b] -= e * d[0];
    to[3 * b + 1] -= e * d[1];
    to[3 * b + 2] -= e * d[2];
  }
}

Tracer::SegmentHit Tracer::cast(const Vec3& o, const Vec3& d) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = geometry::makeRayHit(o, d, 0.0, 1e300);
  return cast(o, d, context, rh);
}

Tracer::SegmentHit Tracer::cast(const Vec3& o, const Vec3& d, RTCIntersectContext& context, RTCRayHit& rh) const {
  SegmentHit h;
  const RTCScene scene = geometry.embreeScene();
  if (!scene) {
    const geometry::Hit g = geometry.intersector().intersect(geometry::Ray{o, d, 0.0, 1e300});
    h.t = g.t;
    h.triangle = g.valid() ? g.triangle : -1;
    return h;
  }
  geometry::aimRayHit(rh, o, d);
  rtcIntersect1(scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.t = rh.ray.tfar;
  h.triangle = static_cast<int>(rh.hit.primID);
  h.interior = std::min(std::min(rh.hit.u, rh.hit.v), 1.0f - rh.hit.u - rh.hit.v) > 1e-4f;
  return h;
}

template <class Energy>
void Tracer::addInFlight(RoomTraceResult& acc, double path_m, double length, const Energy& energy, double scale) const {
  receiver::EnergyHistogram& h = acc.in_flight;
  const double c = opt.speed_of_sound_m_s;
  const double t_start = path_m / c, t_stop = std::min((path_m + length) / c, h.lengthSeconds());
  int bin = h.binOf(t_start);
  if (bin < 0) return;
  // Bins by index, so that a start on a bin edge can never stall the loop.
  for (double t0 = t_start; bin < h.bins() && t0 < t_stop; ++bin) {
    const double edge = std::min(t_stop, (bin + 1) * h.binSeconds());
    if (edge > t0)
      for (int b = 0; b < bands; ++b) h.add(b, bin, scale * energy[b] * std::exp(-opt.air_m_per_m[b] * path_m) * (edge - t0));
    t0 = std::max(t0, edge);
  }
}

void Tracer::tracePath(RoomTraceResult& acc, core::FastRng& rng, const Vec3& start, const Vec3& dir0,
                     const core::BandArray& energy0, const double* qmc) const {
  Path s{start, dir0, energy0};
  s.e_start = *std::max_element(s.e.begin(), s.e.begin() + bands);
  if (qmc) {
    s.has_qmc = true;
    std::copy(qmc, qmc + 3, s.qmc);
  }
  // Octave bands (8, every shipped room) get the hot loop with a fixed band count.
  if (bands == 8) follow<8>(acc, rng, s);
  else follow<0>(acc, rng, s);
}

template <int NB>
void Tracer::follow(RoomTraceResult& acc, core::FastRng& rng, Path& s) const {
  Vec3 pos = s.pos, dir = s.dir;
  // Octaves carry the energies relative to the emitted level (scores multiply it back).
  const double scale = NB == 8 && s.e_start > 0.0 && std::isfinite(s.e_start) ? s.e_start : 1.0;
  typename EnergyOf<NB>::type e = carried<NB>(s.e, scale);
  double path_m = s.path_m;
  int order = s.order;
  bool specular_chain = s.specular_chain;
  std::uint64_t skip_next = s.skip_next_score, skip_after_floor = s.skip_after_floor;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit ray = geometry::makeRayHit(pos, dir, 0.0, 1e300);
  // Options read once (opt is a reference: each use would be two loads). Roulette's threshold (on the
  // Path's energies, and relative to `scale` on e), the latter also as four floats rounded up, so that a
  // band at or above them is at or above it.
  const bool in_flight = opt.in_flight;
  const int skip_order = opt.skip_order;
  const double threshold = opt.roulette_level * s.e_start, threshold_e = threshold / scale;
  float threshold_f = static_cast<float>(threshold_e);
  if (threshold_f < threshold_e) threshold_f = std::nextafter(threshold_f, HUGE_VALF);
  const Quad threshold4 = {threshold_f, threshold_f, threshold_f, threshold_f};
  for (;;) {
    // tnear 0: the origin sits eps_m off the surface it left, on the side it travels (15× Embree's float
    // rounding), so that surface cannot be hit again, while a wall meeting it at a corner still can.
    SegmentHit hit = cast(pos, dir, context, ray);
    ++acc.segments;
    if (!hit.valid()) {
      // Embree's fast (non-watertight) traversal can let a ray through the shared edge of two triangles:
      // about one ray in 30,000 in a finely tessellated room. Escapes are rare, so look again along a
      // direction turned by ~1e-6 rad before believing one (a real opening lets the retry out too).
      const Vec3 nudged = (dir + 1e-6 * Vec3(dir.y() - dir.z(), dir.z() - dir.x(), dir.x() - dir.y())).normalized();
      hit = cast(pos, nudged, context, ray);
      ++acc.segments;
    }
    // Embree's distance is float. Well inside a triangle the hit point is put back on its plane by a
    // projection (no division on the critical path); near an edge the distance is refined in double on
    // the plane instead, so a hit within float rounding of a corner cannot land outside the
    // neighbouring wall (which would let the ray slip out).
    double t_hit = 1e300;
    bool project = false;
    if (hit.valid()) {
      if (hit.interior) {
        t_hit = hit.t;
        project = true;
      } else {
        t_hit = geometry.planeDistance(hit.triangle, pos, dir);
        if (!(t_hit >= 0.0 && t_hit < 1e300)) t_hit = hit.t;
      }
    }
    const double remaining = max_path_m - path_m;
    const double t_end = std::min(t_hit, remaining);
    score<NB>(acc, pos, dir, t_end, path_m, e, scale, specular_chain && order <= skip_order, skip_next);
    skip_next = 0;
    if (in_flight) addInFlight(acc, path_m, t_end, e, scale);
    if (!hit.valid()) {
      ++acc.escaped;
      return;
    }
    if (t_hit >= remaining) {
      ++acc.timed_out;
      return;
    }
    path_m += t_hit;
    const TrianglePlane& tri = geometry.triangle(hit.triangle);
    const double dn = tri.normal.dot(dir);
    // The projection's distance off the plane, (n·pos − offset) + t·(n·dir) of the old pos (so the chain
    // from Embree's t is short), taken off below together with the offset off the surface.
    double off_plane = project ? tri.normal.dot(pos) - tri.offset + t_hit * dn : 0.0;
    pos += t_hit * dir;
    std::uint64_t after_floor = 0;  // only the first bounce after an occluder (rare: kept off the common path)
    if (skip_after_floor) {
      after_floor = skip_after_floor;
      skip_after_floor = 0;
    }
    const int m = tri.material;
    // The normal facing the ray is side·n; the offsets off the surface below are ±eps_m along it.
    const double side = dn < 0.0 ? 1.0 : -1.0;
    if (special[hit.triangle]) {  // the cold cases: an occluder, an opening, a surface absorbing all
      pos -= off_plane * tri.normal;
      off_plane = 0.0;  // applied: a surface event below must not take it off again
      const Vec3 n_in = side * tri.normal;
      if (opt.occluders) {
        const int k = opt.occluders->occluderOf(hit.triangle);
        const bool scatters = k >= 0 && s.diffractions < opt.max_diffractions;
        // Once the path's WBSDF scatterings are spent, an opening that returns energy still divides it:
        // through or back, per band.
        if (scatters || (k >= 0 && opt.occluders->returnsEnergy(k))) {
          // The occluder code works on the Path.
          s.e = asBands(e, scale);
          s.pos = pos, s.dir = dir, s.path_m = path_m, s.order = order, s.specular_chain = specular_chain;
          if (!scatters) {
            passOpening(rng, s, k, n_in);
          } else if (opt.portal && opt.next_event && opt.occluders->nextEventSupported(k)) {
            if (!portalAtOccluder(acc, rng, s, k, n_in)) return;
          } else {
            if (s.band < 0) chooseBand(rng, s);
            if (s.band < 0 || !scatterAtOccluder(acc, rng, s, k, n_in)) return;
          }
          if (!roulette<0>(acc, rng, s.e, threshold)) return;
          e = carried<NB>(s.e, scale);
          pos = s.pos, dir = s.dir, order = s.order, specular_chain = s.specular_chain;
          if (scatters) skip_next = s.skip_next_score, skip_after_floor = s.skip_after_floor;
          continue;
        }
      }
      if (materials.opening[m]) {  // a hole: go on as if nothing were there
        pos -= eps_m * n_in;
        continue;
      }
      if (materials.absorbing[m]) return;
    }
    // Reflect or transmit, then Lambert or specular, with the material's fixed probabilities and
    // per-band weights (MaterialTable).
    ++order;
    const double p_reflect = materials.p_reflect[m];
    if (p_reflect >= 1.0 || rng.uniform() < p_reflect) {
      const double p_diffuse = materials.p_diffuse[m];
      if (p_diffuse > 0.0 && (p_diffuse >= 1.0 || rng.uniform() < p_diffuse)) {
        weigh<NB>(e, materials.w_diffuse, materials.octave_diffuse, m);
        dir = sampleLambert(side * tri.normal, [&rng] { return rng.uniform(); });
        specular_chain = false;
      } else {
        weigh<NB>(e, materials.w_specular, materials.octave_specular, m);
        dir -= (2.0 * dn) * tri.normal;
        if (after_floor && tri.plane == s.floor_plane) skip_next = after_floor;  // nextEventViaFloor's
      }
      pos += (side * eps_m - off_plane) * tri.normal;  // off the surface, on the side the ray now travels
    } else {
      weigh<NB>(e, materials.w_transmit, materials.octave_transmit, m);
      specular_chain = false;
      pos -= (side * eps_m + off_plane) * tri.normal;
    }
    if (!roulette<NB>(acc, rng, e, threshold_e, threshold4)) return;
  }
}

template <int NB>
bool Tracer::roulette(RoomTraceResult& acc, core::FastRng& rng, typename EnergyOf<NB>::type& e, double threshold,
                    Quad threshold4) const {
  double level = 0.0;
  if constexpr (NB == 8) {
    const Quad m = maxAbs(e);
    // The common case, some band at or above the threshold (rounded up to a float), in one compare.
    if (anyLane(m >= threshold4)) return true;
    level = std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
  } else {
    for (int b = 0; b < bands; ++b) level = std::max(level, std::abs(e[b]));
  }
  if (level >= threshold) return true;
  const double q = level / threshold;
  if (!(rng.uniform() < q)) {
    ++acc.roulette_killed;
    return false;
  }
  if constexpr (NB == 8) {
    const float inv = static_cast<float>(1.0 / q);
    e.lo *= inv;
    e.hi *= inv;
  } else {
    for (int b = 0; b < bands; ++b) e[b] /= q;
  }
  return true;
}

template <int NB>
void Tracer::weigh(typename EnergyOf<NB>::type& e, const std::vector<core::BandArray>& w, const std::vector<Octaves>& w8,
                 int m) const {
  if constexpr (NB == 8) {
    e.lo *= w8[m].lo;
    e.hi *= w8[m].hi;
  } else {
    for (int b = 0; b < bands; ++b) e[b] *= w[m][b];
  }
}

}  // namespace detail

using detail::Tracer;

namespace {

// The plane next-event estimation reaches listeners through (Tracer::nextEventViaFloor), or −1.
// A door: its floor (sill), the mirror plane through its bottom edge, perpendicular to it. An edge or a
// barrier (an edge axis across a uniform one): the plane nearest its edge among the reflecting ones
// perpendicular to the occluder's plane that leave its whole zone on one side, the ground a barrier stands on. Mirroring in a
// plane perpendicular to the occluder keeps the listener's image on the listener's side of it, where the
// estimate applies; any such plane gives an unbiased estimate (the tracer skips exactly the paths it
// covers), the nearest the one most paths take.
int floorPlaneOf(const room::Room& room, const room::Occluder& o, const RoomGeometry& geometry, double eps_m) {
  using Kind = room::OccluderAxis::Kind;
  const auto& planes = geometry.planes();
  if (o.y.kind == Kind::Opening && o.y.mirror_lo) {
    const Vec3 f = o.origin_m + o.y.lo_m * o.ey;
    int found = -1;
    for (std::size_t p = 0; p < planes.size(); ++p)
      if (std::abs(planes[p].normal.dot(o.ey)) > 1.0 - 1e-9 && std::abs(planes[p].normal.dot(f) - planes[p].offset) < eps_m)
        found = static_cast<int>(p);
    return found;
  }
  if (o.x.kind != Kind::Edge || o.y.kind != Kind::Uniform) return -1;
  const Vec3 hx = o.half_x_m * o.ex, hy = o.half_y_m * o.ey;
  const Vec3 corners[4] = {o.origin_m - hx - hy, o.origin_m - hx + hy, o.origin_m + hx - hy, o.origin_m + hx + hy};
  const Vec3 edge_mid = o.origin_m + o.x.lo_m * o.ex;  // the edge is the zone's x-lo side
  int found = -1;
  double nearest = 1e300;
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const MirrorPlane& mp = planes[p];
    if (std::abs(mp.normal.dot(o.normal)) > 1e-9) continue;
    bool reflects = false;  // a plane that absorbs everything has no paths to estimate
    for (int t : mp.triangles)
      for (int b = 0; b < room.bands.size(); ++b)
        reflects = reflects || room.materials[static_cast<std::size_t>(geometry.triangle(t).material)].absorption[b] < 1.0;
    if (!reflects) continue;
    double lo = 1e300, hi = -1e300;
    for (const Vec3& c : corners) lo = std::min(lo, mp.normal.dot(c) - mp.offset), hi = std::max(hi, mp.normal.dot(c) - mp.offset);
    if (lo < -eps_m && hi > eps_m) continue;  // it cuts the zone
    const double d = std::abs(mp.normal.dot(edge_mid) - mp.offset);
    if (d < nearest) nearest = d, found = static_cast<int>(p);
  }
  return found;
}

}  // namespace

RoomTraceResult traceRoom(const room::Room& room, const RoomGeometry& geometry, int source_index,
                          const RoomTraceOptions& options) {
  if (source_index < 0 || source_index >= static_cast<int>(room.sources.size()))
    throw core::InternalError("traceRoom: no such source");
  core::requirePositive("speed of sound", options.speed_of_sound_m_s);
  if (options.rays == 0) throw core::InputError("--rays", "must be at least 1");
  const auto t0 = std::chrono::steady_clock::now();
  Tracer tr{room, geometry, options, makeMaterials(room), {}, {}, 0, room.bands.size(), 0, 0.0, 0.0, 0.0, {}, {}, {}, {}};
  for (const room::Listener& l : room.listeners) {
    tr.spheres.push_back({l.position_m, l.radius_m});
    // The margins: far above the rounding of the squared distance (terms up to extent², relative 1e-16)
    // and of the projection (terms up to extent).
    const double r = l.radius_m, e = geometry.extent();
    const int lane = static_cast<int>((tr.spheres.size() - 1) % 2);
    if (lane == 0) {
      Tracer::ListenerPair empty;
      empty.x = empty.y = empty.z = Pair{0.0, 0.0};
      empty.r_slack = empty.r2_plus_margin = Pair{-1e300, -1e300};
      tr.listener_pairs.push_back(empty);
    }
    Tracer::ListenerPair& lp = tr.listener_pairs.back();
    lp.x[lane] = l.position_m.x(), lp.y[lane] = l.position_m.y(), lp.z[lane] = l.position_m.z();
    lp.r_slack[lane] = r + 1e-9 * (e + r);
    lp.r2_plus_margin[lane] = r * r + 1e-9 * (e * e + r * r);
  }
  tr.pair_count = static_cast<int>(tr.listener_pairs.size());
  tr.bins = histogramBins(options.length_s, options.bin_s, tr.bands, room.listeners.size(), options.directions);
  const room::Source& src = room.sources[source_index];
  tr.ray_energy = 4.0 * core::kPi * src.power_w / static_cast<double>(options.rays);
  tr.max_path_m = options.length_s * options.speed_of_sound_m_s;
  tr.eps_m = 1e-6 * geometry.extent();
  for (int k = 0; k < tr.bins; ++k) {
    const double s_k = (k + 0.5) * options.bin_s * options.speed_of_sound_m_s;
    tr.air_centre_m.push_back(s_k);
    for (int b = 0; b < tr.bands; ++b) tr.air_table.push_back(std::exp(-options.air_m_per_m[b] * s_k));
  }  // 15× the float rounding of a coordinate: no self-hits

  if (options.occluders)
    for (int k = 0; k < options.occluders->size(); ++k)
      tr.floor_plane.push_back(floorPlaneOf(room, options.occluders->occluder(k), geometry, tr.eps_m));
  const Vec3 axis = src.directivity.axis.normalized();
  for (int t = 0; t < static_cast<int>(room.mesh.triangleCount()); ++t) {
    const int m = geometry.triangle(t).material;
    tr.special.push_back(tr.materials.opening[m] || tr.materials.absorbing[m] ||
                         (options.occluders && options.occluders->occluderOf(t) >= 0));
  }

  auto make = [&] {
    RoomTraceResult r;
    r.listeners.assign(room.listeners.size(), receiver::EnergyHistogram(tr.bands, tr.bins, options.bin_s));
    r.crossings.assign(room.listeners.size(), 0);
    if (options.in_flight) r.in_flight = receiver::EnergyHistogram(tr.bands, tr.bins, options.bin_s);
    if (options.directions) r.directions.assign(room.listeners.size(), receiver::DirectionHistogram(tr.bands, tr.bins));
    return r;
  };
  auto body = [&](RoomTraceResult& acc, core::Rng& rng, std::uint64_t begin, std::uint64_t end) {
    const bool qmc5 = options.occluders != nullptr;
    core::ChunkSampler sampler(rng, qmc5 ? kGenerators5 : kGenerators, qmc5 ? 5 : 2, true);
    core::FastRng fast(rng);  // the bounces' uniforms
    for (std::uint64_t i = begin; i < end; ++i) {
      int dim = 0;
      const double xi1 = sampler.next(i - begin, dim), xi2 = sampler.next(i - begin, dim);
      double scale = 1.0;  // 1/(4π·pdf) of the direction, relative to uniform emission
      const Vec3 dir = emissionDirection(options.aim, src.position_m, xi1, xi2, scale);
      const double gain = src.directivity.a == 1.0 ? 1.0 : directivityGain(src.directivity, dir.dot(axis));
      core::BandArray e = core::bandFill(0.0);
      for (int b = 0; b < tr.bands; ++b) e[b] = tr.ray_energy * gain * scale;
      if (qmc5) {
        double q[3];
        for (double& v : q) v = sampler.next(i - begin, dim);
        tr.tracePath(acc, fast, src.position_m, dir, e, q);
      } else {
        tr.tracePath(acc, fast, src.position_m, dir, e);
      }
    }
    acc.rays += end - begin;
    // The chunk's batch by its first ray's index (a fixed share of the rays, whatever the thread count).
    const int batch = options.batches > 0 ? static_cast<int>(begin * static_cast<std::uint64_t>(options.batches) / options.rays) : -1;
    for (auto& h : acc.listeners) h.closeChunk(batch, options.batches, static_cast<double>(end - begin));
    if (options.in_flight) acc.in_flight.closeChunk();
  };
  RoomTraceResult result = core::deterministicReduce<RoomTraceResult>(
      options.rays, options.chunk_rays, options.seed, make, body, core::reportProgressTo(options.on_progress));
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace diffray::transport
