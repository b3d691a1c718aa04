// Diffraction validation cases. Each builds a scene in code from its
// parameters, runs the three models on it — the WBSDF ray tracer (compare/wbsdf_levels.h), UTD
// (utd/paths.h) and the exact reference (reference/half_plane_point.h, reference/aperture_point.h, which
// share no code with either) — and scores the level at each listener, per octave band, in dB re free field:
//   half-plane: listeners swept at one distance from the edge across the shadow boundary (angles relative
//               to it, + into the shadow), against Macdonald's exact point-source solution (rigid screen);
//   barrier:    insertion loss of a thin screen (a long wall): source and listeners given by distances from
//               the wall and heights relative to its top edge, against the same solution;
//   door-room:  a door on a rigid floor in a black partition between two rooms, listeners behind it from
//               in view to hidden behind a jamb, against Rayleigh–Sommerfeld over the opening (+ floor image).
// Targets: WBSDF within 1 dB of the exact reference in the lit and transition zones (angle into the
// shadow ≤ `transition` degrees) and within 3 dB up to 30° into the shadow, in the bands from `target-from`
// Hz (250 Hz) up; UTD is scored the same way and reported, not required.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "diffray/compare/point_models.h"
#include "diffray/compare/wbsdf_levels.h"
#include "diffray/core/error.h"
#include "diffray/room/air.h"
#include "diffray/validate/case.h"
#include "diffray/validate/diffraction_setup.h"

namespace diffray::validate {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
// Default rays. Every case scores the paths from the occluder by next-event estimation
// (RoomTraceOptions::next_event), the door's also through one specular bounce off its floor.
constexpr std::uint64_t kEdgeCaseRays = 500'000;
constexpr std::uint64_t kDoorCaseRays = 1'000'000;

struct Scored {
  double worst_wbsdf = 0, worst_utd = 0, worst_noise = 0, rms = 0;
  int n = 0;
  bool ok = true;
};

// Runs the models on `room` (one source, listeners with their shadow angles) and fills the case result.
CaseResult runModels(const std::string& name, const room::Room& room, const std::vector<double>& delta_deg,
                     const compare::WbsdfRunOptions& wopt, const Params& p) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c = room::speedOfSound(room.air);
  const int points = static_cast<int>(p.at("band-points")[0]);
  const double transition = p.at("transition")[0], target_from = p.at("target-from")[0];
  const compare::WbsdfLevels w = compare::wbsdfLevels(room, 0, wopt);
  std::string why_not, assumption, coherent_assumption;
  // The WBSDF model is scored against the reference it can match (floor reflections added as energy); UTD,
  // coherent, against the coherent one. Without a floor the two are the same.
  const auto exact = compare::exactModelFor(room, c, why_not, assumption, true);
  const auto exact_coherent = compare::exactModelFor(room, c, why_not, coherent_assumption, false);
  if (!exact || !exact_coherent) throw core::InternalError(name + ": " + why_not);
  const bool two_refs = exact->name() != exact_coherent->name();
  const auto utd = compare::utdModelFor(room, c);

  CaseResult r;
  r.name = name;
  r.rays = w.rays;
  r.errors_in_db = true;
  Scored s;
  int non_positive = 0;
  double neg = 0, all = 0;
  std::ostringstream misses;
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const room::Listener& li = room.listeners[l];
    for (int b = 0; b < room.bands.size(); ++b) {
      const double lo = room.bands.lowerHz(b), hi = room.bands.upperHz(b);
      const double e_exact = compare::bandRelativeEnergy(*exact, room.sources[0].position_m, li.position_m, li.radius_m, lo, hi, points);
      const double e_utd = compare::bandRelativeEnergy(*utd, room.sources[0].position_m, li.position_m, li.radius_m, lo, hi, points);
      const double e_coherent = two_refs ? compare::bandRelativeEnergy(*exact_coherent, room.sources[0].position_m,
                                                                       li.position_m, li.radius_m, lo, hi, points)
                                         : e_exact;
      const compare::BandLevel& bl = w.listeners[l][b];
      Row row;
      row.x_m = delta_deg[l];
      row.y_m = room.bands.nominalHz(b);
      row.traced = bl.level_db;
      row.reference = compare::levelDb(e_exact);
      row.alt_reference = compare::levelDb(e_utd);
      // dB noise of the traced level (first order in the ratio's standard error).
      row.std_error = bl.ratio > 0 ? 10.0 / std::log(10.0) * bl.ratio_std_error / bl.ratio : 1e9;
      row.label = "f=" + room.bands.label(b) + "Hz;angle=" + std::to_string(static_cast<int>(std::lround(delta_deg[l])));
      r.rows.push_back(row);
      all += std::abs(bl.ratio);
      if (bl.ratio < 0) neg -= bl.ratio;
      const double target = delta_deg[l] <= transition ? 1.0 : (delta_deg[l] <= 30.0 ? 3.0 : 0.0);
      if (target == 0.0 || room.bands.nominalHz(b) < target_from) continue;
      if (!std::isfinite(row.traced)) {  // the traced energy came out ≤ 0: all noise, no level to compare
        ++non_positive;
        s.ok = false;
        misses << " " << row.label << ":no-level";
        continue;
      }
      const double err = row.traced - row.reference;
      const double err_utd = row.alt_reference - compare::levelDb(e_coherent);
      const std::string zone = delta_deg[l] <= transition ? "lit_transition" : "shadow";
      const std::string key = zone + "_" + room.bands.label(b) + "Hz_";
      r.extra["wbsdf_" + key + "worst_db"] = std::max(r.extra["wbsdf_" + key + "worst_db"], std::abs(err));
      r.extra["utd_" + key + "worst_db"] = std::max(r.extra["utd_" + key + "worst_db"], std::abs(err_utd));
      s.worst_wbsdf = std::max(s.worst_wbsdf, std::abs(err));
      s.worst_utd = std::max(s.worst_utd, std::abs(err_utd));
      s.worst_noise = std::max(s.worst_noise, row.std_error);
      s.rms += err * err;
      ++s.n;
      if (!(std::abs(err) <= target)) {
        s.ok = false;
        misses << " " << row.label << ":" << err;
      }
    }
  }
  r.max_abs_error_rel_peak = s.worst_wbsdf;
  r.rms_error_rel_peak = s.n ? std::sqrt(s.rms / s.n) : 0.0;
  r.max_std_error_rel_peak = s.worst_noise;
  r.target_rel_peak = 1.0;
  r.negative_energy_fraction = all > 0 ? neg / all : 0.0;
  r.passed = s.ok && s.n > 0;  // no listener in a zone with a target: nothing was checked
  r.extra["levels_checked"] = s.n;  // (listener, band) pairs with a target
  r.extra["utd_worst_db"] = s.worst_utd;
  r.extra["occluder_events"] = static_cast<double>(w.occluder_events);
  std::ostringstream d;
  d.precision(3);
  d << "WBSDF worst |error| " << s.worst_wbsdf << " dB vs " << assumption << "; UTD " << s.worst_utd << " dB vs "
    << (two_refs ? coherent_assumption : std::string("the same"))
    << " (targets: 1 dB lit/transition up to " << transition << " deg, 3 dB to 30 deg, from " << target_from << " Hz)";
  if (non_positive) d << "; " << non_positive << " band level(s) traced at or below zero energy (noise)";
  if (!s.ok) d << "; WBSDF misses:" << misses.str();
  r.detail = d.str();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::vector<ParamSpec> commonParams(double radius) {
  std::vector<ParamSpec> ps{
      {"radius", {radius}, "listener sphere radius (m)"},
      {"transition", {5}, "listeners up to this angle into the shadow (deg) count as transition zone (1 dB target)", -90, false, 90},
      {"target-from", {250}, "lowest band (Hz) the targets apply to (lower bands are reported)"},
      {"band-points", {32}, "frequencies per band for the band-averaged UTD and exact levels", 1, true, 4096},
      {"rigid-weighting", {1}, "1: WBSDF edge rays weighted by the rigid/Kirchhoff coefficient ratio; 0: plain WBSDF (Kirchhoff)", -1, false, 2}};
  for (ParamSpec& p : ps) p.whole = p.name == "band-points" || p.name == "rigid-weighting";
  return ps;
}

room::OccluderAxis::Faces facesOf(const Params& p) {
  return p.at("rigid-weighting")[0] >= 0.5 ? room::OccluderAxis::Faces::Rigid : room::OccluderAxis::Faces::Kirchhoff;
}

// Rays aimed at the edge zone, within the heights that can reach a listener sphere (all at z = 0 with the
// source): a ray crossing the zone at height z reaches the listener's distance at a height ≥ |z|.
// The run options every case shares: rays (the case's default unless given), seed, progress, and every ray
// aimed at the scene's occluder (compare::aimAtOccluder), arrivals up to 1 s.
compare::WbsdfRunOptions aimedRun(const room::Room& room, const RunOptions& o, std::uint64_t default_rays) {
  compare::WbsdfRunOptions w;
  w.rays = o.rays ? o.rays : default_rays;
  w.seed = o.seed;
  w.on_progress = o.on_progress;
  compare::aimAtOccluder(w, room.occluders[0]);
  w.length_s = 1.0;
  return w;
}

// Rays aimed at the edge zone, within the heights that can reach a listener sphere (all at z = 0 with the
// source): a ray crossing the zone at height z reaches the listener's distance at a height ≥ |z|.
compare::WbsdfRunOptions edgeAim(const room::Room& room, const RunOptions& o, std::uint64_t default_rays, double radius) {
  compare::WbsdfRunOptions w = aimedRun(room, o, default_rays);
  w.aim_half_y_m = radius;
  return w;
}

}  // namespace

CaseInfo halfPlaneCase() {
  CaseInfo c{"half-plane", "point source, thin rigid half-plane: WBSDF, UTD vs Macdonald's exact solution across the shadow boundary", {}, kEdgeCaseRays, {}};
  c.params = {{"source-distance", {5}, "source distance from the edge (m)"},
              {"source-angle", {60}, "source angle from the lit face (deg)", 0, false, 180},
              {"listener-distance", {5}, "listener distance from the edge (m)"},
              {"listener-angles", {-30, -20, -10, -5, 0, 5, 10, 15, 20, 25, 30}, "listener angles past the shadow boundary (deg, + into the shadow)", -180, false, 180},
              {"zone", {3}, "width of the WBSDF edge zone (m): past it rays go straight"}};
  for (auto& ps : commonParams(0.15)) c.params.push_back(ps);
  c.param("listener-angles").list = true;
  c.run = [](const Params& p, const RunOptions& o) {
    HalfPlaneSpec spec;
    spec.source_rho_m = p.at("source-distance")[0];
    spec.source_phi_rad = p.at("source-angle")[0] * kDeg;
    spec.listener_rho_m = p.at("listener-distance")[0];
    spec.radius_m = p.at("radius")[0];
    spec.zone_m = p.at("zone")[0];
    spec.faces = facesOf(p);
    std::vector<double> deltas = p.at("listener-angles");
    for (double d : deltas) {
      const double phi = 180.0 + p.at("source-angle")[0] + d;
      if (!(phi > 0.0 && phi < 360.0)) throw core::InputError("--listener-angles", "an angle puts the listener on the screen");
      spec.listener_phi_rad.push_back(phi * kDeg);
    }
    if (!(spec.radius_m < 0.5 * spec.listener_rho_m)) throw core::InputError("--radius", "must be below half the listener distance");
    const room::Room room = makeHalfPlaneScene(spec);
    return runModels("half-plane", room, deltas, edgeAim(room, o, kEdgeCaseRays, spec.radius_m), p);
  };
  return c;
}

CaseInfo barrierCase() {
  CaseInfo c{"barrier", "insertion loss of a thin rigid screen (a long wall): WBSDF, UTD vs the exact half-plane", {}, kEdgeCaseRays, {}};
  c.params = {{"source-distance", {4}, "source distance from the screen (m)"},
              {"source-height", {-1}, "source height relative to the top edge (m; < 0 below it)", -1e3, false, 1e3},
              {"listener-distance", {6}, "listener distance from the screen (m)"},
              {"listener-heights", {1, 0.5, 0, -0.5, -1, -2, -3}, "listener heights relative to the top edge (m)", -1e3, false, 1e3},
              {"zone", {3}, "width of the WBSDF edge zone above the top edge (m)"}};
  for (auto& ps : commonParams(0.15)) c.params.push_back(ps);
  c.param("listener-heights").list = true;
  c.run = [](const Params& p, const RunOptions& o) {
    // The half-plane frame: the edge on the z axis, the screen the half-plane toward +x (downward); a point
    // at distance D from the screen on the source side and height h relative to the edge is (−h, D, 0).
    const double ds = p.at("source-distance")[0], hs = p.at("source-height")[0], dl = p.at("listener-distance")[0];
    HalfPlaneSpec spec;
    spec.source_rho_m = std::hypot(ds, hs);
    spec.source_phi_rad = std::atan2(ds, -hs);
    spec.radius_m = p.at("radius")[0];
    spec.zone_m = p.at("zone")[0];
    spec.faces = facesOf(p);
    std::vector<double> deltas;
    room::Room room = makeHalfPlaneScene(spec);  // no listeners yet: they are placed by height below
    room.name = "barrier";
    for (double h : p.at("listener-heights")) {
      const core::Vec3 at(-h, -dl, 0.0);
      const double phi = std::atan2(-dl, -h) + 2.0 * 3.14159265358979323846;
      deltas.push_back((phi - 3.14159265358979323846 - spec.source_phi_rad) / kDeg);
      room.listeners.push_back({"R" + std::to_string(room.listeners.size() + 1), at, spec.radius_m});
    }
    // The rows hold levels re free field: the insertion loss is their negative.
    return runModels("barrier", room, deltas, edgeAim(room, o, kEdgeCaseRays, spec.radius_m), p);
  };
  return c;
}

CaseInfo doorRoomCase() {
  CaseInfo c{"door-room", "door on a floor between two rooms (black partition): WBSDF, UTD vs Rayleigh–Sommerfeld through the opening", {}, kDoorCaseRays, {}};
  c.params = {{"width", {0.9}, "door width (m)"},
              {"height", {2.1}, "door height (m)"},
              {"source-distance", {2.5}, "source distance from the partition, room A (m)"},
              {"source-height", {1.5}, "source height (m)"},
              {"listener-distance", {2.5}, "listener distance from the door's jamb, room B (m)"},
              {"listener-height", {1.5}, "listener height (m)"},
              {"listener-angles", {-20, -10, -5, 0, 5, 10, 20, 30}, "listener angles past the jamb's shadow boundary (deg, + hidden)", -90, false, 90},
              {"floor", {1}, "1: the door stands on a rigid floor; 0: an opening in a free-standing screen", -1, false, 2}};
  for (auto& ps : commonParams(0.15)) c.params.push_back(ps);
  c.param("listener-angles").list = true;
  c.param("floor").whole = true;
  c.run = [](const Params& p, const RunOptions& o) {
    DoorSpec spec;
    spec.width_m = p.at("width")[0];
    spec.height_m = p.at("height")[0];
    spec.source_m = core::Vec3(-p.at("source-distance")[0], 0.0, p.at("source-height")[0]);
    spec.radius_m = p.at("radius")[0];
    spec.floor = p.at("floor")[0] >= 0.5;
    const double dl = p.at("listener-distance")[0], zl = p.at("listener-height")[0];
    if (!(spec.source_m.z() > 0 && zl > 0)) throw core::InputError("--source-height", "source and listener must be above the floor");
    // Listeners on a circle of radius dl around the jamb at y = +width/2, at angles past its shadow boundary.
    const double jamb = 0.5 * spec.width_m;
    const double boundary = std::atan2(jamb - spec.source_m.y(), -spec.source_m.x());
    std::vector<double> deltas;
    for (double d : p.at("listener-angles")) {
      const double a = boundary + d * kDeg;
      if (!(a > -80 * kDeg && a < 170 * kDeg)) throw core::InputError("--listener-angles", "a listener falls behind the partition");
      spec.listeners_m.emplace_back(dl * std::cos(a), jamb + dl * std::sin(a), zl);
    }
    for (const auto& l : spec.listeners_m) deltas.push_back(doorShadowAngleDeg(spec, l));
    const room::Room room = makeDoorScene(spec);
    // Aimed at the door and, on a floor, its mirror image (the image source's paths).
    const compare::WbsdfRunOptions w = aimedRun(room, o, kDoorCaseRays);
    return runModels("door-room", room, deltas, w, p);
  };
  return c;
}

}  // namespace diffray::validate
