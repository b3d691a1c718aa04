// `diffray metrics IR.wav`: ISO 3382-1 room metrics per octave (or third-octave) band of any impulse
// response libsndfile reads, measured ones included (the noise floor is found and cut off: ir/metrics.h).
// Prints a table, or with --json {"file", "sample_rate_hz", "channels", "channel", "bands": {…}}; with
// --spatial ambix or binaural also the spatial figures (ir/spatial_metrics.h) under "spatial".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/core/error.h"
#include "diffray/core/memory.h"
#include "diffray/ir/band_filter.h"
#include "diffray/ir/metrics.h"
#include "diffray/ir/spatial_metrics.h"

namespace diffray::cli {

namespace {

struct MetricsOptions {
  std::string file;
  std::string bands = "octave";
  int channel = 1;
  std::string spatial;  ///< "", "ambix" or "binaural"
};

/// The default bands (63 Hz – 8 kHz octaves, 50 Hz – 10 kHz thirds) without those whose filters would
/// reach the Nyquist frequency of a low sample rate: the top band goes while BandFilter refuses the set
/// (its own test, crossovers included: at 12 kHz the 4 kHz octave, up to ~5.7 kHz, stays).
core::Bands bandsFor(const std::string& kind, double sample_rate_hz, const std::string& file) {
  const bool third = kind == "third";
  const double top = third ? 10000.0 : 8000.0;
  const core::Bands all = third ? core::Bands::thirdOctave(50.0, top) : core::Bands::octave(63.0, top);
  for (int last = all.size() - 1; last >= 0; --last) {
    const double hi = all.nominalHz(last);
    const core::Bands bands = third ? core::Bands::thirdOctave(50.0, hi) : core::Bands::octave(63.0, hi);
    try {
      const ir::BandFilter fits(bands, sample_rate_hz);
      return bands;
    } catch (const core::InputError&) {
      // the top band reaches the Nyquist frequency: one band fewer
    }
  }
  throw core::InputError(file, "its sample rate (" + std::to_string(sample_rate_hz) +
                                   " Hz) is too low for any " + kind + " band from 63 Hz");
}

/// Refuses up front a file whose analysis would need more than half the machine's memory: its samples
/// (all channels), the analysed channel padded, one signal per band and the FFT buffers, in doubles.
void checkAnalysisMemory(const std::string& file, const std::string& kind) {
  const audio::AudioReader reader(file);
  const double frames = static_cast<double>(reader.frames()), fs = reader.sampleRateHz();
  const double bands = kind == "third" ? 24.0 : 8.0;
  const double need = 8.0 * frames * (reader.channels() + bands + 6.0);
  const double physical = core::physicalMemoryBytes();
  if (physical > 0.0 && need > 0.5 * physical) {
    char what[260];
    std::snprintf(what, sizeof what,
                  "its header claims %.0f frames (%.0f s); analysing that needs about %.1f GB, more than half of "
                  "this machine's %.1f GB: cut it to the impulse response",
                  frames, frames / fs, need / 1e9, physical / 1e9);
    throw core::InputError(file, what);
  }
}

}  // namespace

// A file alone holds one realisation of the response: nothing to estimate a figure's scatter from.
constexpr const char* kNoStandardErrors =
    "no standard errors: a WAV alone has no ray batches to estimate them from (`diffray ir` gives them for a "
    "traced room, in its table's flags and its sidecar's \"se\")";

Runner addMetricsCommand(CLI::App& app, CommonOptions& common) {
  auto o = std::make_shared<MetricsOptions>();
  CLI::App* sub = app.add_subcommand(
      "metrics", "Room metrics of an impulse response (ISO 3382-1): T20, T30, EDT, C50, C80, D50 and Ts per "
                 "band, from any audio file libsndfile reads; a measured noise floor is cut off (Lundeby).");
  sub->add_option("file", o->file, "impulse response (WAV, FLAC, AIFF, …); time zero is found at the onset")
      ->check(inputPathValidator())
      ->required();
  sub->add_flag("--json", common.json, "print a JSON object instead of a table");
  sub->add_option("--bands", o->bands, "octave (63 Hz - 8 kHz) or third (third octaves, 50 Hz - 10 kHz)")
      ->check(CLI::IsMember({"octave", "third"}))
      ->capture_default_str();
  sub->add_option("--channel", o->channel, "channel to analyse, from 1")
      ->transform(wholeNumberValidator())
      ->capture_default_str();
  sub->add_option("--spatial", o->spatial,
                  "also the spatial figures (ISO 3382-1 A.3): ambix = J_LF and J_LFC from a first-order AmbiX file "
                  "(ACN, SN3D: W, Y, Z, X; its front toward the source), binaural = IACC_E and IACC_L from a "
                  "two-channel file (left, right)")
      ->check(CLI::IsMember({"ambix", "binaural"}));
  return [o, &common]() {
    checkAnalysisMemory(o->file, o->bands);
    std::string cut;
    const audio::AudioBuffer audio = audio::readAudio(o->file, &cut);
    warnOf(cut);
    if (o->channel < 1 || o->channel > audio.channels)
      throw core::InputError("--channel", "must lie between 1 and " + std::to_string(audio.channels) + " (" +
                                              o->file + " has " + std::to_string(audio.channels) + " channel" +
                                              (audio.channels > 1 ? "s" : "") + "), got " + std::to_string(o->channel));
    const core::Bands bands = bandsFor(o->bands, audio.sample_rate_hz, o->file);
    const std::vector<double> signal = audio.channel(o->channel - 1);
    if (std::all_of(signal.begin(), signal.end(), [](double v) { return v == 0.0; }))
      throw core::InputError(o->file, "every sample of channel " + std::to_string(o->channel) +
                                          " is zero: there is no response to measure");
    const bool ambix = o->spatial == "ambix";
    if (ambix && audio.channels < 4)
      throw core::InputError(o->file, "--spatial ambix needs a first-order AmbiX file of at least 4 channels (W, Y, Z, "
                                      "X), it has " + std::to_string(audio.channels));
    if (o->spatial == "binaural" && audio.channels != 2)
      throw core::InputError(o->file, "--spatial binaural needs a two-channel file (left, right), it has " +
                                          std::to_string(audio.channels));
    const auto metrics = ir::metricsFromSignal(signal, audio.sample_rate_hz, bands);
    std::vector<ir::SpatialBandMetrics> spatial;
    if (ambix) spatial = ir::lateralFractions(audio.channel(0), audio.channel(1), audio.sample_rate_hz, bands);
    else if (!o->spatial.empty())
      spatial = ir::interauralCrossCorrelation(audio.channel(0), audio.channel(1), audio.sample_rate_hz, bands);
    if (common.json) {
      nlohmann::ordered_json j{{"file", o->file},
                       {"sample_rate_hz", audio.sample_rate_hz},
                       {"channels", audio.channels},
                       {"channel", o->channel},
                       {"bands", ir::metricsJson(bands, metrics)},
                       {"standard_errors", kNoStandardErrors}};
      if (!o->spatial.empty()) {
        j["spatial"] = ir::spatialJson(bands, spatial, ambix);
        j["spatial"]["format"] = o->spatial;
      }
      std::cout << jsonText(j) << std::endl;
    } else {
      std::cout << o->file << ": " << audio.frames() << " frames at " << audio.sample_rate_hz << " Hz, channel "
                << o->channel << " of " << audio.channels << "\n"
                << ir::metricsTable(bands, metrics) << kNoStandardErrors << "\n";
      if (!o->spatial.empty())
        std::cout << "\n" << (ambix ? "lateral fractions (W and Y of the AmbiX file)" : "interaural cross-correlation")
                  << ":\n" << ir::spatialTable(bands, spatial, ambix);
    }
    return 0;
  };
}

}  // namespace diffray::cli
