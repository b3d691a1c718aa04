// Room validation cases with exact oracles:
//   free-field:  listener spheres at several distances from a point source in a fully absorbing room;
//                fluence against the ball average of e^{−m d}/d², the exact delay, and the fraction of
//                rays that cross each sphere against (1 − √(1 − R²/r²))/2 (the sphere's solid angle over 4π).
//   shoebox-ism: the image sources of transport/image_sources.h (general rooms, validated by tracing)
//                against the closed-form image lattice of reference/image_lattice.h: every arrival's delay
//                and per-band energy.
#include <chrono>
#include <cmath>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/reference/image_lattice.h"
#include "diffray/reference/room_acoustics.h"
#include "diffray/room/air.h"
#include "diffray/transport/image_sources.h"
#include "diffray/transport/room_tracer.h"
#include "diffray/validate/room_setup.h"

namespace diffray::validate {

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

CaseInfo freeFieldCase() {
  CaseInfo c{"free-field", "point source in free field: fluence 1/r², delay r/c, sphere hit fraction", {}, 4'000'000, {}};
  c.params = {{"distance", {1, 2, 4}, "source-listener distances (m), one listener each"},
              {"radius", {0.3}, "listener sphere radius (m)"}};
  c.param("distance").list = true;
  c.run = [](const Params& p, const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const double radius = p.at("radius")[0];
    const std::vector<double>& dist = p.at("distance");
    double far = 0;
    for (double d : dist) {
      if (!(d > radius)) throw core::InputError("--distance", "every distance must exceed the radius");
      far = std::max(far, d);
    }
    // A fully absorbing box far larger than the distances: only the direct sound reaches a listener.
    const double half = 4.0 * (far + radius) + 1.0;
    ShoeboxSpec spec;
    spec.dims_m = {2 * half, 2 * half, 2 * half};
    spec.source_m = {half, half, half};
    spec.listener_m = {half + dist[0], half, half};
    spec.radius_m = radius;
    spec.absorption = {1.0};
    room::Room room = makeShoebox(spec);
    room.listeners.clear();
    for (std::size_t i = 0; i < dist.size(); ++i) {
      // Listeners on different axes so that no sphere shadows another (spheres are transparent anyway).
      const core::Vec3 axis = i % 3 == 0 ? core::Vec3(1, 0, 0) : (i % 3 == 1 ? core::Vec3(0, 1, 0) : core::Vec3(0, 0, 1));
      room.listeners.push_back({"L" + std::to_string(i), room.sources[0].position_m + dist[i] * axis, radius});
    }
    const transport::RoomGeometry geometry(room);
    transport::RoomTraceOptions to;
    to.rays = o.rays ? o.rays : 4'000'000;
    to.seed = o.seed;
    to.skip_order = -1;  // rays alone: the direct sound is what is tested
    to.speed_of_sound_m_s = room::speedOfSound(room.air);
    to.air_m_per_m = room::airAttenuationPerM(room.air, room.bands);
    to.length_s = (far + 2 * radius) / to.speed_of_sound_m_s + 0.002;
    to.bin_s = 20e-6;  // fine bins, so that the delay is resolved to 20 µs
    to.on_progress = o.on_progress;
    const auto tr = transport::traceRoom(room, geometry, 0, to);

    CaseResult r;
    r.name = "free-field";
    r.rays = tr.rays;
    double worst_sigma = 0, worst_rel = 0, worst_noise = 0;
    bool ok = true;
    for (std::size_t i = 0; i < dist.size(); ++i) {
      const auto& h = tr.listeners[i];
      const double ball = reference::sphereMeanInverseSquare(radius, dist[i]);
      double t_sum = 0, t_weighted = 0;
      for (int b = 0; b < room.bands.size(); ++b) {
        double sum = 0, var = 0;
        for (int k = 0; k < h.bins(); ++k) {
          sum += h.value(b, k);
          var += h.standardError(b, k) * h.standardError(b, k);  // bins of one crossing: ~uncorrelated
          if (b == 0) {
            t_sum += h.value(b, k);
            t_weighted += h.value(b, k) * (k + 0.5) * h.binSeconds();
          }
        }
        // e^{−m d} over the ball differs from e^{−m r} by O((mR)²): below 1e-4 here.
        const double ref = ball * std::exp(-to.air_m_per_m[b] * dist[i]);
        const double se = std::sqrt(var);
        Row row;
        row.x_m = dist[i];
        row.traced = sum;
        row.reference = ref;
        row.std_error = se;
        row.alt_reference = 1.0 / (dist[i] * dist[i]) * std::exp(-to.air_m_per_m[b] * dist[i]);
        row.label = "r=" + std::to_string(dist[i]).substr(0, 4) + "m," + room.bands.label(b) + "Hz";
        r.rows.push_back(row);
        worst_sigma = std::max(worst_sigma, std::abs(sum - ref) / se);
        worst_rel = std::max(worst_rel, std::abs(sum - ref) / ref);
        worst_noise = std::max(worst_noise, se / ref);
      }
      // Hit fraction: a binomial count (QMC makes it tighter, never looser).
      const double p_hit = reference::sphereHitFraction(radius, dist[i]);
      const double n = static_cast<double>(tr.rays);
      const double frac = static_cast<double>(tr.crossings[i]) / n;
      const double sigma = std::sqrt(p_hit * (1 - p_hit) / n);
      const std::string key = "r" + std::to_string(static_cast<int>(std::lround(dist[i] * 100))) + "cm_";
      r.extra[key + "hit_fraction"] = frac;
      r.extra[key + "hit_fraction_expected"] = p_hit;
      r.extra[key + "hit_fraction_sigmas"] = (frac - p_hit) / sigma;
      ok = ok && std::abs(frac - p_hit) <= 5 * sigma;
      // Delay: the energy centroid of the arrivals. A ray at angle θ to the centre line scores its chord
      // 2√(R² − r²sin²θ) at the chord's midpoint, r·cosθ from the source, with density sinθ dθ: the
      // expected centroid is their ratio of integrals (slightly short of r/c), by quadrature.
      const double r0 = dist[i], theta_max = std::asin(radius / r0);
      const auto chord = [&](double th) { return 2 * std::sqrt(std::max(0.0, radius * radius - r0 * r0 * std::sin(th) * std::sin(th))); };
      const double num = core::integrate([&](double th) { return chord(th) * r0 * std::cos(th) * std::sin(th); }, 0, theta_max, 64);
      const double den = core::integrate([&](double th) { return chord(th) * std::sin(th); }, 0, theta_max, 64);
      const double centroid = t_weighted / t_sum, delay = num / den / to.speed_of_sound_m_s;
      r.extra[key + "delay_ms"] = 1e3 * centroid;
      r.extra[key + "delay_expected_ms"] = 1e3 * delay;
      ok = ok && std::abs(centroid - delay) <= to.bin_s;
    }
    r.max_abs_error_rel_peak = worst_rel;
    r.max_std_error_rel_peak = worst_noise;
    r.rms_error_rel_peak = worst_rel;
    r.target_rel_peak = 5 * worst_noise;
    r.extra["worst_sigmas"] = worst_sigma;
    r.passed = ok && worst_sigma <= 5.0;
    std::ostringstream d;
    d.precision(3);
    d << "fluence within " << worst_sigma << " sigma (5 allowed)";
    r.detail = d.str();
    r.seconds = secondsSince(t0);
    return r;
  };
  return c;
}

CaseInfo shoeboxIsmCase() {
  CaseInfo c{"shoebox-ism", "image sources of any room vs the exact shoebox lattice: delays and energies", {}, 0, {}};
  c.params = shoeboxParams(0.1, 0.2, 0.1);
  c.params.push_back({"order", {4}, "image-source order", 0.0, true, 12.0});
  c.param("order").whole = true;
  c.run = [](const Params& p, const RunOptions&) {
    const auto t0 = std::chrono::steady_clock::now();
    ShoeboxSpec spec = shoeboxFromParams(p);
    spec.wall_spread = 0.1;  // every wall its own absorption: a wall mix-up would show
    const int order = static_cast<int>(p.at("order")[0]);
    const room::Room room = makeShoebox(spec);
    const transport::RoomGeometry geometry(room);
    transport::ImageSourceOptions io;
    io.max_order = order;
    io.speed_of_sound_m_s = room::speedOfSound(room.air);
    io.air_m_per_m = room::airAttenuationPerM(room.air, room.bands);
    io.length_s = 1e6;
    const auto traced = transport::imageSources(room, geometry, 0, 0, io);
    std::vector<double> air(io.air_m_per_m.begin(), io.air_m_per_m.begin() + room.bands.size());
    const auto ref = reference::shoeboxImages(spec.dims_m, spec.source_m, spec.listener_m, specularFactors(room), air,
                                              io.speed_of_sound_m_s, order, reference::kAnyDistance);
    CaseResult r;
    r.name = "shoebox-ism";
    std::size_t matched = 0;
    double worst_delay = 0, worst_energy = 0;
    std::vector<char> used(traced.size(), 0);
    for (const auto& a : ref) {
      Row row;
      row.x_m = a.delay_s;
      row.reference = a.energy[0];
      row.label = "order=" + std::to_string(a.order);
      for (std::size_t k = 0; k < traced.size(); ++k) {
        if (used[k] || std::abs(traced[k].delay_s - a.delay_s) > 1e-9 || traced[k].order != a.order) continue;
        double e_err = 0;
        for (int b = 0; b < room.bands.size(); ++b)
          e_err = std::max(e_err, std::abs(traced[k].energy[b] - a.energy[b]) / a.energy[b]);
        if (e_err > 1e-6) continue;
        used[k] = 1;
        ++matched;
        row.traced = traced[k].energy[0];
        worst_delay = std::max(worst_delay, std::abs(traced[k].delay_s - a.delay_s));
        worst_energy = std::max(worst_energy, e_err);
        break;
      }
      r.rows.push_back(row);
    }
    r.extra["images_reference"] = static_cast<double>(ref.size());
    r.extra["images_traced"] = static_cast<double>(traced.size());
    r.extra["matched"] = static_cast<double>(matched);
    r.extra["worst_delay_error_s"] = worst_delay;
    r.extra["worst_energy_rel_error"] = worst_energy;
    r.max_abs_error_rel_peak = worst_energy;
    r.rms_error_rel_peak = worst_energy;
    r.target_rel_peak = 1e-6;
    r.passed = matched == ref.size() && traced.size() == ref.size();
    std::ostringstream d;
    d << matched << "/" << ref.size() << " arrivals matched (" << traced.size() << " found)";
    r.detail = d.str();
    r.seconds = secondsSince(t0);
    return r;
  };
  return c;
}

}  // namespace diffray::validate
