// The BTM reference's speed on the plate and on the box on ground (see btm_bench.h).
#include "btm_bench.h"

#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <string>
#include <cstdio>
#include <vector>

#include "diffray/compare/point_models.h"
#include "diffray/core/parallel.h"
#include "diffray/reference/btm_box.h"
#include "diffray/reference/btm_plate.h"
#include "diffray/reference/btm_spectrum.h"
#include "diffray/room/scene_file.h"

namespace diffray::bench {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr double kPi = 3.14159265358979323846;
constexpr double kSoundSpeed = 343.0;

// Equal steps in log frequency from 100 Hz to 4 kHz inclusive, `per_octave` of them per octave (rounded).
std::vector<double> benchGridHz(int per_octave) {
  std::vector<double> hz;
  const int steps = static_cast<int>(std::lround(per_octave * std::log2(4000.0 / 100.0)));
  for (int i = 0; i <= steps; ++i) hz.push_back(100.0 * std::pow(40.0, static_cast<double>(i) / steps));
  return hz;
}

std::vector<double> wavenumbers(const std::vector<double>& hz) {
  std::vector<double> k;
  for (double f : hz) k.push_back(2.0 * kPi * f / kSoundSpeed);
  return k;
}

}  // namespace

void benchBtm(int per_octave) {
  // The plate x ∈ [−2, 2] m in the plane y = 0, standing on the ground z = 0, 2 m tall; the source 2 m before
  // it at 0.5 m height; receivers 2 m behind it: behind the middle low and high, behind the side edge's
  // region and past the side edge.
  reference::BtmPlate plate{{core::Vec3(-2, 0, 0), core::Vec3(2, 0, 0), core::Vec3(2, 0, 2), core::Vec3(-2, 0, 2)}};
  const core::Vec3 source(0.0, -2.0, 0.5);
  const std::vector<core::Vec3> receivers{{0.0, 2.0, 0.5}, {0.0, 2.0, 1.5}, {1.5, 2.0, 0.5}, {2.5, 2.0, 0.5}};
  const std::vector<double> hz = benchGridHz(per_octave), k = wavenumbers(hz);

  const auto t0 = Clock::now();
  std::vector<std::vector<reference::BtmPlateField>> spectra;
  for (const core::Vec3& r : receivers) spectra.push_back(reference::btmPlateSpectrum(k, plate, 0.0, source, r, 2));
  const double spectrum_s = secondsSince(t0);

  // UTD on the same scene as compare runs it (rooms/screen.json: the same plate, ground, source and four
  // receivers), the same frequencies.
  const room::Room screen = room::loadRoom(std::string(DIFFRAY_BENCH_ROOMS) + "/screen.json");
  const auto utd = compare::utdModelFor(screen, kSoundSpeed);
  const auto t2 = Clock::now();
  for (const room::Listener& l : screen.listeners) utd->relativePressure(screen.sources[0].position_m, l.position_m, hz);
  const double utd_s = secondsSince(t2);

  // The anchor: one frequency at a time, at three of the grid's frequencies, at the first receiver.
  const std::size_t picks[3] = {0, hz.size() / 2, hz.size() - 1};
  double anchor_s = 0.0, worst = 0.0;
  for (std::size_t p : picks) {
    const auto t1 = Clock::now();
    const reference::BtmPlateField u = reference::btmPlateOnGroundField(k[p], plate, 0.0, source, receivers[0], 2);
    anchor_s += secondsSince(t1);
    worst = std::max(worst, std::abs(u.total() - spectra[0][p].total()) * (receivers[0] - source).norm());
  }
  std::printf("{\"bench\":\"btm\",\"scene\":\"4x2 m plate on ground\",\"order\":2,\"receivers\":%zu,\"frequencies\":%zu,"
              "\"per_octave\":%d,\"f_lo_hz\":100,\"f_hi_hz\":%.1f,\"threads\":%d,\"seconds\":%.2f,\"target_s\":60,"
              "\"anchor_one_frequency_at_a_time_s_per_frequency\":%.2f,\"anchor_frequencies_hz\":[%.1f,%.1f,%.1f],"
              "\"anchor_extrapolated_s\":%.0f,\"max_difference_re_free_field\":%.2e,\"utd_seconds\":%.3f,"
              "\"utd_target_s\":1}\n",
              receivers.size(), hz.size(), per_octave, hz.back(), core::ThreadLimit::current(), spectrum_s,
              anchor_s / 3.0, hz[picks[0]], hz[picks[1]], hz[picks[2]],
              anchor_s / 3.0 * static_cast<double>(hz.size() * receivers.size()), worst, utd_s);
  std::fflush(stdout);
}

void benchBtmBox(int per_octave) {
  // The box x ∈ [0, 1.2], y ∈ [0, 0.6], z ∈ [0, 1.8] m (a cupboard) on the ground z = 0; the source 2 m
  // before its front face at 0.5 m height, the receiver 2 m behind its back face at 1.2 m, off the middle.
  const reference::BtmBox box{core::Vec3(0, 0, 0), core::Vec3(1.2, 0.6, 1.8)};
  const core::Vec3 source(0.6, -2.0, 0.5), receiver(0.9, 2.6, 1.2);
  const std::vector<double> hz = benchGridHz(per_octave), k = wavenumbers(hz);

  const auto t0 = Clock::now();
  const std::vector<reference::BtmBoxField> spectrum = reference::btmBoxSpectrum(k, box, 0.0, source, receiver, 2);
  const double spectrum_s = secondsSince(t0);

  // The anchor: one frequency at a time, at three of the grid's frequencies.
  const std::size_t picks[3] = {0, hz.size() / 2, hz.size() - 1};
  double anchor_s = 0.0, worst = 0.0;
  for (std::size_t p : picks) {
    const auto t1 = Clock::now();
    const reference::BtmBoxField u = reference::btmBoxOnGroundField(k[p], box, 0.0, source, receiver, 2);
    anchor_s += secondsSince(t1);
    worst = std::max(worst, std::abs(u.total() - spectrum[p].total()) * (receiver - source).norm());
  }
  std::printf("{\"bench\":\"btm-box\",\"scene\":\"1.2x0.6x1.8 m box on ground\",\"order\":2,\"receivers\":1,"
              "\"frequencies\":%zu,\"per_octave\":%d,\"f_lo_hz\":100,\"f_hi_hz\":%.1f,\"threads\":%d,\"seconds\":%.2f,"
              "\"anchor_one_frequency_at_a_time_s_per_frequency\":%.2f,\"anchor_frequencies_hz\":[%.1f,%.1f,%.1f],"
              "\"anchor_extrapolated_s\":%.0f,\"max_difference_re_free_field\":%.2e}\n",
              hz.size(), per_octave, hz.back(), core::ThreadLimit::current(), spectrum_s, anchor_s / 3.0, hz[picks[0]],
              hz[picks[1]], hz[picks[2]], anchor_s / 3.0 * static_cast<double>(hz.size()), worst);
  std::fflush(stdout);
}

}  // namespace diffray::bench
