#include "diffray/compare/scene_compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>

#include <tbb/parallel_for.h>

#include "diffray/compare/point_models.h"
#include "diffray/compare/room_compare.h"
#include "diffray/compare/scene_checks.h"
#include "diffray/compare/wbsdf_levels.h"
#include "diffray/core/error.h"
#include "diffray/room/air.h"
#include "diffray/room/occluder_file.h"

namespace diffray::compare {

using core::Vec3;
using Kind = room::OccluderAxis::Kind;

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Band and fine-grid rows of one point model for listener l.
void listenerRows(const room::Room& room, const PointModel& m, const CompareOptions& o, int l,
                  const std::vector<double>& fine, const std::function<void(std::uint64_t)>& tick,
                  std::uint64_t steps, std::vector<LevelRow>& out) {
  const Vec3 src = room.sources[0].position_m;
  const int nb = room.bands.size();
  const room::Listener& li = room.listeners[l];
  std::vector<std::pair<double, double>> bands;
  for (int b = 0; b < nb; ++b) bands.emplace_back(room.bands.lowerHz(b), room.bands.upperHz(b));
  const std::vector<double> e_band = bandRelativeEnergies(m, src, li.position_m, li.radius_m, bands, o.band_points);
  for (int b = 0; b < nb; ++b) {
    out.push_back({l, m.name(), room.bands.nominalHz(b), true, room.bands.label(b), levelDb(e_band[b]), 0.0});
    if (tick) tick(steps);
  }
  const std::vector<std::complex<double>> p = m.relativePressure(src, li.position_m, fine);
  std::vector<double> e;
  if (m.addsEnergies())
    e = m.relativeEnergy(src, li.position_m, fine);  // arrivals added as energies: no phase
  else
    for (const auto& v : p) e.push_back(std::norm(v));  // NaN where the model gives no value
  for (std::size_t j = 0; j < fine.size(); ++j)
    out.push_back({l, m.name(), fine[j], false, "", levelDb(e[j]), 0.0, std::arg(p[j]) * 180.0 / 3.14159265358979323846});
  if (tick) tick(steps);
}

// Band and fine-grid rows of one point model for every listener (listeners in parallel).
void pointRows(const room::Room& room, const PointModel& m, const CompareOptions& o, std::vector<LevelRow>& rows) {
  const int nl = static_cast<int>(room.listeners.size()), nb = room.bands.size();
  const double f_lo = room.bands.lowerHz(0), f_hi = room.bands.upperHz(nb - 1);
  const int n_fine = std::max(2, static_cast<int>(std::ceil(o.fine_per_octave * std::log2(f_hi / f_lo))) + 1);
  std::vector<double> fine = o.freqs_hz;
  if (fine.empty())
    for (int j = 0; j < n_fine; ++j) fine.push_back(f_lo * std::pow(f_hi / f_lo, static_cast<double>(j) / (n_fine - 1)));
  std::vector<std::vector<LevelRow>> per(nl);
  const auto tick = o.model_progress ? o.model_progress(m.name()) : std::function<void(std::uint64_t)>();
  const auto steps = static_cast<std::uint64_t>(nl) * static_cast<std::uint64_t>(nb + 1);
  tbb::parallel_for(0, nl, [&](int l) {
    try {
      listenerRows(room, m, o, l, fine, tick, steps, per[l]);
    } catch (const core::InputError& e) {  // every error names the listener and the model it is about
      throw core::InputError("listener " + room.listeners[l].name + ": model " + m.name(), e.what());
    }
  });
  for (auto& v : per) rows.insert(rows.end(), v.begin(), v.end());
}

// Whether the listener at `p` is on the far side of the room's single opening (door or slit) from source 0,
// where a shadow boundary of the opening exists; true for every other scene (an edge's angle runs all round it).
bool beyondOccluder(const room::Room& room, const Vec3& p) {
  const std::vector<const room::Occluder*> own = room::ownOccluders(room);
  if (own.size() != 1 || own[0]->x.kind == Kind::Edge) return true;
  const room::Occluder& d = *own[0];
  return (room.sources[0].position_m - d.origin_m).dot(d.normal) * (p - d.origin_m).dot(d.normal) < 0.0;
}

// The listener's angle past one edge's shadow boundary, in the plane across the edge: angles from the screen
// face (−ex), the source's side +.
double edgeShadowAngleDeg(const room::Occluder& o, const Vec3& source, const Vec3& listener) {
  const Vec3 e0 = o.origin_m - o.half_x_m * o.ex;
  const auto angle = [&](const Vec3& p, double side) {
    const Vec3 d = p - e0;
    double a = std::atan2(side * d.dot(o.normal), -d.dot(o.ex));
    return a < 0 ? a + 2.0 * core::kPi : a;
  };
  const double side = (source - e0).dot(o.normal) >= 0 ? 1.0 : -1.0;
  const double phi0 = angle(source, side), phi = angle(listener, side);
  return wrapDegrees((phi - core::kPi - phi0) * 180.0 / core::kPi);
}

}  // namespace

std::optional<double> shadowAngleDeg(const room::Room& room, const Vec3& source, const Vec3& listener) {
  const std::vector<const room::Occluder*> own = room::ownOccluders(room);
  if (own.size() != 1) return std::nullopt;
  const room::Occluder& o = *own[0];
  if (o.x.kind == Kind::Edge) {
    // A barrier's top edge and, where they diffract, its side and foot edges ("barrier side" zones): the
    // straight line from the source passes the plate, and the listener is lit, exactly when it passes one
    // of the edges, so the listener is as far into the shadow as past the edge that comes nearest to
    // lighting it: the least of the edges' angles.
    double least = edgeShadowAngleDeg(o, source, listener);
    for (const room::Occluder& side : room.occluders)
      if (side.type == "barrier side") least = std::min(least, edgeShadowAngleDeg(side, source, listener));
    return least;
  }
  if (o.x.kind == Kind::Opening || o.x.kind == Kind::Slits) {
    // In the plane spanned by ex and the normal: each side edge's boundary continues the line from the
    // source past it; the listener's angle beyond it, + on the hidden side; the larger of the two.
    const double side = (source - o.origin_m).dot(o.normal) < 0 ? 1.0 : -1.0;  // source at Z < 0
    const auto xz = [&](const Vec3& p) {
      const Vec3 d = p - o.origin_m;
      return std::make_pair(d.dot(o.ex), side * d.dot(o.normal));
    };
    const auto [xs, zs] = xz(source);
    const auto [xl, zl] = xz(listener);
    double worst = -1e300;
    for (const double jamb : {-o.half_x_m, o.half_x_m}) {
      const double boundary = std::atan2(jamb - xs, -zs), seen = std::atan2(xl - jamb, zl);
      worst = std::max(worst, jamb > 0 ? seen - boundary : boundary - seen);
    }
    return wrapDegrees(worst * 180.0 / core::kPi);
  }
  return std::nullopt;
}

SceneComparison compareScene(const room::Room& room, const CompareOptions& o) {
  if (room.sources.empty() || room.listeners.empty()) throw core::InputError(room.file, "needs a source and a listener");
  checkListeners(room);
  const double c = room::speedOfSound(room.air);
  SceneComparison out;
  if (isEnclosedRoom(room))  // a wall between rooms is no ground plane: the hidden-listener test does not apply
    out.warnings.push_back("the scene is a closed room: free-field mode leaves out its reverberation (room mode, "
                           "the default for it, compares whole room simulations)");
  else
    out.warnings = hiddenListenerWarnings(room);
  if (room.sources.size() > 1) out.warnings.push_back("the scene has several sources: compare uses the first only");
  for (const room::Listener& l : room.listeners)
    out.shadow_angle_deg.push_back(beyondOccluder(room, l.position_m)
                                       ? shadowAngleDeg(room, room.sources[0].position_m, l.position_m)
                                       : std::nullopt);
  const auto has = [&](const char* m) { return std::find(o.models.begin(), o.models.end(), m) != o.models.end(); };
  if (has("exact") && room.occluders.size() == 1 && room.occluders[0].x.kind == Kind::Opening) {
    // The aperture reference holds only beyond the opening's plane: refuse, naming the listener, before any
    // model runs (rather than after the WBSDF trace, from inside the reference).
    const room::Occluder& d = room.occluders[0];
    for (const room::Listener& l : room.listeners)
      if (!beyondOccluder(room, l.position_m))
        throw core::InputError("listener " + l.name + ": model exact",
                               "on the source's side of " + d.type + " " + d.name +
                                   ": the free-field aperture reference needs the listener beyond the opening's "
                                   "plane (a room with a door: --mode room)");
  }

  if (has("wbsdf")) {
    const auto t0 = std::chrono::steady_clock::now();
    WbsdfRunOptions w;
    w.rays = o.rays;
    w.seed = o.seed;
    w.on_progress = o.on_progress;
    if (room.occluders.empty()) out.warnings.push_back("the scene has no occluders: the WBSDF model is plain geometric acoustics");
    if (o.aim) {
      const std::vector<const room::Occluder*> own = room::ownOccluders(room);
      if (own.size() != 1) throw core::InputError("--aim", "needs exactly one occluder in the scene");
      const AimGround ground = checkAimReflectors(room);
      const room::Occluder& d = *own[0];
      aimAtOccluder(w, d);
      if (d.y.kind == Kind::Uniform) {
        // Along an edge the ray keeps its cosine: a path from the source to a listener crosses the zone at an
        // edge coordinate between theirs (widened by the listener's radius). Aim only there.
        const double ys = (room.sources[0].position_m - d.origin_m).dot(d.ey);
        double lo = ys, hi = ys;
        for (const room::Listener& l : room.listeners) {
          const double yl = (l.position_m - d.origin_m).dot(d.ey);
          lo = std::min(lo, yl - l.radius_m);
          hi = std::max(hi, yl + l.radius_m);
        }
        lo = std::max(lo, -d.half_y_m);
        hi = std::min(hi, d.half_y_m);
        if (hi > lo) {
          w.aim_origin = d.origin_m + 0.5 * (lo + hi) * d.ey;
          w.aim_half_y_m = 0.5 * (hi - lo);
        }
      }
      std::vector<AimRect> rects = {{w.aim_origin, w.aim_ex, w.aim_ey, w.aim_half_x_m, w.aim_half_y_m}};
      for (const room::Occluder& side : room.occluders)  // a barrier's side zones, whole
        if (&side != &d) {
          w.aim_more.push_back({side.origin_m, side.ex, side.ey, side.half_x_m, side.half_y_m});
          rects.push_back({side.origin_m, side.ex, side.ey, side.half_x_m, side.half_y_m});
        }
      checkAimReachesListeners(room, rects, ground);
      w.aim_mirrored = ground.present;
      w.aim_mirror_normal = ground.normal;
      w.aim_mirror_offset = ground.offset;
    }
    const WbsdfLevels lv = wbsdfLevels(room, 0, w);
    out.rays = lv.rays;
    for (std::size_t l = 0; l < room.listeners.size(); ++l)
      for (int b = 0; b < room.bands.size(); ++b) {
        const BandLevel& bl = lv.listeners[l][b];
        const double se = bl.ratio > 0 ? 10.0 / std::log(10.0) * bl.ratio_std_error / bl.ratio : INFINITY;
        out.rows.push_back({static_cast<int>(l), "wbsdf", room.bands.nominalHz(b), true, room.bands.label(b), bl.level_db, se});
      }
    out.wbsdf_seconds = since(t0);
  }
  if (has("utd")) {
    const auto t0 = std::chrono::steady_clock::now();
    pointRows(room, *utdModelFor(room, c), o, out.rows);
    out.utd_seconds = since(t0);
  }
  if (has("exact")) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why_not, assumption;
    const auto exact = exactModelFor(room, c, why_not, assumption, false);
    out.exact_available = exact != nullptr;
    out.exact_note = exact ? assumption : why_not;
    if (exact) {
      pointRows(room, *exact, o, out.rows);
      std::string a2;
      const auto incoherent = exactModelFor(room, c, why_not, a2, true);
      if (incoherent && incoherent->name() != exact->name()) {
        pointRows(room, *incoherent, o, out.rows);
        out.exact_note += "; " + incoherent->name() + ": the floor reflection added as energy, what an energy ray "
                                                       "tracer (the WBSDF model) can match";
      }
    }
    out.exact_seconds = since(t0);
  }
  return out;
}

}  // namespace diffray::compare
