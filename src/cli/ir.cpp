// `diffray ir ROOM.json`: a room in, an impulse response and its metrics out.
// Writes OUT.wav (32-bit float, one channel per listener, physical units: Σp² over a span is the energy in
// J/m², so the direct sound of a 1 W source at 1 m has amplitude 1), OUT.json (the sidecar: metrics per
// listener from the energy histograms and from the WAV, rays, seed, version, timing, warnings) and OUT.csv
// (the band × time energy histograms), each atomically. Prints a metrics table (or the sidecar with --json).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include <tbb/parallel_for.h>

#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/cli/plot.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/ir/spatial_metrics.h"
#include "diffray/ir/spatial_synthesis.h"
#include "diffray/spatial/hrtf.h"
#include "diffray/ir/direction.h"
#include "diffray/ir/metrics.h"
#include "diffray/ir/strength.h"
#include "diffray/ir/synthesis.h"
#include "diffray/ir/uncertainty.h"
#include "diffray/room/checks.h"
#include "diffray/room/json_fields.h"
#include "diffray/room/reverberation.h"
#include "diffray/room/scene_file.h"
#include "diffray/transport/room_simulation.h"

namespace diffray::cli {

namespace {

struct IrOptions {
  std::string room_file;
  std::string out;
  std::uint64_t rays = 0;
  int ism_order = -2;
  double length_s = 0;
  std::string plot;
  std::string diffraction = "none";
  int diffraction_order = 1;
  bool portal = true;
  std::string format = "omni";
  int order = 1;
  std::string hrtf;
  std::string plot_directions;
};

// The spatial IR file of one listener: OUT's stem, the listener's name (characters other than letters,
// digits, '.', '-' and '_' become '_') and ".FORMAT.wav".
std::string spatialFile(const std::string& wav, const std::string& listener, const std::string& format) {
  std::string name = listener;
  for (char& ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == '_')) ch = '_';
  return withExtension(wav, "." + name + "." + format + ".wav");
}

// Σ negative / Σ |energy| over a listener's traced bins: how signed the WBSDF result is (negative energy is
// physical only after integration over a finite aperture, Cuypers et al. 2012, section 2.4: report it rather than clamp
// it silently; the synthesis reads negative bins as silence).
double negativeFraction(const std::vector<std::vector<double>>& traced) {
  double neg = 0.0, all = 0.0;
  for (const auto& band : traced)
    for (double e : band) {
      all += std::abs(e);
      if (e < 0.0) neg -= e;
    }
  return all > 0.0 ? neg / all : 0.0;
}

void writeHistogramCsv(const std::string& path, const room::Room& room, const transport::RoomSimulation& sim) {
  core::writeFileAtomically(path, [&](std::ostream& out) {
    out << "listener,time_s";
    for (int b = 0; b < room.bands.size(); ++b) out << ",e_" << room.bands.label(b) << "hz";
    out << '\n' << std::setprecision(9);
    for (std::size_t l = 0; l < sim.listeners.size(); ++l) {
      const auto& r = sim.listeners[l];
      std::vector<std::vector<double>> total;
      for (int b = 0; b < room.bands.size(); ++b) total.push_back(r.total(b));
      for (int k = 0; k < r.bins(); ++k) {
        out << room.listeners[l].name << ',' << k * r.bin_s;
        for (int b = 0; b < room.bands.size(); ++b) out << ',' << total[b][k];
        out << '\n';
      }
    }
  });
}

/// The room's Sabine and Eyring T beside the traced T30 (mean over the listeners that have one), per band,
/// as a table, and the bands where the traced T30 and Eyring's differ by more than a factor 1.5 as notes: a
/// field far from diffuse (absorption on a few surfaces, little scattering, coupled volumes) decays unlike
/// the statistical formulas, and the user should know which case the room is before trusting either.
struct Statistics {
  std::string table;
  std::vector<std::string> notes;
  nlohmann::ordered_json json;
};
Statistics statisticsAgainstTraced(const room::Room& room, const std::vector<std::vector<double>>& traced_t30) {
  const room::StatisticalReverberation st = room::statisticalReverberation(room);
  Statistics out;
  out.json = {{"volume_m3", st.volume_m3}, {"surface_m2", st.surface_m2}, {"bands", nlohmann::ordered_json::object()}};
  if (!(st.volume_m3 > 0)) return out;
  char line[160];
  std::snprintf(line, sizeof line, "room (statistical, diffuse field): V = %.1f m3, S = %.1f m2\n", st.volume_m3,
                st.surface_m2);
  out.table = line;
  out.table += "band Hz  mean alpha  Sabine T s  Eyring T s  traced T30 s  traced/Eyring\n";
  for (int b = 0; b < room.bands.size(); ++b) {
    double sum = 0;
    int n = 0;
    for (const auto& l : traced_t30)
      if (std::isfinite(l[static_cast<std::size_t>(b)])) sum += l[static_cast<std::size_t>(b)], ++n;
    const double traced = n ? sum / n : std::nan("");
    const double eyring = st.eyring_s[static_cast<std::size_t>(b)], ratio = traced / eyring;
    std::snprintf(line, sizeof line, "%7s  %10.3f  %10.3f  %10.3f", room.bands.label(b).c_str(),
                  st.mean_alpha[static_cast<std::size_t>(b)], st.sabine_s[static_cast<std::size_t>(b)], eyring);
    out.table += line;
    if (std::isfinite(traced))  // no listener with a T30 in this band (negative or too short a decay): '-'
      std::snprintf(line, sizeof line, "  %12.3f  %13.2f\n", traced, ratio);
    else
      std::snprintf(line, sizeof line, "  %12s  %13s\n", "-", "-");
    out.table += line;
    const auto finite = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); };
    out.json["bands"][room.bands.label(b)] = {
        {"mean_alpha", finite(st.mean_alpha[static_cast<std::size_t>(b)])},
        {"sabine_s", finite(st.sabine_s[static_cast<std::size_t>(b)])},
        {"eyring_s", finite(eyring)},
        {"traced_t30_s", finite(traced)}};
    if (std::isfinite(ratio) && (ratio > 1.5 || ratio < 1 / 1.5)) {
      std::snprintf(line, sizeof line, "%s Hz %.1fx", room.bands.label(b).c_str(), ratio);
      out.notes.push_back(line);
    }
  }
  return out;
}

}  // namespace

Runner addIrCommand(CLI::App& app, CommonOptions& common) {
  auto opts = std::make_shared<IrOptions>();
  CLI::App* sub = app.add_subcommand(
      "ir", "Trace a room (rooms/*.json) to an impulse response (WAV + JSON sidecar + CSV histograms) and print "
            "its ISO 3382 metrics.");
  sub->add_option("room", opts->room_file, "scene file (see rooms/README.md)")->check(inputPathValidator())->required();
  sub->add_option("-o,--output", opts->out, "output WAV; its sidecar and histograms take its name with .json and .csv (default: ROOM.ir.wav, here, ROOM the room file's name; a sidecar that would replace an input, as -o ROOM.wav beside ROOM.json, is named OUT.ir.json and OUT.ir.csv)")
      ->check(outputPathValidator());
  addRaysOption(sub, opts->rays, "rays per source (default: the room file's output.rays; 1e6 is accepted)");
  CLI::Option* seed_option =
      sub->add_option("--seed", common.seed, "random seed (default: the room file's output.seed); the same seed "
                                             "gives the same IR")
          ->transform(seedValidator());
  addThreadsOption(sub, common.threads);
  sub->add_option("--ism-order", opts->ism_order, "image-source order (default: the room file's; -1 = rays only)")
      ->transform(wholeNumberValidator(-1, 50));
  sub->add_option("--length", opts->length_s, "IR length in s (default: the room file's, or until -60 dB)")
      ->check(CLI::Range(1e-3, 120.0))
      ->check(CLI::Validator(
          [](std::string& text) {  // CLI::Range lets NaN through (every comparison with it is false)
            double v = 0.0;
            return CLI::detail::lexical_cast(text, v) && std::isfinite(v) ? std::string() : "must be a number";
          },
          "", "finite"));
  sub->add_flag("--json", common.json, "print the JSON sidecar to stdout instead of the table");
  sub->footer(
      "Every figure gets a standard error: the rays are traced in 16 independent batches and each metric is "
      "jackknifed over them (the sidecar's \"se\" per band; the WAV's figures get the histogram's). A figure "
      "whose standard error exceeds its ISO 3382-1 JND (5 % for T and EDT, 1 dB for C, 0.05 for D50, 10 ms for "
      "Ts) is marked '?' and its band \"noisy\"; a band whose (WBSDF-signed) energy sums negative, or whose "
      "decay curve falls to zero, is \"negative_energy\" ('!', no figure). Each marked band is also a warning "
      "(stderr and the sidecar) and is labelled in --plot.");
  sub->add_option("--plot", opts->plot, "draw each listener's energy decay curves per band into this PNG (gnuplot)")
      ->check(outputPathValidator());
  sub->add_option("--plot-directions", opts->plot_directions,
                  "draw where each listener's sound comes from over its first 200 ms into this PNG (gnuplot)")
      ->check(outputPathValidator());
  addDiffractionOptions(sub, opts->diffraction, opts->diffraction_order);
  addContinuationOption(sub, opts->portal);
  sub->add_option("--format", opts->format,
                  "omni (default): one channel per listener; ambix: also one AmbiX file per listener, "
                  "OUT.LISTENER.ambix.wav ((order+1)^2 channels, ACN order, SN3D; W is the omni channel); "
                  "binaural: also one two-channel file per listener, OUT.LISTENER.binaural.wav (left, right)")
      ->check(CLI::IsMember({"omni", "ambix", "binaural"}));
  sub->add_option("--order", opts->order, "Ambisonic order of --format ambix: 1, 2 or 3 (default 1)")
      ->transform(wholeNumberValidator(1, 3));
  addHrtfOption(sub, opts->hrtf, "--format binaural");

  return [opts, &common, seed_option]() {
    const auto t_start = std::chrono::steady_clock::now();
    core::ThreadLimit limit(common.threads);
    std::vector<std::string> warnings;
    const room::Room room = room::loadRoom(opts->room_file, &warnings);
    // A scene in the open (an object on a ground, a barrier): no source inside an enclosure. ir simulates rooms;
    // say which command suits it, beside the warnings that say what is wrong.
    if (std::none_of(room.sources.begin(), room.sources.end(),
                     [&](const room::Source& s) { return room::insideRoom(room, s.position_m); }))
      warnings.push_back("no source is inside an enclosed room: ir simulates rooms (reverberation, metrics); for a "
                         "scene in the open, such as an object or a barrier on a ground, use diffray compare");
    if (seed_option->count() == 0) common.seed = room.output.seed;  // the file's seed unless --seed is given
    // The default names carry ".ir" so that they never take the scene's own name (`cd rooms && diffray ir
    // shoebox.json` writes shoebox.ir.wav, .ir.json, .ir.csv beside shoebox.json). With -o OUT.wav the sidecar
    // and histograms are OUT.json and OUT.csv, unless one of those is a file the room was read from (-o
    // classroom.wav beside classroom.json): then both take OUT.ir.json and OUT.ir.csv, and a note says so.
    const std::string wav = opts->out.empty()
                                ? std::filesystem::path(opts->room_file).stem().string() + ".ir.wav"
                                : opts->out;
    checkOutputFile(wav, ".wav");
    std::string side_json = withExtension(wav, ".json"), side_csv = withExtension(wav, ".csv");
    if (isAnyOf(side_json, room.input_files) || isAnyOf(side_csv, room.input_files)) {
      side_json = withExtension(wav, ".ir.json");
      side_csv = withExtension(wav, ".ir.csv");
      std::cerr << "diffray: note: " << withExtension(wav, ".json") << " is an input of this room, so the sidecar is "
                << side_json << " and the histograms " << side_csv << "\n";
    }
    // No output may replace a file the room was read from (-o materials.wav: the material library).
    const bool ambix = opts->format == "ambix", binaural = opts->format == "binaural";
    if (!opts->hrtf.empty() && !binaural) throw core::InputError("--hrtf", "is for --format binaural");
    std::vector<std::string> spatial_files;
    if (ambix || binaural)
      for (const room::Listener& li : room.listeners) spatial_files.push_back(spatialFile(wav, li.name, opts->format));
    std::vector<std::string> outputs{wav, side_json, side_csv, opts->plot, opts->plot_directions};
    outputs.insert(outputs.end(), spatial_files.begin(), spatial_files.end());
    checkOutputFiles(outputs, room.input_files);
    // The HRTF set before any work: a bad file is one line and nothing written.
    std::optional<spatial::Hrtf> hrtf;
    if (binaural) {
      hrtf = spatial::Hrtf::load(opts->hrtf, room.output.sample_rate_hz);
      std::cerr << "diffray: info: HRTF " << describeHrtf(*hrtf) << "\n";
    }
    checkPlotOption("--plot", opts->plot);
    checkPlotOption("--plot-directions", opts->plot_directions);
    room::checkSynthesis(room, opts->length_s, room.output.sample_rate_hz,
                   (room.file.empty() ? std::string("room") : room.file) + ": output.sample_rate_hz");

    transport::RoomSimulationOptions so;
    so.rays = opts->rays;
    so.seed = common.seed;
    so.ism_order = opts->ism_order;
    so.length_s = opts->length_s;
    so.diffraction = opts->diffraction;
    so.max_diffractions = opts->diffraction_order;
    so.portal = opts->portal;
    so.directions = true;
    const std::uint64_t rays = opts->rays ? opts->rays : room.output.rays;
    core::Progress progress("ir " + room.name, rays * room.sources.size());
    so.on_progress = [&progress](std::uint64_t n) { progress.add(n); };
    so.on_start = [&warnings] {
      for (const auto& w : warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
    };
    const transport::RoomSimulation sim = transport::simulateRoom(room, so);
    progress.finish();
    for (const auto& w : sim.warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";

    // Synthesis and metrics, per listener.
    const auto t_synth = std::chrono::steady_clock::now();
    audio::AudioBuffer buffer;
    buffer.sample_rate_hz = room.output.sample_rate_hz;
    buffer.channels = static_cast<int>(room.listeners.size());
    nlohmann::ordered_json listeners = nlohmann::ordered_json::array();
    std::string table;
    std::vector<std::string> metric_warnings;  // noisy or negative bands, one per listener and band
    std::vector<std::vector<std::string>> plot_flags;  // [listener][band]: the histogram's flags
    std::vector<std::vector<double>> traced_t30;       // [listener][band], from the histograms
    double total_power_w = 0.0;
    for (const room::Source& s : room.sources) total_power_w += s.power_w;
    // Each listener's IRs (omni, and the spatial one), its WAV's metrics and its spatial figures, the listeners
    // in parallel: each from its own seed, so the same samples and figures as one after the other.
    const std::size_t listener_count = room.listeners.size();
    std::vector<std::vector<double>> channels(listener_count);
    std::vector<std::vector<std::vector<double>>> spatial_irs(ambix || binaural ? listener_count : 0);  // [listener][channel]: AmbiX (ACN) or left, right
    std::vector<std::vector<ir::BandMetrics>> wav_metrics(listener_count);
    std::vector<std::vector<ir::SpatialBandMetrics>> spatial_metrics(listener_count);
    tbb::parallel_for(std::size_t{0}, listener_count, [&](std::size_t l) {
      const auto& resp = sim.listeners[l];
      const room::Listener& li = room.listeners[l];
      if (ambix) {  // its W channel is the omni channel
        spatial_irs[l] = ir::synthesizeAmbisonic(resp, room.output.sample_rate_hz, sim.length_s, room.volume(),
                                                 sim.speed_of_sound_m_s, ir::listenerSeed(common.seed, l), opts->order,
                                                 li.forward, li.left, li.up);
        channels[l] = spatial_irs[l][0];
      } else if (binaural) {  // the omni channel comes with it
        spatial_irs[l] = ir::synthesizeBinaural(resp, room.output.sample_rate_hz, sim.length_s, room.volume(),
                                                sim.speed_of_sound_m_s, ir::listenerSeed(common.seed, l), *hrtf,
                                                li.forward, li.left, li.up, ir::Phasing::Orthogonal, &channels[l]);
      } else {
        channels[l] = ir::synthesize(resp, room.output.sample_rate_hz, sim.length_s, room.volume(),
                                     sim.speed_of_sound_m_s, ir::listenerSeed(common.seed, l));
      }
      wav_metrics[l] = ir::metricsFromSignal(channels[l], room.output.sample_rate_hz, room.bands);
      // ISO 3382-1 A.3 figures of the spatial IR: J_LF, J_LFC and L_J (re the sources' free field at 10 m)
      // from W and Y; IACC_E and IACC_L from the ears.
      if (!spatial_irs.empty()) {
        const auto& s = spatial_irs[l];
        spatial_metrics[l] = ambix ? ir::lateralFractions(s[0], s[1], room.output.sample_rate_hz, room.bands, total_power_w / 100.0)
                                   : ir::interauralCrossCorrelation(s[0], s[1], room.output.sample_rate_hz, room.bands);
      }
    });
    for (std::size_t l = 0; l < listener_count; ++l) {
      const auto& resp = sim.listeners[l];
      const room::Listener& li = room.listeners[l];
      std::vector<std::vector<double>> totals;
      for (int b = 0; b < room.bands.size(); ++b) totals.push_back(resp.total(b));
      auto from_hist = ir::metricsFromHistograms(totals, resp.bin_s);
      std::vector<ir::BandMetrics>& from_wav = wav_metrics[l];
      // Standard errors (jackknife over the ray batches) and marks; the WAV's figures get the histogram's
      // standard errors, and a band whose energy sums negative no figure from either.
      traced_t30.emplace_back();
      for (const auto& m : from_hist) traced_t30.back().push_back(m.t30);
      const auto jack = ir::jackknifeMetrics(resp);
      const auto marks_hist = ir::markMetrics(from_hist, jack);
      const auto marks_wav = ir::markMetrics(from_wav, jack, &marks_hist);
      for (const std::string& w : ir::uncertaintyWarnings(li.name, room.bands, from_hist, marks_hist)) {
        std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";
        metric_warnings.push_back(w);
      }
      plot_flags.emplace_back();
      for (const auto& m : marks_hist) plot_flags.back().push_back(m.flagName());
      nlohmann::ordered_json band_json = ir::metricsJson(room.bands, from_hist);
      nlohmann::ordered_json wav_json = ir::metricsJson(room.bands, from_wav);
      ir::addUncertaintyJson(band_json, room.bands, marks_hist);
      ir::addUncertaintyJson(wav_json, room.bands, marks_wav);
      // Strength G (ISO 3382-1 A.2.1) re the sources' total power at 10 m, from the whole band energy.
      const std::vector<ir::Strength> g = ir::strengthPerBand(resp, total_power_w);
      ir::addStrengthJson(band_json, room.bands, g);
      std::string g_line = "  G dB (strength, re the free field at 10 m):";
      for (int b = 0; b < room.bands.size(); ++b) {
        const ir::Strength& gb = g[static_cast<std::size_t>(b)];
        char cell[48];
        if (std::isfinite(gb.g_db)) std::snprintf(cell, sizeof cell, " %s %.1f", room.bands.label(b).c_str(), gb.g_db);
        else std::snprintf(cell, sizeof cell, " %s -", room.bands.label(b).c_str());
        g_line += cell;
      }
      // Where the first 10 ms come from (ir/direction.h), in the listener's frame.
      nlohmann::ordered_json early = nlohmann::ordered_json::object();
      std::string dir_line = "  from (first 10 ms; azimuth left of forward / elevation, deg; r_E):";
      for (int b = 0; b < room.bands.size(); ++b) {
        const ir::EarlyDirection d = ir::earlyDirection(resp, b, li.forward, li.left, li.up);
        const auto num = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); };
        early[room.bands.label(b)] = {{"azimuth_deg", num(d.azimuth_deg)}, {"elevation_deg", num(d.elevation_deg)},
                                      {"r_e", num(d.r_e)}};
        char cell[64];
        if (std::isfinite(d.r_e))
          std::snprintf(cell, sizeof cell, " %s %+.0f/%+.0f %.2f", room.bands.label(b).c_str(), d.azimuth_deg,
                        d.elevation_deg, d.r_e);
        else std::snprintf(cell, sizeof cell, " %s -", room.bands.label(b).c_str());
        dir_line += cell;
      }
      nlohmann::ordered_json spatial_json;
      std::string spatial_table;
      if (!spatial_irs.empty()) {
        const auto& m = spatial_metrics[l];
        spatial_json = ir::spatialJson(room.bands, m, ambix);
        spatial_table = "listener " + li.name + " (" + opts->format + ", ISO 3382-1 A.3):\n" +
                        ir::spatialTable(room.bands, m, ambix);
      }
      const auto vec = [](const core::Vec3& v) { return nlohmann::ordered_json{v.x(), v.y(), v.z()}; };
      listeners.push_back({{"name", li.name},
                           {"position_m", {li.position_m.x(), li.position_m.y(), li.position_m.z()}},
                           {"radius_m", li.radius_m},
                           {"orientation", {{"forward", vec(li.forward)}, {"left", vec(li.left)}, {"up", vec(li.up)}}},
                           {"early_direction", {{"window_ms", 10}, {"bands", early}}},
                           {"spatial_wav", spatial_files.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(spatial_files[l])},
                           {"spatial", spatial_json},
                           {"image_sources", resp.arrivals.size()},
                           {"negative_energy_fraction", negativeFraction(resp.traced)},
                           {"batches", resp.batches.size()},
                           {"bands", band_json},
                           {"bands_from_wav", wav_json}});
      table += "listener " + li.name + " (from the energy histogram):\n" +
               ir::metricsTable(room.bands, from_hist, &marks_hist) + g_line + "\n" + dir_line + "\n";
      table += "listener " + li.name + " (from the synthesized WAV; standard errors and flags from the histogram):\n" +
               ir::metricsTable(room.bands, from_wav, &marks_wav) + spatial_table;
    }
    Statistics stats = statisticsAgainstTraced(room, traced_t30);
    table += stats.table;
    if (!stats.notes.empty()) {
      std::string bands_text;
      for (const std::string& n : stats.notes) bands_text += (bands_text.empty() ? "" : ", ") + n;
      const std::string note = "the traced T30 differs from Eyring's by more than a factor 1.5 (" + bands_text +
                               "): the field is not diffuse (absorption on a few surfaces, little scattering, or "
                               "coupled volumes); if the real room has furniture or people, model them or raise "
                               "the surfaces' scattering (rooms/README.md)";
      std::cerr << "diffray: note: " << core::oneLine(note) << "\n";
      stats.json["note"] = note;
    }
    const long frames = channels.empty() ? 0 : static_cast<long>(channels[0].size());
    buffer.samples.assign(static_cast<std::size_t>(frames) * buffer.channels, 0.0);
    for (int c = 0; c < buffer.channels; ++c)
      for (long f = 0; f < frames; ++f) buffer.samples[f * buffer.channels + c] = channels[c][f];
    const double synth_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_synth).count();

    nlohmann::ordered_json bands = nlohmann::ordered_json::array();
    for (int b = 0; b < room.bands.size(); ++b) bands.push_back(room.bands.nominalHz(b));
    std::vector<std::string> all_warnings = warnings;
    all_warnings.insert(all_warnings.end(), sim.warnings.begin(), sim.warnings.end());
    all_warnings.insert(all_warnings.end(), metric_warnings.begin(), metric_warnings.end());
    // ordered_json: band keys (and the sidecar's own) stay in the order written, not sorted as strings.
    nlohmann::ordered_json side{
        {"diffray_version", DIFFRAY_VERSION},
        {"room", room.name},
        {"room_file", opts->room_file},
        {"wav", wav},
        {"format", opts->format},
        {"ambisonic_order", ambix ? nlohmann::ordered_json(opts->order) : nlohmann::ordered_json()},
        {"hrtf", hrtf ? nlohmann::ordered_json(hrtf->path()) : nlohmann::ordered_json()},
        {"sample_rate_hz", room.output.sample_rate_hz},
        {"length_s", sim.length_s},
        {"frames", frames},
        {"channels", listeners.size()},
        {"band_centres_hz", bands},
        {"seed", common.seed},
        {"rays_per_source", rays},
        {"rays", sim.rays},
        {"threads", core::ThreadLimit::current()},
        {"ism_order", sim.ism_order},
        {"diffraction", opts->diffraction},
        {"diffraction_order", opts->diffraction_order},
        {"wbsdf_continuation", opts->portal ? "portal" : "wigner"},
        {"occluders", room.occluders.size()},
        {"image_sources", sim.image_sources},
        {"speed_of_sound_m_s", sim.speed_of_sound_m_s},
        {"volume_m3", room.volume()},
        {"surface_m2", room.surfaceArea()},
        {"eyring_t60_s_longest_band", sim.eyring_t60_s},
        {"stats",
         {{"segments", sim.segments},
          {"escaped", sim.escaped},
          {"roulette_killed", sim.roulette_killed},
          {"timed_out", sim.timed_out},
          {"occluder_events", sim.occluder_events},
          {"evanescent", sim.evanescent},
          {"utd_diffraction_paths", sim.diffraction_paths},
          {"queries_per_ray", sim.rays ? static_cast<double>(sim.segments) / static_cast<double>(sim.rays) : 0.0}}},
        {"timing_s", {{"trace", sim.trace_seconds}, {"image_sources", sim.ism_seconds}, {"synthesis_and_metrics", synth_s}}},
        {"warnings", all_warnings},
        {"statistical_reverberation", stats.json},
        {"listeners", listeners},
        {"bands", listeners.at(0).at("bands")}};

    // Outputs: each written whole or not at all, and replaced together (OutputFiles): if a later one fails,
    // none of this run's is left and a previous run's stay. The plot first, the likelier to fail.
    OutputFiles written;
    if (!opts->plot.empty()) {
      std::vector<std::string> names;
      for (const auto& li : room.listeners) names.push_back(li.name);
      written.write(opts->plot, [&](const std::string& f) { writeDecayPlot(f, names, sim.listeners, plot_flags); });
    }
    if (!opts->plot_directions.empty()) {
      std::vector<std::string> names;
      for (const auto& li : room.listeners) names.push_back(li.name);
      written.write(opts->plot_directions,
                    [&](const std::string& f) { writeDirectionPlot(f, names, sim.listeners, room.listeners); });
    }
    written.write(wav, [&](const std::string& f) { audio::writeWavFloat(f, buffer); });
    written.writeEach(spatial_files, [&](std::size_t l, const std::string& f) {
      audio::writeWavFloat(f, spatial_irs[l], room.output.sample_rate_hz);
    });
    written.write(side_csv, [&](const std::string& f) { writeHistogramCsv(f, room, sim); });
    side["timing_s"]["total"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    written.write(side_json, [&](const std::string& f) {
      core::writeFileAtomically(f, [&](std::ostream& out) { out << jsonText(side, 2) << '\n'; });
    });
    commitAndAnnounce(written);
    if (common.json) {
      std::cout << jsonText(side, 2) << std::endl;
    } else {
      std::printf("%s: %llu rays, %zu image sources, %.2f s IR, traced in %.2f s -> %s, %s, %s\n",
                  room.name.c_str(), static_cast<unsigned long long>(sim.rays), sim.image_sources, sim.length_s,
                  sim.trace_seconds, wav.c_str(), side_json.c_str(), side_csv.c_str());
      std::cout << table;
    }
    return 0;
  };
}

}  // namespace diffray::cli
