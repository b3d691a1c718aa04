// `diffray compare SCENE.json`, in one of two modes.
// Free-field mode: the level at each listener relative to free field from the WBSDF ray tracer, UTD and the
// exact reference that fits the scene (compare/scene_compare.h), as a table of levels and dB errors against
// the exact reference per band, JSON lines (one object per listener, model and frequency), a CSV file and a
// PNG of level against frequency and against the listener's angle past the shadow boundary. The exact
// reference exists for one edge or barrier (Macdonald's half-plane) or one door or slit (Rayleigh–Sommerfeld).
// Room mode (a closed room holding its source, or --mode room): whole room simulations with diffraction
// none, utd and wbsdf, compared per listener and band by G, early energy, EDT, T30, C50, C80
// (compare/room_compare.h; outputs in cli/compare_room.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "diffray/cli/commands.h"
#include "diffray/cli/compare_room.h"
#include "diffray/cli/plot.h"
#include "diffray/compare/room_compare.h"
#include "diffray/compare/wave_model.h"
#include "diffray/compare/scene_checks.h"
#include "diffray/compare/scene_compare.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "diffray/room/json_fields.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/room/scene_file.h"

namespace diffray::cli {

namespace {

struct CompareCliOptions {
  std::string scene;
  std::string mode = "auto";
  std::string models;  // not given: the mode's every model
  bool models_given = false;
  std::string csv, plot;
  std::uint64_t rays = 0;  // 0: 1e6 in free-field mode, the room file's output.rays in room mode
  int fine = 24;
  std::vector<double> freqs;  // free-field mode: --freq, replaces the fine grid
  bool aim = false;
  std::vector<double> wave_bands;  // room mode, model wave: the bands to simulate (empty: up to 500 Hz)
  double wave_ppw = 10.0;
  double wave_length_s = 0.0;  // 0: as long as the ray models' IR
};

// The models of `s` (comma-separated), each one of `allowed`; all of them when --models was not `given`.
std::vector<std::string> splitModels(const std::string& s, bool given, const std::vector<std::string>& allowed,
                                     const std::string& mode) {
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  if (!given) return allowed;
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string m; std::getline(in, m, ',');) {
    if (std::find(allowed.begin(), allowed.end(), m) == allowed.end())
      throw core::InputError("--models", "unknown model \"" + m + "\" in " + mode + " mode (a comma-separated list of " + list + ")");
    if (std::find(out.begin(), out.end(), m) == out.end()) out.push_back(m);
  }
  if (out.empty()) throw core::InputError("--models", "give at least one of " + list);
  return out;
}

// Band level of `model` at listener l and band label, or NaN.
double bandLevel(const compare::SceneComparison& c, int l, const std::string& model, const std::string& band) {
  for (const auto& r : c.rows)
    if (r.band && r.listener == l && r.model == model && r.band_label == band) return r.level_db;
  return NAN;
}

// Which models the comparison holds rows of (what was asked for and could be computed).
struct Present {
  bool wbsdf = false, utd = false, exact = false, incoherent = false;
};

Present presentModels(const compare::SceneComparison& c) {
  Present p;
  for (const auto& r : c.rows) {
    p.wbsdf = p.wbsdf || r.model == "wbsdf";
    p.utd = p.utd || r.model == "utd";
    p.exact = p.exact || r.model == "exact";
    p.incoherent = p.incoherent || r.model == "exact-incoherent-floor";
  }
  return p;
}

void printTable(const room::Room& room, const compare::SceneComparison& c, bool exact_asked) {
  const Present p = presentModels(c);
  // On a door with a floor the WBSDF (an energy tracer) is compared with the incoherent-floor reference.
  const std::string ref_w = p.incoherent ? "exact-incoherent-floor" : "exact";
  const char* w_head = p.incoherent ? "wbsdf-exact-inc" : "wbsdf-exact";
  std::printf("%s", room.name.c_str());
  if (exact_asked) std::printf(": exact reference: %s", c.exact_available ? c.exact_note.c_str() : ("none: " + c.exact_note).c_str());
  std::printf("\n");
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const room::Listener& li = room.listeners[l];
    const int il = static_cast<int>(l);
    std::printf("\nlistener %s at (%.2f, %.2f, %.2f) m", li.name.c_str(), li.position_m.x(), li.position_m.y(), li.position_m.z());
    if (c.shadow_angle_deg[l])
      std::printf(", %+.1f deg past the shadow boundary", *c.shadow_angle_deg[l]);
    else if (room.occluders.size() == 1 && room.occluders[0].x.kind != room::OccluderAxis::Kind::Edge)
      std::printf(", on the source's side of %s: no shadow boundary", room.occluders[0].name.c_str());
    std::printf("\n%8s", "band Hz");
    if (p.wbsdf) std::printf(" %16s", "wbsdf dB");
    if (p.utd) std::printf(" %9s", "utd dB");
    if (p.exact) std::printf(" %9s", "exact dB");
    if (p.incoherent) std::printf(" %12s", "exact-inc dB");
    if (p.wbsdf && p.exact) std::printf(" %15s", w_head);
    if (p.utd && p.exact) std::printf(" %11s", "utd-exact");
    std::printf("\n");
    for (int b = 0; b < room.bands.size(); ++b) {
      const std::string band = room.bands.label(b);
      double se = NAN;
      for (const auto& r : c.rows)
        if (r.band && r.listener == il && r.model == "wbsdf" && r.band_label == band) se = r.std_error_db;
      const double w = bandLevel(c, il, "wbsdf", band), u = bandLevel(c, il, "utd", band);
      const double e = bandLevel(c, il, "exact", band), ew = bandLevel(c, il, ref_w, band);
      // A number, or n/a where a model gives none (the exact reference above its size limit).
      const auto num = [](int width, double v) {
        if (std::isnan(v)) std::printf(" %*s", width, "n/a");
        else std::printf(" %*.2f", width, v);
      };
      std::printf("%8s", band.c_str());
      if (p.wbsdf) {
        if (std::isfinite(w)) std::printf(" %9.2f ±%5.2f", w, se);
        else std::printf(" %16s", "no energy");  // no ray reached the listener in this band, or a negative sum
      }
      if (p.utd) num(9, u);
      if (p.exact) num(9, e);
      if (p.incoherent) num(12, ew);
      if (p.wbsdf && p.exact) num(15, std::isfinite(w) ? w - ew : NAN);
      if (p.utd && p.exact) num(11, u - e);
      std::printf("\n");
    }
  }
}

// The timing line: only the models that ran.
void printTimes(const compare::SceneComparison& c) {
  const Present p = presentModels(c);
  std::string line;
  char buf[96];
  if (p.wbsdf) {
    std::snprintf(buf, sizeof buf, "WBSDF %llu rays in %.2f s", static_cast<unsigned long long>(c.rays), c.wbsdf_seconds);
    line += buf;
  }
  if (p.utd) {
    std::snprintf(buf, sizeof buf, "%sUTD %.2f s", line.empty() ? "" : ", ", c.utd_seconds);
    line += buf;
  }
  if (p.exact) {
    std::snprintf(buf, sizeof buf, "%sexact %.2f s", line.empty() ? "" : ", ", c.exact_seconds);
    line += buf;
  }
  if (!line.empty()) std::printf("\n%s\n", line.c_str());
}

// A CSV cell: the number, or empty when it is missing (−inf level of a silent WBSDF band, its undefined error).
std::string cell(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream s;
  s << v;
  return s.str();
}

void writeCompareCsv(const std::string& path, const room::Room& room, const compare::SceneComparison& c) {
  core::writeFileAtomically(path, [&](std::ostream& out) {
    out << "listener,model,freq_hz,band,level_db_re_free_field,std_error_db,angle_past_shadow_boundary_deg,"
           "phase_deg_re_free_field\n";
    for (const auto& r : c.rows) {
      out << room.listeners[r.listener].name << ',' << r.model << ',' << r.freq_hz << ',' << (r.band ? r.band_label : "")
          << ',' << cell(r.level_db) << ',' << cell(r.std_error_db) << ',';
      if (c.shadow_angle_deg[r.listener]) out << *c.shadow_angle_deg[r.listener];
      out << ',' << cell(r.phase_deg) << '\n';
    }
  });
}

// Room mode (compare/room_compare.h): every ray model a whole room simulation; returns the exit code.
int runRoomMode(const CompareCliOptions& o, CommonOptions& common, bool seed_given, const room::Room& room,
                const std::vector<std::string>& warnings) {
  if (o.aim) throw core::InputError("--aim", "applies to free-field scenes only, not in room mode");
  if (!o.freqs.empty()) throw core::InputError("--freq", "applies to free-field scenes only, not in room mode (its models give bands)");
  std::vector<std::string> models =
      splitModels(o.models, o.models_given, {"none", "utd", "wbsdf", "exact", "wave"}, "room");
  if (!o.models_given) models.pop_back();  // the wave reference (minutes) only when asked for
  compare::RoomCompareOptions ro;
  ro.free_field = std::find(models.begin(), models.end(), "exact") != models.end();
  const bool wave = std::find(models.begin(), models.end(), "wave") != models.end();
  models.erase(std::remove(models.begin(), models.end(), "exact"), models.end());
  models.erase(std::remove(models.begin(), models.end(), "wave"), models.end());
  ro.models = models;
  ro.rays = o.rays;
  ro.seed = seed_given ? common.seed : room.output.seed;
  reference::WaveOptions wo;
  wo.bands_hz = o.wave_bands;
  wo.ppw = o.wave_ppw;
  wo.length_s = o.wave_length_s;
  // The wave reference's own checks (bands, memory) before any model runs: one line, no work done.
  if (wave) reference::planWave(room, wo);
  for (const auto& w : warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
  const std::uint64_t rays = (o.rays ? o.rays : room.output.rays) * room.sources.size() * models.size();
  core::Progress progress("compare " + room.name, rays);
  ro.on_progress = [&progress](std::uint64_t n) { progress.add(n); };
  std::unique_ptr<core::Progress> wave_progress;
  if (wave)
    // Run after the ray models, on the room with their IR length (compareRoom): its plan is stated then.
    ro.wave = [wo, &progress, &wave_progress](const room::Room& timed) mutable {
      progress.finish();
      const reference::WavePlan plan = reference::planWave(timed, wo);
      printWavePlan(timed, plan);
      wave_progress = std::make_unique<core::Progress>("compare " + timed.name + " wave", plan.total_steps);
      wo.on_progress = [p = wave_progress.get()](std::uint64_t n) { p->add(n); };
      return compare::waveHistograms(timed, reference::simulateWave(timed, wo));
    };
  const compare::RoomComparison c = compare::compareRoom(room, ro);
  progress.finish();
  if (wave_progress) wave_progress->finish();
  for (const auto& w : c.warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
  OutputFiles written;  // replaced together: a later failure leaves the previous files
  if (!o.plot.empty()) written.write(o.plot, [&](const std::string& f) { writeRoomComparePlot(f, room, c); });
  if (!o.csv.empty()) written.write(o.csv, [&](const std::string& f) { writeRoomCompareCsv(f, room, c); });
  commitAndAnnounce(written);
  if (common.json) {
    std::cout << roomComparisonJsonLines(room, c);
    std::cout.flush();
  } else {
    printRoomComparison(room, c);
  }
  return 0;
}

}  // namespace

Runner addCompareCommand(CLI::App& app, CommonOptions& common) {
  auto o = std::make_shared<CompareCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "compare",
      "Compare diffraction models at each listener. Free-field mode (one edge, barrier, door or slit in the "
      "open): level re free field from the WBSDF ray tracer, UTD edge diffraction and the exact reference "
      "(Macdonald's half-plane for one edge/barrier, Rayleigh-Sommerfeld for one door/slit), per band and on a "
      "fine frequency grid, with dB errors against the exact reference. Room mode (chosen when the scene's mesh "
      "is closed and holds its first source, or by --mode room): whole room simulations (as `diffray ir`) with "
      "diffraction none, utd and wbsdf, same rays and seed, per listener and octave band: G (strength, dB re "
      "the free-field energy of the same source at 10 m, ISO 3382-1), early (the energy in the 20 ms from the "
      "direct-sound time, same reference, the window opened R/c + 1/(band width) sooner for the spread of the "
      "listener sphere and of the wave reference's band filter), EDT, T30, C50, C80. The free-field aperture "
      "reference (exact) is shown only for listeners beyond the door's plane from the source (the direct sound through the door, "
      "read beside the early energy); for the others the table says why. --models ...,wave adds the FDTD "
      "wave reference (as `diffray wave`, as long as the ray models' IR) and each ray model's difference from "
      "it (dB; % for EDT and T30).");
  sub->add_option("scene", o->scene, "scene file (rooms/README.md; occluders under \"occluders\")")
      ->check(inputPathValidator())
      ->required();
  sub->add_option("--mode", o->mode,
                  "auto: room mode when the scene's mesh is closed and holds its first source, else free-field; "
                  "room; free-field")
      ->check(CLI::IsMember({"auto", "room", "free-field"}))
      ->capture_default_str();
  CLI::Option* models_option = sub->add_option("--models", o->models,
                  "comma-separated; free-field mode: wbsdf, utd, exact (default all); room mode: none, utd, wbsdf, "
                  "exact, wave (default all but wave; exact = the free-field aperture reference where it applies; "
                  "wave = the FDTD wave reference of `diffray wave`, minutes, and every ray model's difference "
                  "from it)");
  addRaysOption(sub, o->rays, "rays (free-field: WBSDF rays, default 1e6; room: per model and source, default the "
                              "room file's output.rays)");
  CLI::Option* seed_option =
      sub->add_option("--seed", common.seed, "random seed (room mode: default the room file's output.seed)")
          ->transform(seedValidator());
  addThreadsOption(sub, common.threads);
  sub->add_option("--csv", o->csv, "write every figure (listener, model, band or frequency) to this CSV file")
      ->check(outputPathValidator());
  sub->add_option("--plot", o->plot,
                  "PNG (gnuplot); free-field: level against frequency and against angle past the shadow boundary; "
                  "room: G and early energy per band, per model, one panel per listener")
      ->check(outputPathValidator());
  sub->add_option("--freq", o->freqs, "free-field mode: the frequencies (Hz, comma-separated) for UTD and exact "
                                      "instead of the fine grid, each with level and phase re the free field")
      ->delimiter(',');
  sub->add_option("--fine-per-octave", o->fine, "free-field mode: fine-grid frequencies per octave for UTD and exact")
      ->transform(wholeNumberValidator(1, 400))
      ->capture_default_str();
  sub->add_option("--wave-bands", o->wave_bands,
                  "room mode, model wave: octave band centres the FDTD reference simulates (default: every room "
                  "band up to 500 Hz)")
      ->delimiter(',');
  sub->add_option("--wave-ppw", o->wave_ppw, "room mode, model wave: grid points per wavelength at each band's upper edge")
      ->check(CLI::Range(4.0, 100.0))
      ->capture_default_str();
  sub->add_option("--wave-length", o->wave_length_s,
                  "room mode, model wave: simulated length in s (default: as long as the ray models' IR; a decay "
                  "slower than theirs needs more for its T30)")
      ->check(CLI::Range(1e-3, 120.0));
  sub->add_flag("--aim", o->aim,
                "free-field mode: aim every WBSDF ray at the scene's single occluder (valid only when every path to "
                "the listeners crosses it: an edge or a door in free field, an edge or barrier on a specular ground, "
                "half the rays then aimed through the ground)");
  sub->add_flag("--json", common.json, "print one JSON object per listener, model and band or frequency (JSON lines)");
  return [o, &common, seed_option, models_option]() {
    core::ThreadLimit limit(common.threads);
    o->models_given = models_option->count() > 0;
    std::vector<std::string> warnings;
    const room::Room room = room::loadRoom(o->scene, &warnings);
    checkOutputFiles({o->csv, o->plot}, room.input_files);
    checkPlotOption("--plot", o->plot);
    if (o->mode == "room" || (o->mode == "auto" && compare::isEnclosedRoom(room)))
      return runRoomMode(*o, common, seed_option->count() > 0, room, warnings);
    compare::checkListeners(room);  // before the loader's warnings: a refused listener gives one line
    // Comparison scenes are usually open (a barrier on the ground, a wall in free field): the room checks'
    // warnings about an open mesh and listeners "outside the room" do not apply to them. A listener hidden
    // behind a surface (below the ground) is warned about by compareScene instead (compare/scene_checks.h).
    for (const auto& w : warnings)
      if (w.find("is not closed") == std::string::npos && w.find("is outside the room") == std::string::npos)
        std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
    compare::CompareOptions co;
    co.models = splitModels(o->models, o->models_given, {"wbsdf", "utd", "exact"}, "free-field");
    co.rays = o->rays ? o->rays : 1'000'000;
    co.seed = common.seed;
    co.fine_per_octave = o->fine;
    for (double f : o->freqs) {
      core::requireFinite("--freq", f);
      if (!(f > 0.0 && f <= 100000.0))
        throw core::InputError("--freq", "each frequency must lie in (0, 100000] Hz, got " + room::formatNumber(f));
    }
    co.freqs_hz = o->freqs;
    co.aim = o->aim;
    core::Progress progress("compare " + room.name, co.rays);
    co.on_progress = [&progress](std::uint64_t n) { progress.add(n); };
    co.model_progress = [&progress, &room](const std::string& model) {
      progress.finish();  // the rays are traced first: close their bar before a model's
      return core::progressOfUnknownSize("compare " + room.name + " " + model);
    };
    const compare::SceneComparison c = compare::compareScene(room, co);
    progress.finish();
    for (const auto& w : c.warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
    OutputFiles written;  // replaced together: a later failure leaves the previous files
    if (!o->plot.empty()) written.write(o->plot, [&](const std::string& f) { writeComparePlot(f, room, c); });
    if (!o->csv.empty()) written.write(o->csv, [&](const std::string& f) { writeCompareCsv(f, room, c); });
    commitAndAnnounce(written);
    if (common.json) {
      for (const auto& r : c.rows) {
        nlohmann::ordered_json j{{"listener", room.listeners[r.listener].name},
                                 {"model", r.model},
                                 {"freq_hz", r.freq_hz},
                                 {"band", r.band},
                                 {"level_db_re_free_field", std::isfinite(r.level_db) ? nlohmann::ordered_json(r.level_db) : nlohmann::ordered_json()}};
        if (r.band) j["band_hz"] = r.band_label;
        if (r.model == "wbsdf") j["std_error_db"] = std::isfinite(r.std_error_db) ? nlohmann::ordered_json(r.std_error_db) : nlohmann::ordered_json();
        if (c.shadow_angle_deg[r.listener]) j["angle_past_shadow_boundary_deg"] = *c.shadow_angle_deg[r.listener];
        if (!r.band && r.model != "wbsdf")
          j["phase_deg_re_free_field"] = std::isfinite(r.phase_deg) ? nlohmann::ordered_json(r.phase_deg) : nlohmann::ordered_json();
        std::cout << jsonText(j) << '\n';
      }
      std::cout.flush();
    } else {
      printTable(room, c, std::find(co.models.begin(), co.models.end(), "exact") != co.models.end());
      printTimes(c);
    }
    return 0;
  };
}

}  // namespace diffray::cli
