// The WBSDF occluder events of a room path (detail::Tracer, room_tracer_core.h): the band choice of the
// plain estimator, next-event estimation toward the listeners (directly and via a door's floor), the plain
// signed scattering and the portal (RoomTraceOptions::portal).
#include <algorithm>
#include <cmath>

#include "diffray/geometry/embree_scene.h"
#include "diffray/transport/room_tracer_core.h"

namespace diffray::transport::detail {

Tracer::BandPick Tracer::pickBand(core::FastRng& rng, const Path& s) const {
  BandPick p;
  for (int b = 0; b < bands; ++b)
    if (s.e[b] != 0.0) p.live[p.n++] = b;
  if (p.n == 0) return p;
  // One uniform picks the band and, rescaled within the band's slot, the place of the frequency in it
  // (quasi-random at the path's first occluder).
  const double x = (s.has_qmc && s.diffractions == 0 ? s.qmc[2] : rng.uniform()) * p.n;
  p.pick = std::min(p.n - 1, static_cast<int>(x));
  p.place = std::min(1.0, x - p.pick);
  return p;
}

double Tracer::wavelengthAt(int b, double place) const {
  return opt.speed_of_sound_m_s / (room.bands.lowerHz(b) + place * (room.bands.upperHz(b) - room.bands.lowerHz(b)));
}

void Tracer::chooseBand(core::FastRng& rng, Path& s) const {
  const BandPick p = pickBand(rng, s);
  if (p.n == 0) return;
  const int b = p.live[p.pick];
  const double e_b = s.e[b] * p.n;
  s.e = core::bandFill(0.0);
  s.e[b] = e_b;
  s.band = b;
  s.lambda_m = wavelengthAt(b, p.place);
}

std::uint64_t Tracer::nextEvent(RoomTraceResult& acc, core::FastRng& rng, const Path& s, int k, const Vec3& n_in,
                              std::uint64_t& floor_served, bool sample_when_nan) const {
  const int b = s.band;
  const double xi[2] = {rng.uniform(), rng.uniform()};  // a door's vertical shift (expectedSphereScore)
  std::uint64_t served = 0;
  floor_served = 0;
  if (floor_plane[k] >= 0)
    for (std::size_t l = 0; l < spheres.size() && l < 64; ++l)
      if (nextEventViaFloor(acc, rng, s, k, n_in, l, xi, sample_when_nan)) floor_served |= std::uint64_t{1} << l;
  for (std::size_t l = 0; l < spheres.size() && l < 64; ++l) {
    const Vec3 q = spheres[l].centre - s.pos;
    const double L = q.norm();
    if (!(L > spheres[l].radius_m)) continue;
    const Vec3 qh = q / L;
    // In view: nothing between the hit point (just off the occluder's plane, on the listener's side) and
    // the sphere's near side.
    const Vec3 from = s.pos + (qh.dot(n_in) > 0.0 ? eps_m : -eps_m) * n_in;
    const SegmentHit h = cast(from, qh);
    // Hidden listeners are served too: nothing of the segment reaches them straight (estimate 0).
    served |= std::uint64_t{1} << l;
    if (h.valid() && h.t < L - spheres[l].radius_m) continue;
    double v = opt.occluders->expectedSphereScore(k, s.pos, s.dir, s.lambda_m, spheres[l].centre, spheres[l].radius_m, xi);
    if (std::isnan(v)) {
      if (!sample_when_nan) {
        served &= ~(std::uint64_t{1} << l);
        continue;
      }
      v = sampledSphereScore(rng, s, k, spheres[l].centre, spheres[l].radius_m);
    }
    if (v == 0.0) continue;
    const double path = s.path_m + L;
    const int bin = acc.listeners[l].binOf(path / opt.speed_of_sound_m_s);
    if (bin < 0) continue;
    const double energy = s.e[b] * v * std::exp(-opt.air_m_per_m[b] * path);
    acc.listeners[l].add(b, bin, energy);
    if (opt.directions) acc.directions[l].add(b, bin, energy, -qh);
  }
  return served;
}

double Tracer::sampledSphereScore(core::FastRng& rng, const Path& s, int k, const Vec3& centre, double radius_m) const {
  double xi[4];
  for (double& v : xi) v = rng.uniform();
  const RoomOccluders::Scatter sc = opt.occluders->scatter(k, s.pos, s.dir, s.lambda_m, xi);
  if (!sc.alive) return 0.0;
  const receiver::Sphere sphere{centre, radius_m};
  const double o[3] = {s.pos.x(), s.pos.y(), s.pos.z()}, d[3] = {sc.dir.x(), sc.dir.y(), sc.dir.z()};
  double t_in, t_out;
  if (!sphere.chordSpan(o, d, 0.0, 1e300, t_in, t_out)) return 0.0;
  return sc.weight * sphere.chordWeight(t_out - t_in) / sphere.crossSection();
}

bool Tracer::nextEventViaFloor(RoomTraceResult& acc, core::FastRng& rng, const Path& s, int k, const Vec3& n_in,
                             std::size_t l, const double* xi, bool sample_when_nan) const {
  const MirrorPlane& fp = geometry.planes()[floor_plane[k]];
  const receiver::Sphere& sp = spheres[l];
  const double height = fp.normal.dot(sp.centre) - fp.offset;
  const Vec3 image = sp.centre - 2.0 * height * fp.normal;
  const Vec3 q = image - s.pos;
  const double L = q.norm();
  if (!(L > sp.radius_m)) return false;
  const Vec3 qh = q / L;
  const Vec3 from = s.pos + (qh.dot(n_in) > 0.0 ? eps_m : -eps_m) * n_in;
  const SegmentHit h = cast(from, qh);
  if (!h.valid() || geometry.triangle(h.triangle).plane != floor_plane[k]) return true;  // no floor there
  const Vec3 r = from + h.t * qh, leg = sp.centre - r;
  const double leg_len = leg.norm();
  const Vec3 up = fp.normal.dot(leg) > 0.0 ? fp.normal : Vec3(-fp.normal);
  const SegmentHit back = cast(r + eps_m * up, leg / leg_len);
  if (back.valid() && back.t < leg_len - sp.radius_m) return true;  // the reflected leg is blocked
  double v = opt.occluders->expectedSphereScore(k, s.pos, s.dir, s.lambda_m, image, sp.radius_m, xi);
  if (std::isnan(v)) {
    if (!sample_when_nan) return false;
    v = sampledSphereScore(rng, s, k, image, sp.radius_m);
  }
  const room::Material& m = room.materials[geometry.triangle(h.triangle).material];
  const double reflect = (1.0 - m.absorption[s.band]) * (1.0 - m.scattering[s.band]);
  const double path = s.path_m + L;
  const int bin = acc.listeners[l].binOf(path / opt.speed_of_sound_m_s);
  if (v != 0.0 && bin >= 0) {
    const double energy = s.e[s.band] * v * reflect * std::exp(-opt.air_m_per_m[s.band] * path);
    acc.listeners[l].add(s.band, bin, energy);
    if (opt.directions) acc.directions[l].add(s.band, bin, energy, -leg / leg_len);
  }
  return true;
}

void Tracer::leaveOccluder(Path& s, const Vec3& dir, const Vec3& n_in) const {
  s.dir = dir;
  s.pos += (dir.dot(n_in) > 0.0 ? eps_m : -eps_m) * n_in;
  s.specular_chain = false;
  ++s.order;
  ++s.diffractions;
}

bool Tracer::scatterAtOccluder(RoomTraceResult& acc, core::FastRng& rng, Path& s, int k, const Vec3& n_in) const {
  ++acc.occluder_events;
  if (opt.next_event && opt.occluders->nextEventSupported(k)) {
    s.skip_next_score = nextEvent(acc, rng, s, k, n_in, s.skip_after_floor, false);
    s.floor_plane = floor_plane[k];
  }
  double through = 1.0;
  if (turnsBack(rng, s, k, n_in, through)) return true;
  double xi[4];
  for (double& v : xi) v = rng.uniform();
  if (s.has_qmc && s.diffractions == 0) xi[0] = s.qmc[0], xi[1] = s.qmc[1];
  const RoomOccluders::Scatter sc = opt.occluders->scatter(k, s.pos, s.dir, s.lambda_m, xi);
  if (!sc.alive) {
    if (sc.evanescent) ++acc.evanescent;
    return false;
  }
  const room::Occluder& o = opt.occluders->occluder(k);
  double w = sc.weight * through;
  if (o.reflect) w *= 1.0 - room.materials[o.material].absorption[s.band];
  s.e[s.band] *= w;
  leaveOccluder(s, sc.dir, n_in);
  return true;
}

bool Tracer::portalAtOccluder(RoomTraceResult& acc, core::FastRng& rng, Path& s, int k, const Vec3& n_in) const {
  ++acc.occluder_events;
  const bool first = s.has_qmc && s.diffractions == 0;  // before pickBand: the quasi-random uniforms' turn
  const BandPick bp = pickBand(rng, s);
  const int n = bp.n, pick = bp.pick;
  const int* live = bp.live;
  if (n == 0) return false;
  double lambda[core::kMaxBands];
  for (int i = 0; i < n; ++i) lambda[i] = wavelengthAt(live[i], bp.place);
  Path one = s;
  one.band = live[pick];
  one.lambda_m = lambda[pick];
  one.e[one.band] = s.e[one.band] * n;
  s.skip_next_score = nextEvent(acc, rng, one, k, n_in, s.skip_after_floor, true);
  s.floor_plane = floor_plane[k];
  double through = 1.0;
  if (turnsBack(rng, s, k, n_in, through)) return true;
  double xi[4];
  for (double& v : xi) v = rng.uniform();
  if (first) xi[0] = s.qmc[0], xi[1] = s.qmc[1];
  double w[core::kMaxBands];
  const RoomOccluders::PortalScatter sc = opt.occluders->scatterPortal(k, s.pos, s.dir, lambda, n, pick, xi, w);
  if (!sc.alive) {
    if (sc.evanescent) ++acc.evanescent;
    return false;
  }
  core::BandArray e = core::bandFill(0.0);
  for (int i = 0; i < n; ++i) e[live[i]] = s.e[live[i]] * w[i] * through;
  s.e = e;
  leaveOccluder(s, sc.dir, n_in);
  return true;
}

Tracer::OpeningFate Tracer::openingFate(core::FastRng& rng, const Path& s, int k) const {
  OpeningFate f;
  double carried = 0.0, total = 0.0;
  for (int b = 0; b < bands; ++b) {
    if (s.e[b] == 0.0) continue;
    f.tau[b] = opt.occluders->transmission(k, b, s.dir);
    carried += std::abs(s.e[b]) * f.tau[b];
    total += std::abs(s.e[b]);
  }
  f.p_through = total > 0.0 ? carried / total : 1.0;
  f.back = rng.uniform() >= f.p_through;
  return f;
}

bool Tracer::turnsBack(core::FastRng& rng, Path& s, int k, const Vec3& n_in, double& through) const {
  if (!opt.occluders->returnsEnergy(k)) return false;
  const OpeningFate f = openingFate(rng, s, k);
  if (f.back) {
    comeBack(s, k, f, n_in);
    return true;
  }
  through = 1.0 / f.p_through;
  return false;
}

void Tracer::comeBack(Path& s, int k, const OpeningFate& f, const Vec3& n_in) const {
  const core::BandArray& r = opt.occluders->surround(k);
  const double p_back = 1.0 - f.p_through;
  for (int b = 0; b < bands; ++b) s.e[b] *= (1.0 - f.tau[b]) * r[b] / p_back;
  const Vec3 n = opt.occluders->occluder(k).normal;
  s.dir -= 2.0 * s.dir.dot(n) * n;
  s.pos += eps_m * n_in;  // n_in faces the side the path came from
  s.specular_chain = false;
  ++s.order;
  s.skip_next_score = 0;
  s.skip_after_floor = 0;
}

void Tracer::passOpening(core::FastRng& rng, Path& s, int k, const Vec3& n_in) const {
  const OpeningFate f = openingFate(rng, s, k);
  if (f.back) {
    comeBack(s, k, f, n_in);
    return;
  }
  for (int b = 0; b < bands; ++b) s.e[b] *= f.tau[b] / f.p_through;
  s.pos -= eps_m * n_in;  // through, along the same direction
}

}  // namespace diffray::transport::detail
