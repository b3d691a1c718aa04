// `diffray wave ROOM.json`: the FDTD wave reference (reference/fdtd.h) on a room: per listener and octave
// band the strength G (re the free field at 10 m), EDT, T30, C50 and C80 from band energy histograms.
// States the grid and memory of each band on stderr before the work, draws a progress bar, prints a table
// (or with --json the result object); -o writes that object (energy histograms included), --csv one row
// per listener per band, each atomically and together.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "diffray/cli/commands.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/reference/fdtd.h"
#include "diffray/room/scene_file.h"

namespace diffray::cli {

namespace {

struct WaveCliOptions {
  std::string room_file;
  std::string out;
  std::string csv;
  std::vector<double> bands;
  double ppw = 10.0;
  double max_h = 0.1;
  double length_s = 0.0;
};

nlohmann::ordered_json numberOrNull(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

nlohmann::ordered_json resultJson(const room::Room& room, const WaveCliOptions& o, const reference::WaveResult& r) {
  const auto& plan = r.plan;
  nlohmann::ordered_json bands = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < plan.bands.size(); ++k) {
    const auto& bp = plan.bands[k];
    bands.push_back({{"band_hz", room.bands.nominalHz(bp.band)},
                     {"h_m", bp.h_m},
                     {"dt_s", bp.dt_s},
                     {"courant", bp.courant},
                     {"grid", {bp.nx, bp.ny, bp.nz}},
                     {"air_nodes", r.air_nodes[k]},
                     {"steps_per_source", bp.steps},
                     {"memory_estimate_bytes", bp.bytes},
                     {"axial_phase_error_at_upper_edge", bp.phase_error_top},
                     {"seconds", r.seconds[k]}});
  }
  nlohmann::ordered_json listeners = nlohmann::ordered_json::array();
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const auto& li = room.listeners[l];
    const auto& lr = r.listeners[l];
    nlohmann::ordered_json per_band = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < plan.bands.size(); ++k) {
      const auto& m = lr.metrics[k];
      per_band[room.bands.label(plan.bands[k].band)] = {
          {"g_db", numberOrNull(lr.g_db[k])}, {"edt_s", numberOrNull(m.edt)}, {"t20_s", numberOrNull(m.t20)},
          {"t30_s", numberOrNull(m.t30)},     {"c50_db", numberOrNull(m.c50)}, {"c80_db", numberOrNull(m.c80)},
          {"points", lr.points[k]},           {"energy", lr.energy[k]}};
    }
    listeners.push_back({{"name", li.name},
                         {"position_m", {li.position_m.x(), li.position_m.y(), li.position_m.z()}},
                         {"radius_m", li.radius_m},
                         {"bands", per_band}});
  }
  return {{"diffray_version", DIFFRAY_VERSION},
          {"model", "fdtd-srl"},
          {"room", room.name},
          {"room_file", o.room_file},
          {"speed_of_sound_m_s", plan.speed_of_sound_m_s},
          {"length_s", plan.length_s},
          {"histogram_bin_s", plan.bin_s},
          {"ppw", o.ppw},
          {"max_h_m", o.max_h},
          {"threads", core::ThreadLimit::current()},
          {"energy_units", "J/m2 per bin: a source of power P gives P/r^2 in free field"},
          {"bands", bands},
          {"listeners", listeners},
          {"warnings", r.warnings}};
}

std::string fmt(double v, const char* f) {
  if (!std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

// The plan of a wave run on stderr, before its first time step: per band the grid, its steps and memory and
// the axial phase error at the band's top; then the length, the peak memory and the threads.
void printWavePlan(const room::Room& room, const reference::WavePlan& plan) {
  double peak = 0.0;
  for (const auto& bp : plan.bands) {
    peak = std::max(peak, bp.bytes);
    std::fprintf(stderr,
                 "wave: %s Hz: h = %.4g m, dt = %.4g ms, grid %d x %d x %d (%.3g nodes), %ld steps x %zu source(s), "
                 "~%.2f GB; axial phase error at %.0f Hz %.2f %%\n",
                 room.bands.label(bp.band).c_str(), bp.h_m, 1e3 * bp.dt_s, bp.nx, bp.ny, bp.nz,
                 double(bp.nx) * bp.ny * bp.nz, bp.steps, room.sources.size(), bp.bytes / 1e9,
                 room.bands.upperHz(bp.band), 100.0 * bp.phase_error_top);
  }
  std::fprintf(stderr, "wave: %.3g s simulated, peak memory ~%.2f GB of %.1f GB, %d thread(s)\n", plan.length_s,
               peak / 1e9, plan.physical_bytes / 1e9, core::ThreadLimit::current());
}

Runner addWaveCommand(CLI::App& app, CommonOptions& common) {
  auto o = std::make_shared<WaveCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "wave", "Wave-based reference of a room (3D FDTD, one run per octave band): per listener and band G, EDT, "
              "T30, C50, C80 from band energy histograms (reference/fdtd.h).");
  sub->add_option("room", o->room_file, "scene file (see rooms/README.md)")->check(inputPathValidator())->required();
  sub->add_option("-o,--output", o->out, "write the result (histograms included) to this JSON file")
      ->check(outputPathValidator());
  sub->add_option("--csv", o->csv, "write one row per listener per band (G, EDT, T30, C50, C80) to this CSV file")
      ->check(outputPathValidator());
  sub->add_option("--bands", o->bands, "octave band centres to simulate, e.g. 63,125,250,500 (default: every room "
                                       "band up to 500 Hz)")
      ->delimiter(',');
  sub->add_option("--ppw", o->ppw, "grid points per wavelength at each band's upper edge (4-100)")
      ->check(CLI::Range(4.0, 100.0))
      ->capture_default_str();
  sub->add_option("--max-h", o->max_h, "the grid spacing never exceeds this (m)")
      ->check(CLI::Range(1e-3, 10.0))
      ->capture_default_str();
  sub->add_option("--length", o->length_s, "simulated length in s (default: the room file's, or 1.5 x Eyring)")
      ->check(CLI::Range(1e-3, 120.0));
  addThreadsOption(sub, common.threads);
  sub->add_flag("--json", common.json, "print the result as JSON instead of the table");
  return [o, &common]() {
    core::ThreadLimit limit(common.threads);
    std::vector<std::string> warnings;
    const room::Room room = room::loadRoom(o->room_file, &warnings);
    checkOutputFiles({o->out, o->csv}, room.input_files);
    for (double f : o->bands)
      if (!std::isfinite(f)) throw core::InputError("--bands", "must be numbers");
    reference::WaveOptions wo;
    wo.bands_hz = o->bands;
    wo.ppw = o->ppw;
    wo.max_h_m = o->max_h;
    wo.length_s = o->length_s;
    const reference::WavePlan plan = reference::planWave(room, wo);
    core::Progress progress("wave " + room.name, plan.total_steps);
    wo.on_progress = [&progress](std::uint64_t n) { progress.add(n); };
    wo.on_start = [&]() {
      for (const auto& w : warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
      printWavePlan(room, plan);
    };
    const reference::WaveResult r = reference::simulateWave(room, wo);
    progress.finish();
    for (const auto& w : r.warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
    const nlohmann::ordered_json j = resultJson(room, *o, r);

    OutputFiles written;
    if (!o->csv.empty())
      written.write(o->csv, [&](const std::string& f) {
        core::writeFileAtomically(f, [&](std::ostream& out) {
          out << "listener,band_hz,g_db,edt_s,t30_s,c50_db,c80_db\n";
          for (std::size_t l = 0; l < room.listeners.size(); ++l)
            for (std::size_t k = 0; k < r.plan.bands.size(); ++k) {
              const auto& m = r.listeners[l].metrics[k];
              out << room.listeners[l].name << ',' << room.bands.label(r.plan.bands[k].band) << ','
                  << fmt(r.listeners[l].g_db[k], "%.3f") << ',' << fmt(m.edt, "%.4f") << ',' << fmt(m.t30, "%.4f") << ','
                  << fmt(m.c50, "%.3f") << ',' << fmt(m.c80, "%.3f") << '\n';
            }
        });
      });
    if (!o->out.empty())
      written.write(o->out, [&](const std::string& f) {
        core::writeFileAtomically(f, [&](std::ostream& out) { out << jsonText(j, 2) << '\n'; });
      });
    commitAndAnnounce(written);
    if (common.json) {
      std::cout << jsonText(j, 2) << std::endl;
      return 0;
    }
    std::printf("%s: FDTD (SRL), %.3g s, c = %.1f m/s\n", room.name.c_str(), r.plan.length_s, r.plan.speed_of_sound_m_s);
    for (std::size_t l = 0; l < room.listeners.size(); ++l) {
      std::printf("listener %s:\n  band    G dB   EDT s   T30 s  C50 dB  C80 dB  points\n", room.listeners[l].name.c_str());
      for (std::size_t k = 0; k < r.plan.bands.size(); ++k) {
        const auto& m = r.listeners[l].metrics[k];
        std::printf("  %4s %7s %7s %7s %7s %7s %7d\n", room.bands.label(r.plan.bands[k].band).c_str(),
                    fmt(r.listeners[l].g_db[k], "%.1f").c_str(), fmt(m.edt, "%.2f").c_str(), fmt(m.t30, "%.2f").c_str(),
                    fmt(m.c50, "%.1f").c_str(), fmt(m.c80, "%.1f").c_str(), r.listeners[l].points[k]);
      }
    }
    return 0;
  };
}

}  // namespace diffray::cli
