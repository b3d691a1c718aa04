// diffray_bench: prints one JSON line per benchmark, each with the anchor it is compared against,
// measured in the same run (tools/bench runs it).
//   transport:   diffray's signed-energy tracer vs a plain rtcIntersect1 loop over the same scene, with the
//                same number of intersection queries per path and the same thread count (the target's
//                anchor), and vs the same queries in Embree's coherent packets of the width diffray uses.
//   room:        the acoustic tracer vs a plain rtcIntersect1 loop on each shipped room (room_bench.cpp).
//   room-wbsdf:  rays and seconds `none` and `wbsdf` each need on a reverberant room (two-rooms) before
//                every band metric stays within one JND of a 4M-ray run (room_wbsdf_bench.cpp).
//   convergence: RMS error of a validation case against its oracle as rays grow, for plain Monte Carlo and
//                randomised quasi-Monte Carlo; the fitted slope of log(error) vs log(rays) (-0.5 = 1/√N).
//   fdtd:        the FDTD wave reference's cell updates per second on two-rooms' 500 Hz grid beside a
//                STREAM-like triad's bytes/s over arrays of the grid's size (fdtd_bench.cpp).
//   btm:         the BTM edge-diffraction reference on the 4 × 2 m plate on ground, second order, 96
//                frequencies per octave 100 Hz–4 kHz at four receivers, beside the same field one frequency
//                at a time at three of them (btm_bench.cpp).
//   btm-box:     the same reference on a 1.2 × 0.6 × 1.8 m rigid box on ground, second order, 96 frequencies
//                per octave 100 Hz–4 kHz at one receiver, beside one frequency at a time (btm_bench.cpp).
//   realtime:    the playback callback's cost per 256-frame block (3 s stereo IR, 48 kHz) against the
//                block's duration (realtime_bench.cpp).
//   render-is:   the light tracer's importance-sampled WBSDF shifts vs uniform shifts at equal wall time,
//                errors against the absolute Fraunhofer double slit, and on the CD scene against an 8× longer
//                importance-sampled render (render_is_bench.cpp).
#include <embree3/rtcore.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "btm_bench.h"
#include "fdtd_bench.h"
#include "realtime_bench.h"
#include "render_is_bench.h"
#include "room_bench.h"
#include "room_wbsdf_bench.h"

#include "diffray/core/parallel.h"
#include "diffray/room/scene_file.h"
#include "diffray/transport/tracer.h"
#include "diffray/validate/case.h"
#include "diffray/wbsdf/microstructure.h"

namespace {

using namespace diffray;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The slit-fraunhofer scene: a slit table at z = 0, a screen 5 m behind.
struct BenchScene {
  transport::Scene scene;
  transport::CollimatedSource source;
  BenchScene() {
    const double a = 100e-6, lambda = 500e-9, z = 5.0;
    wbsdf::TableOptions o;
    o.wavelength_m = lambda;
    o.u_half_range_per_m = 0.02 / lambda;
    o.rows_per_feature = 8;
    o.cells_per_coherence = 200;
    transport::Occluder occ;
    occ.table_x = wbsdf::WbsdfTable::build(*wbsdf::Openings::slit(a), o);
    occ.half_x_m = a;
    occ.half_y_m = 0.6;
    scene.addOccluder(occ);
    receiver::Screen screen;
    screen.frame.origin = core::Vec3(0, 0, z);
    screen.half_x_m = 0.075;
    screen.half_y_m = 0.6;
    screen.nx = 151;
    scene.addScreen(screen);
    scene.build();
    source.frame.origin = core::Vec3(0, 0, -0.5);
    source.half_x_m = 0.5 * a;
    source.half_y_m = 0.5;
    source.wavelength_m = lambda;
  }
};

// Paths per second of `chunkHits(rng, n)`, which traces n paths with its own generator and returns how many
// reached the screen, over chunks of 16384 paths on every thread (the anchors' shared harness).
template <class ChunkHits>
double anchorPathsPerSecond(std::uint64_t paths, const char* anchor, ChunkHits&& chunkHits) {
  const auto t0 = Clock::now();
  const std::uint64_t chunk = 16384;
  const std::uint64_t chunks = paths / chunk;
  const double hits = tbb::parallel_reduce(
      tbb::blocked_range<std::uint64_t>(0, chunks, 1), 0.0,
      [&](const tbb::blocked_range<std::uint64_t>& r, double acc) {
        for (std::uint64_t c = r.begin(); c != r.end(); ++c) {
          core::Rng rng(7, c);
          acc += chunkHits(rng, chunk);
        }
        return acc;
      },
      std::plus<double>(), tbb::simple_partitioner());
  const double s = secondsSince(t0);
  if (hits < 0.5 * static_cast<double>(chunks * chunk)) std::cerr << "bench: " << anchor << " rays missed the screen\n";
  return static_cast<double>(chunks * chunk) / s;
}

// The anchor: per path, one rtcIntersect1 from the source window to the occluder and one from there in a
// random direction inside the screen's cone, the same queries diffray makes, with nothing else.
double plainEmbreeRaysPerSecond(const BenchScene& b, std::uint64_t paths) {
  RTCScene scene = b.scene.embree()->handle();
  return anchorPathsPerSecond(paths, "anchor", [&](core::Rng& rng, std::uint64_t n) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    double acc = 0.0;
    for (std::uint64_t i = 0; i < n; ++i) {
      RTCRayHit rh;
      rh.ray.org_x = static_cast<float>((2 * rng.uniform() - 1) * b.source.half_x_m);
      rh.ray.org_y = static_cast<float>((2 * rng.uniform() - 1) * b.source.half_y_m);
      rh.ray.org_z = -0.5f;
      rh.ray.dir_x = 0.0f;
      rh.ray.dir_y = 0.0f;
      rh.ray.dir_z = 1.0f;
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = INFINITY;
      rh.ray.mask = 0xFFFFFFFFu;
      rh.ray.flags = 0;
      rh.ray.time = 0.0f;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      const float ox = rh.ray.org_x, oy = rh.ray.org_y;
      rh.ray.org_x = ox;
      rh.ray.org_y = oy;
      rh.ray.org_z = 0.0f;
      rh.ray.dir_x = static_cast<float>(0.0149 * (2 * rng.uniform() - 1));
      rh.ray.dir_z = std::sqrt(1.0f - rh.ray.dir_x * rh.ray.dir_x);
      rh.ray.tnear = 1e-6f;
      rh.ray.tfar = INFINITY;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      acc += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? 1.0 : 0.0;
    }
    return acc;
  });
}

// A second anchor: the same queries in Embree's packets with the coherent-ray hint, of the width diffray's
// tracer uses on this CPU (geometry::EmbreeScene::intersectPacket: 16 where Embree has native 16-wide
// packets, else 8), so that diffray's own cost per path shows beside the ratio the target is set on.
template <int W, typename RayHitW, typename IntersectW>
double packetEmbreeRaysPerSecond(const BenchScene& b, std::uint64_t paths, IntersectW intersect) {
  RTCScene scene = b.scene.embree()->handle();
  return anchorPathsPerSecond(paths, "packet anchor", [&](core::Rng& rng, std::uint64_t n) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[W];
    std::fill(valid, valid + W, -1);
    double acc = 0.0;
    for (std::uint64_t i = 0; i < n; i += W) {
      alignas(64) RayHitW rh;
      for (int k = 0; k < W; ++k) {
        rh.ray.org_x[k] = static_cast<float>((2 * rng.uniform() - 1) * b.source.half_x_m);
        rh.ray.org_y[k] = static_cast<float>((2 * rng.uniform() - 1) * b.source.half_y_m);
        rh.ray.org_z[k] = -0.5f;
        rh.ray.dir_x[k] = 0.0f;
        rh.ray.dir_y[k] = 0.0f;
        rh.ray.dir_z[k] = 1.0f;
        rh.ray.tnear[k] = 0.0f;
        rh.ray.tfar[k] = INFINITY;
        rh.ray.mask[k] = 0xFFFFFFFFu;
        rh.ray.flags[k] = 0;
        rh.ray.time[k] = 0.0f;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      }
      intersect(valid, scene, &ctx, &rh);
      for (int k = 0; k < W; ++k) {
        rh.ray.org_z[k] = 0.0f;
        rh.ray.dir_x[k] = static_cast<float>(0.0149 * (2 * rng.uniform() - 1));
        rh.ray.dir_z[k] = std::sqrt(1.0f - rh.ray.dir_x[k] * rh.ray.dir_x[k]);
        rh.ray.tnear[k] = 1e-6f;
        rh.ray.tfar[k] = INFINITY;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      }
      intersect(valid, scene, &ctx, &rh);
      for (int k = 0; k < W; ++k) acc += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID ? 1.0 : 0.0;
    }
    return acc;
  });
}
double packetEmbreeRaysPerSecond(const BenchScene& b, std::uint64_t paths) {
  return b.scene.embree()->nativePacket16() ? packetEmbreeRaysPerSecond<16, RTCRayHit16>(b, paths, rtcIntersect16)
                                            : packetEmbreeRaysPerSecond<8, RTCRayHit8>(b, paths, rtcIntersect8);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void benchTransport(std::uint64_t paths) {
  BenchScene b;
  const int threads = core::ThreadLimit::current();
  plainEmbreeRaysPerSecond(b, paths / 8);  // warm-up
  packetEmbreeRaysPerSecond(b, paths / 8);
  // Alternate the anchors and diffray three times and keep the medians: the machine's speed drifts.
  std::vector<double> embree_runs, packet_runs, diffray_runs;
  double segments_per_path = 0.0;
  for (int rep = 0; rep < 3; ++rep) {
    embree_runs.push_back(plainEmbreeRaysPerSecond(b, paths));
    packet_runs.push_back(packetEmbreeRaysPerSecond(b, paths));
    transport::TraceOptions to;
    to.rays = paths;
    to.seed = static_cast<std::uint64_t>(rep + 1);
    const auto t0 = Clock::now();
    const auto tr = transport::trace(b.scene, b.source, to);
    diffray_runs.push_back(static_cast<double>(tr.rays) / secondsSince(t0));
    segments_per_path = static_cast<double>(tr.segments) / static_cast<double>(tr.rays);
  }
  const double embree = median(embree_runs), packets = median(packet_runs), diffray = median(diffray_runs);
  nlohmann::json j{{"bench", "transport"},
                   {"scene", "slit-fraunhofer"},
                   {"paths", paths},
                   {"segments_per_path", segments_per_path},
                   {"embree_rays_per_s", embree},
                   {"diffray_rays_per_s", diffray},
                   {"ratio", diffray / embree},
                   {"embree_packet_rays_per_s", packets},
                   {"embree_packet_width", b.scene.embree()->nativePacket16() ? 16 : 8},
                   {"ratio_vs_packets", diffray / packets},
                   {"threads", threads}};
  std::cout << j.dump() << std::endl;
}

void benchConvergence(const std::string& case_name, bool qmc) {
  const validate::CaseInfo* info = validate::findCase(case_name);
  const validate::Params params = validate::resolveParams(*info, {});
  std::vector<double> rays, rms;
  for (std::uint64_t n = 250'000; n <= 16'000'000; n *= 4) {
    // Average the squared error over a few seeds so the slope is not one seed's luck.
    double sq = 0.0;
    const int seeds = 3;
    for (int s = 1; s <= seeds; ++s) {
      validate::RunOptions ro;
      ro.rays = n;
      ro.seed = static_cast<std::uint64_t>(s);
      ro.qmc = qmc;
      const auto r = info->run(params, ro);
      sq += r.rms_error_rel_peak * r.rms_error_rel_peak;
    }
    rays.push_back(static_cast<double>(n));
    rms.push_back(std::sqrt(sq / seeds));
  }
  // Least-squares slope of log(rms) against log(rays).
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) mx += std::log(rays[i]), my += std::log(rms[i]);
  mx /= static_cast<double>(rays.size());
  my /= static_cast<double>(rays.size());
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    sxy += (std::log(rays[i]) - mx) * (std::log(rms[i]) - my);
    sxx += (std::log(rays[i]) - mx) * (std::log(rays[i]) - mx);
  }
  nlohmann::json j{{"bench", "convergence"}, {"case", case_name}, {"sampler", qmc ? "qmc" : "mc"},
                   {"rays", rays},           {"rms_error_rel_peak", rms}, {"slope", sxy / sxx},
                   {"anchor_slope_1_over_sqrt_n", -0.5}};
  std::cout << j.dump() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "all";
  try {
    // `diffray_bench transport [PATHS]`: fewer paths for profiling.
    if (which == "all" || which == "transport")
      benchTransport(argc > 2 && which == "transport" ? std::stoull(argv[2]) : 8'000'000);
    if (which == "all" || which == "room") {
      // The shipped rooms, from the source folder (DIFFRAY_SOURCE_DIR) or the working directory.
      // `diffray_bench room NAME [RAYS]` runs one of them (profiling).
      const std::uint64_t rays = argc > 3 && which == "room" ? std::stoull(argv[3]) : 200'000;
      for (const char* name : {"shoebox", "l-hall", "two-rooms"}) {
        if (argc > 2 && which == "room" && std::string(argv[2]) != name) continue;
        const std::string path = std::string(DIFFRAY_BENCH_ROOMS) + "/" + name + ".json";
        bench::benchRoom(room::loadRoom(path), name, rays);
      }
    }
    if (which == "all" || which == "room-wbsdf") {
      // `diffray_bench room-wbsdf [NAME]`: a shipped room (default two-rooms).
      const std::string name = argc > 2 && which == "room-wbsdf" ? argv[2] : "two-rooms";
      bench::benchRoomWbsdf(std::string(DIFFRAY_BENCH_ROOMS) + "/" + name + ".json", name, 4'000'000);
    }
    if (which == "all" || which == "convergence") {
      benchConvergence("slit-fraunhofer", false);
      benchConvergence("slit-fraunhofer", true);
    }
    if (which == "all" || which == "realtime") bench::benchRealtime(20.0);
    if (which == "all" || which == "fdtd")  // `diffray_bench fdtd [STEPS]`
      bench::benchFdtd(room::loadRoom(std::string(DIFFRAY_BENCH_ROOMS) + "/two-rooms.json"), "two-rooms",
                       argc > 2 && which == "fdtd" ? std::stoi(argv[2]) : 400);
    if (which == "all" || which == "btm")  // `diffray_bench btm [PER_OCTAVE]`
      bench::benchBtm(argc > 2 && which == "btm" ? std::stoi(argv[2]) : 96);
    if (which == "all" || which == "btm-box")  // `diffray_bench btm-box [PER_OCTAVE]`
      bench::benchBtmBox(argc > 2 && which == "btm-box" ? std::stoi(argv[2]) : 96);
    if (which == "all" || which == "render-is") {
      bench::benchRenderIs(20'000'000);
      bench::benchRenderIsScene(std::string(DIFFRAY_BENCH_ROOMS) + "/light/cd.json", "cd", 10'000'000);
    }
  } catch (const std::exception& e) {
    std::cerr << "diffray_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
