// `diffray_bench room-wbsdf [ROOM]`: how many rays, and how much time, the WBSDF model needs in a
// reverberant room to converge as far as the geometric model does. For each model a reference run with many
// rays (seed 1000); then rays from 31,250 up, two seeds each, until both seeds' figures all lie within
// one JND of the reference: every listener, every band, EDT and T30 within 5 %, C50 and C80 within 1 dB
// (ISO 3382-1 Annex A), from the energy histograms. A figure missing in one run and present in the other
// counts as outside. Ray counts grow by 2^{1/4} per step (19 %: finer than the 1.5x the target allows). At the ray count found, the figures of the synthesized
// WAV (as `diffray ir` makes it, with the run's seed) are compared with the reference's too and the count
// outside reported: the synthesis draws its own random Dirac sequence, so a WAV's low bands differ from
// seed to seed by more than the rays explain. The model's time is the wall time of simulateRoom at that ray count (its pilot trace and
// image sources included, as a user waits for them); the anchor is `none` on the same scene in the same run.
#include "room_wbsdf_bench.h"

#include <algorithm>
#include <string>
#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "diffray/ir/metrics.h"
#include "diffray/ir/synthesis.h"
#include "diffray/core/rng.h"
#include "diffray/room/air.h"
#include "diffray/room/scene_file.h"
#include "diffray/transport/room_occluders.h"
#include "diffray/transport/room_simulation.h"

namespace diffray::bench {
namespace {

using Figures = std::vector<std::vector<ir::BandMetrics>>;  // [listener][band]

struct Run {
  Figures figures, wav;  ///< from the energy histograms, from the synthesized WAV
  double seconds = 0.0;
};

Run run(const room::Room& room, const std::string& model, std::uint64_t rays, std::uint64_t seed) {
  transport::RoomSimulationOptions o;
  o.rays = rays;
  o.seed = seed;
  o.diffraction = model;
  const auto t0 = std::chrono::steady_clock::now();
  const transport::RoomSimulation sim = transport::simulateRoom(room, o);
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (std::size_t l = 0; l < sim.listeners.size(); ++l) {
    const ir::EnergyResponse& resp = sim.listeners[l];
    std::vector<std::vector<double>> totals;
    for (int b = 0; b < room.bands.size(); ++b) totals.push_back(resp.total(b));
    r.figures.push_back(ir::metricsFromHistograms(totals, resp.bin_s));
    // The synthesized IR's figures, as `diffray ir` computes them (its synthesis seed per listener).
    const std::vector<double> p = ir::synthesize(resp, room.output.sample_rate_hz, sim.length_s, room.volume(),
                                                 sim.speed_of_sound_m_s, ir::listenerSeed(seed, l));
    r.wav.push_back(ir::metricsFromSignal(p, room.output.sample_rate_hz, room.bands));
  }
  return r;
}

// Figures of `a` outside one JND of `ref`; their names ("LISTENER BAND figure") appended to `names` if given.
int outsideJnd(const Figures& a, const Figures& ref, const room::Room* room = nullptr,
               std::vector<std::string>* names = nullptr) {
  int outside = 0;
  const auto check = [&](double x, double y, bool relative, double jnd, std::size_t l, std::size_t b, const char* what) {
    if (std::isnan(x) && std::isnan(y)) return;
    const bool out = std::isnan(x) || std::isnan(y) || std::abs(relative ? x / y - 1.0 : x - y) > jnd;
    if (!out) return;
    ++outside;
    if (names && room)
      names->push_back(room->listeners[l].name + " " + room->bands.label(static_cast<int>(b)) + " Hz " + what);
  };
  for (std::size_t l = 0; l < a.size(); ++l)
    for (std::size_t b = 0; b < a[l].size(); ++b) {
      check(a[l][b].edt, ref[l][b].edt, true, 0.05, l, b, "EDT");
      check(a[l][b].t30, ref[l][b].t30, true, 0.05, l, b, "T30");
      check(a[l][b].c50, ref[l][b].c50, false, 1.0, l, b, "C50");
      check(a[l][b].c80, ref[l][b].c80, false, 1.0, l, b, "C80");
    }
  return outside;
}

struct Converged {
  std::uint64_t rays = 0;
  int wav_outside = 0;  ///< WAV figures outside one JND of the reference's, both seeds, at `rays`
  double seconds = 0.0;
  double reference_seconds = 0.0;
  int figures = 0;
  std::vector<std::string> last_outside;  ///< the figures outside one JND (either seed) one step before
};

Converged converge(const room::Room& room, const std::string& model, std::uint64_t reference_rays) {
  Converged c;
  const Run ref = run(room, model, reference_rays, 1000);
  c.reference_seconds = ref.seconds;
  for (const auto& l : ref.figures) c.figures += 4 * static_cast<int>(l.size());
  for (int step = 0;; ++step) {
    const auto rays = static_cast<std::uint64_t>(std::llround(31'250.0 * std::pow(2.0, 0.25 * step)));
    if (rays > reference_rays / 4) break;
    double seconds = 0.0;
    bool ok = true;
    int wav_outside = 0;
    std::vector<std::string> outside;
    for (std::uint64_t seed : {1, 2}) {
      const Run r = run(room, model, rays, seed);
      seconds += 0.5 * r.seconds;
      ok = outsideJnd(r.figures, ref.figures, &room, &outside) == 0 && ok;
      wav_outside += outsideJnd(r.wav, ref.wav);
    }
    if (!ok) {
      std::sort(outside.begin(), outside.end());
      outside.erase(std::unique(outside.begin(), outside.end()), outside.end());
      c.last_outside = outside;
    }
    if (ok) {
      c.rays = rays;
      c.seconds = seconds;
      c.wav_outside = wav_outside;
      return c;
    }
  }
  return c;  // rays 0: not within reach below a quarter of the reference's rays
}

// The relative second moment E[w_b²]/E[w_b]² of each band's portal weight (RoomOccluders::scatterPortal) for
// a ray meeting occluder k at its centre along its normal, with the band picked uniformly and the frequency
// uniformly inside it, as the tracer draws them: the factor by which the portal multiplies the variance of
// what each band carries past the opening (1 for a plain opening). One direction serves every band, so the
// bands whose laws differ most from the mixture of all of them pay the most.
std::vector<double> portalSecondMoments(const room::Room& room, const transport::RoomOccluders& occ, int k,
                                        double speed_m_s) {
  const room::Occluder& o = room.occluders[static_cast<std::size_t>(k)];
  const int n = room.bands.size();
  std::vector<double> sum(static_cast<std::size_t>(n), 0.0), sum2(sum);
  core::Rng seeder(7, 0);
  core::FastRng rng(seeder);
  const int draws = 200'000;
  for (int d = 0; d < draws; ++d) {
    const double x = rng.uniform() * n;
    const int pick = std::min(n - 1, static_cast<int>(x));
    const double place = std::min(1.0, x - pick);
    double lambda[core::kMaxBands], w[core::kMaxBands], xi[4];
    for (int b = 0; b < n; ++b)
      lambda[b] = speed_m_s / (room.bands.lowerHz(b) + place * (room.bands.upperHz(b) - room.bands.lowerHz(b)));
    for (double& v : xi) v = rng.uniform();
    if (!occ.scatterPortal(k, o.origin_m, o.normal, lambda, n, pick, xi, w).alive) continue;
    for (int b = 0; b < n; ++b) sum[static_cast<std::size_t>(b)] += w[b], sum2[static_cast<std::size_t>(b)] += w[b] * w[b];
  }
  std::vector<double> m2;
  for (int b = 0; b < n; ++b) {
    const double mean = sum[static_cast<std::size_t>(b)] / draws;
    m2.push_back(mean > 0.0 ? sum2[static_cast<std::size_t>(b)] / draws / (mean * mean) : NAN);
  }
  return m2;
}

}  // namespace

void benchRoomWbsdf(const std::string& room_path, const std::string& label, std::uint64_t reference_rays) {
  const room::Room room = room::loadRoom(room_path);
  {
    const transport::RoomOccluders occ(room, room::speedOfSound(room.air) / room.bands.upperHz(room.bands.size() - 1));
    for (std::size_t k = 0; k < room.occluders.size(); ++k) {
      if (!occ.nextEventSupported(static_cast<int>(k))) continue;
      nlohmann::ordered_json m2;
      const std::vector<double> v = portalSecondMoments(room, occ, static_cast<int>(k), room::speedOfSound(room.air));
      for (int b = 0; b < room.bands.size(); ++b) m2[room.bands.label(b)] = v[static_cast<std::size_t>(b)];
      std::cout << nlohmann::ordered_json{{"bench", "room-wbsdf"}, {"room", label}, {"occluder", room.occluders[k].name},
                                          {"portal_weight_relative_second_moment_at_normal_incidence", m2}}
                       .dump()
                << std::endl;
    }
  }
  Converged by_model[2];
  const char* models[2] = {"none", "wbsdf"};
  for (int m = 0; m < 2; ++m) {
    by_model[m] = converge(room, models[m], reference_rays);
    nlohmann::ordered_json j{{"bench", "room-wbsdf"},          {"room", label},
                             {"model", models[m]},             {"reference_rays", reference_rays},
                             {"reference_s", by_model[m].reference_seconds},
                             {"figures", by_model[m].figures}, {"rays_to_1_jnd", by_model[m].rays},
                             {"seconds_to_1_jnd", by_model[m].seconds},
                             {"wav_figures_outside_1_jnd_there", by_model[m].wav_outside},
                             {"outside_1_jnd_one_step_before", by_model[m].last_outside}};
    std::cout << j.dump() << std::endl;
  }
  const bool both = by_model[0].rays > 0 && by_model[1].rays > 0;
  nlohmann::ordered_json j{{"bench", "room-wbsdf"},
                           {"room", label},
                           {"ratio_rays",
                            both ? static_cast<double>(by_model[1].rays) / static_cast<double>(by_model[0].rays) : NAN},
                           {"ratio_seconds", both ? by_model[1].seconds / by_model[0].seconds : NAN},
                           {"target_ratio_seconds", 1.5}};
  std::cout << j.dump() << std::endl;
}

}  // namespace diffray::bench
