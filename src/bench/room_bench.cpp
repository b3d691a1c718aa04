// The room benchmark: diffray's acoustic tracer against a plain Embree loop on the same room. The anchor
// traces the same number of rays with the same mean number of rtcIntersect1 queries per ray (diffray's own
// figure from the run just made), reflecting each ray specularly about a precomputed normal at each hit,
// with the same thread count: what ray tracing the room costs with no acoustics at all.
#include "room_bench.h"

#include <embree3/rtcore.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "diffray/core/parallel.h"
#include "diffray/geometry/embree_scene.h"
#include "diffray/room/air.h"
#include "diffray/transport/room_tracer.h"

namespace diffray::bench {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// rtcIntersect1 loop: `rays` rays of `bounces` queries each from the source, specular bounces.
double plainEmbreeRaysPerSecond(const geometry::EmbreeScene& scene, const room::Room& room,
                                const core::Vec3& source, std::uint64_t rays, int bounces) {
  const RTCScene handle = scene.handle();
  // Unit normals precomputed (outside the timing): the anchor does as little per bounce as it can.
  std::vector<std::array<float, 3>> normals;
  for (const auto& t : room.mesh.triangles) {
    const auto& v = room.mesh.vertices;
    const core::Vec3 n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).normalized();
    normals.push_back({float(n.x()), float(n.y()), float(n.z())});
  }
  const auto t0 = Clock::now();
  const std::uint64_t hits = tbb::parallel_reduce(
      tbb::blocked_range<std::uint64_t>(0, rays, 4096), std::uint64_t{0},
      [&](const tbb::blocked_range<std::uint64_t>& r, std::uint64_t acc) {
        core::Rng rng(7, r.begin());
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (std::uint64_t i = r.begin(); i != r.end(); ++i) {
          float o[3] = {float(source.x()), float(source.y()), float(source.z())};
          const double z = 1 - 2 * rng.uniform(), phi = core::kTwoPi * rng.uniform();
          const double s = std::sqrt(std::max(0.0, 1 - z * z));
          float d[3] = {float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)};
          for (int k = 0; k < bounces; ++k) {
            RTCRayHit rh;
            rh.ray.org_x = o[0], rh.ray.org_y = o[1], rh.ray.org_z = o[2];
            rh.ray.dir_x = d[0], rh.ray.dir_y = d[1], rh.ray.dir_z = d[2];
            rh.ray.tnear = 1e-4f, rh.ray.tfar = 1e30f, rh.ray.time = 0, rh.ray.mask = 0xFFFFFFFFu;
            rh.ray.id = 0, rh.ray.flags = 0;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(handle, &context, &rh);
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
            ++acc;
            for (int c = 0; c < 3; ++c) o[c] += rh.ray.tfar * d[c];
            // Specular reflection about the precomputed normal: the cheapest bounce there is.
            const auto& n = normals[rh.hit.primID];
            const float dn = 2.0f * (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
            for (int c = 0; c < 3; ++c) d[c] -= dn * n[c];
          }
        }
        return acc;
      },
      std::plus<std::uint64_t>());
  const double seconds = secondsSince(t0);
  if (hits == 0) return 0.0;
  return static_cast<double>(rays) / seconds;
}

}  // namespace

void benchRoom(const room::Room& room, const std::string& label, std::uint64_t rays) {
  const transport::RoomGeometry geometry(room);
  transport::RoomTraceOptions opt;
  opt.rays = rays;
  opt.speed_of_sound_m_s = room::speedOfSound(room.air);
  opt.air_m_per_m = room::airAttenuationPerM(room.air, room.bands);
  opt.length_s = room.output.ir_length_s > 0 ? room.output.ir_length_s : 2.0;
  opt.bin_s = room.output.histogram_bin_s;
  opt.skip_order = room.output.ism_order;
  double best_ratio = 0, diffray_rps = 0, embree_rps = 0, per_ray = 0;
  // Median of three alternating runs: Embree's own speed drifts between runs on a shared machine.
  std::vector<double> ratios, d_rps, e_rps;
  for (int rep = 0; rep < 3; ++rep) {
    const auto res = transport::traceRoom(room, geometry, 0, opt);
    per_ray = static_cast<double>(res.segments) / static_cast<double>(res.rays);
    const double d = static_cast<double>(res.rays) / res.seconds;
    const geometry::EmbreeScene scene(room.mesh);
    const double e = plainEmbreeRaysPerSecond(scene, room, room.sources[0].position_m, rays,
                                              static_cast<int>(std::lround(per_ray)));
    ratios.push_back(d / e);
    d_rps.push_back(d);
    e_rps.push_back(e);
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  best_ratio = median(ratios);
  diffray_rps = median(d_rps);
  embree_rps = median(e_rps);
  nlohmann::json j{{"bench", "room"},
                   {"room", label},
                   {"triangles", room.mesh.triangleCount()},
                   {"rays", rays},
                   {"queries_per_ray", per_ray},
                   {"threads", core::ThreadLimit::current()},
                   {"embree_rays_per_s", embree_rps},
                   {"diffray_rays_per_s", diffray_rps},
                   {"ratio", best_ratio},
                   {"target_ratio", 0.7}};
  std::cout << j.dump() << std::endl;
}

}  // namespace diffray::bench
