// `diffray door ROOM.json --in DRY.wav -o OUT.wav --close START:END [--steps K] [--diffraction wbsdf|utd|none]
// [--play]`:
// the sound of a door closing. A sliding panel narrows the room's door from open (START)
// to shut (END); the room is traced at K gaps (door/closing.h), each response is synthesized at the dry
// signal's sample rate (or at the room's and resampled, when the room's bands reach past the dry signal's
// Nyquist frequency; the same seed and coherent phasing, ir/synthesis.h, for every step, so that neighbouring
// IRs differ by the door only and a crossfade between them cancels nothing), and
// the dry signal is convolved through them with crossfades between their key times
// (dsp::CrossfadeConvolver), streaming. The room's sources play the dry signal (a multichannel one is mixed
// down to mono); OUT.wav has one channel per listener (or the one --listener names), or with --format
// binaural two per listener (left, right: ir::synthesizeBinaural, coherent phasing). Beside it: OUT.png, the
// spectrogram of the first channel with START and END marked; OUT.json, the sidecar (the schedule, each step's
// band levels re the open door per listener, the panel's transmission loss); OUT.csv, the same levels as a
// table. Every output is written whole or not at all. --play plays the same in real time (cli/play.h), after
// the files when -o is given too. Memory: the K IRs, and one channel of the output for the spectrogram (4
// bytes per frame); the dry signal itself streams.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/cli/play.h"
#include "diffray/cli/plot.h"
#include "diffray/cli/spectrogram_plot.h"
#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/door/closing.h"
#include "diffray/door/sliding_panel.h"
#include "diffray/dsp/crossfade_convolver.h"
#include "diffray/dsp/resample.h"
#include "diffray/dsp/spectrogram.h"
#include "diffray/ir/synthesis.h"
#include "diffray/room/checks.h"
#include "diffray/room/json_fields.h"
#include "diffray/room/scene_file.h"
#include "diffray/spatial/hrtf.h"

namespace diffray::cli {

namespace {

struct DoorOptions {
  std::string room_file, in, out, close, door, listener, spectrogram;
  int steps = 8;
  std::string diffraction = "wbsdf";
  int diffraction_order = 1;
  std::uint64_t rays = 0;
  double gain_db = 0.0;
  std::string format = "omni", hrtf;
  bool play = false;         ///< --play: real time on an audio device (with or without -o)
  std::string device;        ///< --device
  int block_frames = 256;    ///< --block
};

constexpr int kBlock = 2048;          ///< convolution block (frames)
constexpr int kSpectrogramWindow = 4096, kSpectrogramHop = 1024;

void parseClose(const std::string& text, double& start_s, double& end_s) {
  const auto colon = text.find(':');
  bool ok = colon != std::string::npos;
  if (ok) {
    try {
      std::size_t used_a = 0, used_b = 0;
      const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
      start_s = std::stod(a, &used_a);
      end_s = std::stod(b, &used_b);
      ok = used_a == a.size() && used_b == b.size() && isDecimalNumber(a) && isDecimalNumber(b);  // not 0x10
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok) throw core::InputError("--close", "must be START:END in seconds (e.g. 1.5:3), got \"" + text + "\"");
  // The crossfade's key times are counted in samples (a long): 1e300 s would overflow there and be blamed on
  // --steps. A door still closing 30 years into the dry signal plays its last IR anyway.
  constexpr double kMaxCloseS = 1e9;
  if (std::abs(start_s) > kMaxCloseS || std::abs(end_s) > kMaxCloseS)
    throw core::InputError("--close", "START and END must be at most 1e9 s, got \"" + text + "\"");
}

// `inputs`: every file the room was read from (Room::input_files); the dry signal is added.
void checkOutputs(const DoorOptions& o, const std::string& png, std::vector<std::string> inputs) {
  checkOutputFile(o.out, ".wav");
  checkOutputFile(png, ".png");
  inputs.push_back(o.in);
  checkOutputFiles({o.out, withExtension(o.out, ".json"), withExtension(o.out, ".csv"), png}, inputs);
  checkPlotOption("--spectrogram", png);  // a name gnuplot can write, and gnuplot itself, before the work
}

double toDb(double ratio) { return ratio > 0.0 ? 10.0 * std::log10(ratio) : -std::numeric_limits<double>::infinity(); }

/// Convolves the dry signal through the steps' IRs into OUT.wav; returns the first output channel and sets
/// `peak` to the largest |sample| written (linear, full scale 1).
std::vector<float> render(audio::AudioReader& reader, const std::vector<std::vector<std::vector<float>>>& irs,
                          const std::vector<long>& keys, double gain, const std::string& out, double& peak) {
  dsp::CrossfadeConvolver conv;
  conv.init(kBlock, irs, 1, keys);
  const int c_in = reader.channels(), c_out = conv.outputChannels();
  audio::WavWriter writer(out, static_cast<int>(std::lround(reader.sampleRateHz())), c_out);
  std::vector<float> raw(static_cast<std::size_t>(kBlock) * c_in), mono(kBlock), wet(static_cast<std::size_t>(kBlock) * c_out);
  std::vector<float> first;
  auto emit = [&](long n) {
    for (long i = 0; i < n * c_out; ++i) {
      wet[i] = static_cast<float>(wet[i] * gain);
      peak = std::max(peak, static_cast<double>(std::abs(wet[i])));
    }
    writer.write(wet.data(), n);
    for (long f = 0; f < n; ++f) first.push_back(wet[f * c_out]);
  };
  for (long n; (n = reader.read(raw.data(), kBlock)) > 0;) {
    for (long f = 0; f < n; ++f) {
      double s = 0.0;
      for (int c = 0; c < c_in; ++c) s += raw[f * c_in + c];
      mono[f] = static_cast<float>(s / c_in);
    }
    conv.process(mono.data(), wet.data(), n);
    emit(n);
  }
  for (long left = conv.tailFrames(); left > 0;) {
    const long n = std::min<long>(left, kBlock);
    conv.flush(wet.data(), n);
    emit(n);
    left -= n;
  }
  writer.commit();
  return first;
}

}  // namespace

Runner addDoorCommand(CLI::App& app, CommonOptions& common) {
  auto opts = std::make_shared<DoorOptions>();
  CLI::App* sub = app.add_subcommand(
      "door", "The sound of a door closing: a sliding panel shuts the room's door between START and END while DRY.wav "
              "plays; the room is traced at K openings and the dry signal convolved through them with crossfades "
              "(WAV + spectrogram PNG + JSON + CSV).");
  sub->add_option("room", opts->room_file, "scene file with a door that has a \"panel\" material (rooms/README.md)")
      ->check(inputPathValidator())
      ->required();
  sub->add_option("--in", opts->in, "dry signal (WAV, FLAC, ...; its sample rate is the output's)")
      ->check(inputPathValidator())
      ->required();
  sub->add_option("-o,--output", opts->out, "output WAV (one channel per listener; or --play, or both)")
      ->check(outputPathValidator());
  sub->add_option("--close", opts->close, "START:END in seconds: the panel leaves the door open at START, shut at END")
      ->required();
  sub->add_option("--steps", opts->steps, "openings traced: gaps W, W/2, W/4, ... and shut")
      ->transform(wholeNumberValidator(2, 32))
      ->capture_default_str();
  addDiffractionOptions(sub, opts->diffraction, opts->diffraction_order);
  sub->get_option("--diffraction")->default_val("wbsdf");
  sub->add_option("--door", opts->door, "the door's name (default: the room's only door)");
  sub->add_option("--listener", opts->listener, "render this listener only (default: all, one channel each)");
  sub->add_option("--format", opts->format,
                  "omni (default): one channel per listener; binaural: two per listener (left, right) through an HRTF")
      ->check(CLI::IsMember({"omni", "binaural"}));
  addHrtfOption(sub, opts->hrtf, "--format binaural");
  addRaysOption(sub, opts->rays, "rays per source and step (default: the room file's output.rays)");
  CLI::Option* seed_option = sub->add_option("--seed", common.seed, "random seed (default: the room file's)")
                                  ->transform(seedValidator());
  addThreadsOption(sub, common.threads);
  sub->add_option("--gain", opts->gain_db, "output gain in dB")->check(gainDbValidator());
  sub->add_option("--spectrogram", opts->spectrogram, "spectrogram PNG of the first channel (default: OUT.png)")
      ->check(outputPathValidator());
  sub->add_flag("--json", common.json, "print the JSON sidecar to stdout instead of the table");
  sub->add_flag("--play", opts->play,
                "play the closing door in real time on an audio device (PortAudio; the crossfades run in the audio "
                "callback), after writing -o if given");
  sub->add_option("--device", opts->device, "with --play: output device, by index or name substring (default: the "
                                            "default device; `diffray auralize --list-devices` lists them)");
  CLI::Option* block = sub->add_option("--block", opts->block_frames,
                                       "with --play: audio block in frames, 16 - 16384 (the latency: block / rate)")
                           ->capture_default_str();

  return [opts, &common, seed_option, block]() {
    const auto t_start = std::chrono::steady_clock::now();
    if (opts->out.empty() && !opts->play) throw core::InputError("door", "give -o OUT.wav, --play, or both");
    if (opts->out.empty() && !opts->spectrogram.empty())
      throw core::InputError("--spectrogram", "is written beside -o OUT.wav; give -o as well");
    if (!opts->play && !opts->device.empty()) throw core::InputError("--device", "only applies with --play");
    if (!opts->play && block->count() > 0) throw core::InputError("--block", "only applies with --play");
    core::ThreadLimit limit(common.threads);
    double start_s = 0.0, end_s = 0.0;
    parseClose(opts->close, start_s, end_s);
    std::vector<std::string> warnings;
    const room::Room room = room::loadRoom(opts->room_file, &warnings);
    if (seed_option->count() == 0) common.seed = room.output.seed;
    const int door = door::findDoor(room, opts->door);
    const room::Occluder& d = room.occluders[door];
    const std::vector<door::ClosingStep> schedule = door::closingSchedule(2.0 * d.half_x_m, start_s, end_s, opts->steps);
    std::vector<int> chosen;
    for (int l = 0; l < static_cast<int>(room.listeners.size()); ++l)
      if (opts->listener.empty() || room.listeners[l].name == opts->listener) chosen.push_back(l);
    if (chosen.empty()) throw core::InputError("--listener", "the room has no listener named \"" + opts->listener + "\"");
    const std::string png = opts->spectrogram.empty() ? withExtension(opts->out, ".png") : opts->spectrogram;
    if (!opts->out.empty()) checkOutputs(*opts, png, room.input_files);
    if (opts->play) {  // the device and the block before the (long) tracing
      requireBlockFrames(opts->block_frames);
      requireOutputDevice(opts->device);
    }
    {  // One pass through the dry signal before the (long) tracing: a NaN in it is an error now, not later.
      audio::AudioReader scan(opts->in);
      std::vector<float> buffer(static_cast<std::size_t>(kBlock) * scan.channels());
      while (scan.read(buffer.data(), kBlock) > 0) {
      }
    }
    audio::AudioReader reader(opts->in);
    warnOf(reader.warning());
    const double fs = reader.sampleRateHz();
    // The IRs are synthesized at the dry signal's rate when the room's bands fit below its Nyquist frequency,
    // else at the room's own rate and resampled (as filters) to the dry signal's; either way with the room
    // rate's gain (door::impulseResponseFor).
    const double synth_fs = door::synthesisRateHz(room.bands, room.output.sample_rate_hz, fs);
    room::checkSynthesis(room, 0.0, synth_fs, (room.file.empty() ? std::string("room") : room.file) + ": output.sample_rate_hz");
    if (synth_fs != fs) {  // the IRs will be resampled to the dry signal's rate: can they be? (before the tracing)
      try {
        dsp::resample(std::vector<float>(1, 0.0f), 1, synth_fs, fs);
      } catch (const core::InputError& e) {
        const std::string hz = std::to_string(static_cast<long>(fs)), room_hz = std::to_string(static_cast<long>(synth_fs));
        throw core::InputError(opts->in, "sample rate " + hz + " Hz: the room's IRs, made at " + room_hz +
                                             " Hz, cannot be resampled to it: " + reasonOf(e));
      }
    }
    // The HRTF set at the IRs' rate, before the tracing: a bad file is one line and nothing written.
    std::optional<spatial::Hrtf> hrtf;
    if (!opts->hrtf.empty() && opts->format != "binaural") throw core::InputError("--hrtf", "is for --format binaural");
    if (opts->format == "binaural") {
      hrtf = spatial::Hrtf::load(opts->hrtf, synth_fs);
      std::cerr << "diffray: info: HRTF " << describeHrtf(*hrtf) << "\n";
    }
    // The crossfade's key frames, before the (long) tracing: too many steps over a short close coincide.
    const std::vector<long> keys = door::keyFrames(schedule, fs, 2.0 * d.half_x_m, start_s, end_s);
    if (end_s > static_cast<double>(reader.frames()) / fs)
      warnings.push_back("the door is still closing when " + opts->in + " ends (its header claims " +
                         std::to_string(reader.frames()) + " frames, " +
                         std::to_string(static_cast<double>(reader.frames()) / fs) + " s); the output's tail is the "
                         "last IR's");
    for (const auto& w : warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";

    // The responses, one trace per step.
    door::ClosingOptions co;
    co.diffraction = opts->diffraction;
    co.max_diffractions = opts->diffraction_order;
    co.rays = opts->rays;
    co.seed = common.seed;
    co.directions = hrtf.has_value();
    const std::uint64_t rays = opts->rays ? opts->rays : room.output.rays;
    core::Progress progress("door " + room.name, rays * room.sources.size() * schedule.size());
    co.on_progress = [&progress](std::uint64_t n) { progress.add(n); };
    const door::ClosingResponse cr = door::simulateClosing(room, door, schedule, co);
    progress.finish();
    for (const auto& w : cr.warnings) std::cerr << "diffray: warning: " << core::oneLine(w) << "\n";

    // Band energies per step and chosen listener, and their levels re the open door (step 0), once.
    std::vector<std::vector<core::BandArray>> energy(schedule.size()), level_db(schedule.size());
    for (std::size_t k = 0; k < schedule.size(); ++k)
      for (std::size_t i = 0; i < chosen.size(); ++i) {
        energy[k].push_back(door::bandEnergies(cr.responses[k][chosen[i]]));
        level_db[k].push_back(core::bandFill(0.0));
        for (int b = 0; b < room.bands.size(); ++b) level_db[k][i][b] = toDb(energy[k][i][b] / energy[0][i][b]);
      }

    // IRs at the dry signal's rate, key frames, and the levels for the sidecars.
    std::vector<std::vector<std::vector<float>>> irs(schedule.size());
    nlohmann::ordered_json steps = nlohmann::ordered_json::array();
    std::ostringstream csv;
    csv << "step,time_s,gap_m,listener";
    for (int b = 0; b < room.bands.size(); ++b) csv << ",level_re_open_db_" << room.bands.label(b) << "hz";
    csv << '\n' << std::setprecision(6);
    for (std::size_t k = 0; k < schedule.size(); ++k) {
      nlohmann::ordered_json levels = nlohmann::ordered_json::object(), energies = nlohmann::ordered_json::object();
      for (std::size_t i = 0; i < chosen.size(); ++i) {
        const int l = chosen[i];
        if (hrtf) {
          for (std::vector<float>& ear :
               door::binauralResponsesFor(cr.responses[k][l], room.output.sample_rate_hz, fs, cr.length_s, cr.volume_m3,
                                          cr.speed_of_sound_m_s, ir::listenerSeed(common.seed, l), *hrtf, room.listeners[l]))
            irs[k].push_back(std::move(ear));
        } else {
          irs[k].push_back(door::impulseResponseFor(cr.responses[k][l], room.output.sample_rate_hz, fs, cr.length_s,
                                                    cr.volume_m3, cr.speed_of_sound_m_s, ir::listenerSeed(common.seed, l)));
        }
        nlohmann::ordered_json row = nlohmann::ordered_json::array(), absolute = nlohmann::ordered_json::array();
        for (int b = 0; b < room.bands.size(); ++b) absolute.push_back(energy[k][i][b]);
        energies[room.listeners[l].name] = absolute;
        csv << k << ',' << schedule[k].time_s << ',' << schedule[k].gap_m << ',' << room.listeners[l].name;
        for (int b = 0; b < room.bands.size(); ++b) {
          const double db = level_db[k][i][b];
          row.push_back(std::isfinite(db) ? nlohmann::ordered_json(std::round(db * 100.0) / 100.0) : nlohmann::ordered_json());
          csv << ',' << db;
        }
        csv << '\n';
        levels[room.listeners[l].name] = row;
      }
      steps.push_back({{"time_s", schedule[k].time_s}, {"gap_m", schedule[k].gap_m}, {"level_re_open_db", levels},
                       {"energy_j_m2", energies}});
    }

    if (synth_fs != fs)
      std::cout << "synthesized the impulse responses at " << synth_fs << " Hz (the room's bands reach past the dry "
                << "signal's Nyquist frequency) and resampled them to its " << fs << " Hz (libsamplerate)\n";
    // Render, then the spectrogram and the sidecars (each atomic; the WAV first, the largest).
    OutputFiles written;  // replaced together: a later failure leaves the previous files
    if (!opts->out.empty()) {
      std::vector<float> first;
      double peak = 0.0;
      written.write(opts->out, [&](const std::string& f) {
        first = render(reader, irs, keys, std::pow(10.0, opts->gain_db / 20.0), f, peak);
      });
      warnIfClips(opts->out, peak, "lower --gain");
      const dsp::Spectrogram spec = dsp::spectrogram(first.data(), static_cast<long>(first.size()), fs,
                                                     kSpectrogramWindow, kSpectrogramHop);
      SpectrogramPlotOptions po;
      po.title = room.name + ": door " + d.name + " closing (" + opts->diffraction + "), listener " +
                 room.listeners[chosen[0]].name;
      po.markers = {{start_s, "open"}, {end_s, "shut"}};
      po.option = "--spectrogram";
      written.write(png, [&](const std::string& f) { writeSpectrogramPlot(f, spec, po); });
    }

    nlohmann::ordered_json bands = nlohmann::ordered_json::array(), tl = nlohmann::ordered_json::array();
    for (int b = 0; b < room.bands.size(); ++b) {
      bands.push_back(room.bands.nominalHz(b));
      tl.push_back(std::round(-toDb(cr.panel_transmission[b]) * 100.0) / 100.0);
    }
    nlohmann::ordered_json listeners = nlohmann::ordered_json::array();
    for (int l : chosen) listeners.push_back(room.listeners[l].name);
    std::vector<std::string> all_warnings = warnings;
    all_warnings.insert(all_warnings.end(), cr.warnings.begin(), cr.warnings.end());
    nlohmann::ordered_json side{
        {"diffray_version", DIFFRAY_VERSION},
        {"room", room.name},
        {"room_file", opts->room_file},
        {"door", d.name},
        {"door_width_m", cr.width_m},
        {"dry", opts->in},
        {"wav", opts->out.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(opts->out)},
        {"spectrogram", opts->out.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(png)},
        {"sample_rate_hz", fs},
        {"close_s", {start_s, end_s}},
        {"diffraction", opts->diffraction},
        {"panel", {{"material", cr.panel_name}, {"transmission_loss_db", tl}}},
        {"band_centres_hz", bands},
        {"listeners", listeners},
        {"ir_length_s", cr.length_s},
        {"seed", common.seed},
        {"rays_per_source_and_step", rays},
        {"threads", core::ThreadLimit::current()},
        {"steps", steps},
        {"warnings", all_warnings}};
    side["timing_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    if (!opts->out.empty()) {
      written.write(withExtension(opts->out, ".csv"), [&](const std::string& f) {
        core::writeFileAtomically(f, [&](std::ostream& out) { out << csv.str(); });
      });
      written.write(withExtension(opts->out, ".json"), [&](const std::string& f) {
        core::writeFileAtomically(f, [&](std::ostream& out) { out << jsonText(side, 2) << '\n'; });
      });
      commitAndAnnounce(written);
    }
    const auto play = [&]() {
      return opts->play ? playCrossfade(irs, keys, opts->in, opts->device, opts->block_frames, opts->gain_db,
                                        common.json ? std::cerr : std::cout)
                        : 0;
    };
    if (common.json) {
      std::cout << jsonText(side, 2) << std::endl;
      return play();
    }
    std::printf("%s: door %s closes %.2f-%.2f s in %zu steps (%s), %llu rays per step -> %s\n", room.name.c_str(),
                d.name.c_str(), start_s, end_s, schedule.size(), opts->diffraction.c_str(),
                static_cast<unsigned long long>(rays),
                opts->out.empty() ? "played, nothing written" : (opts->out + " (+ .png, .json, .csv)").c_str());
    std::printf("level re the open door (dB), listener %s:\n%8s %8s", room.listeners[chosen[0]].name.c_str(), "time_s",
                "gap_m");
    for (int b = 0; b < room.bands.size(); ++b) std::printf(" %7s", room.bands.label(b).c_str());
    std::printf("\n");
    bool signed_noise = false;
    for (std::size_t k = 0; k < schedule.size(); ++k) {
      std::printf("%8.3f %8.4f", schedule[k].time_s, schedule[k].gap_m);
      for (int b = 0; b < room.bands.size(); ++b) {
        const double db = level_db[k][0][b];
        if (std::isfinite(db)) {
          std::printf(" %7.1f", db);
        } else {
          std::printf(" %7s", "-");
          signed_noise = true;
        }
      }
      std::printf("\n");
    }
    if (signed_noise)
      std::printf("-: the band's signed energy summed to <= 0 at this gap (WBSDF noise: use more --rays)\n");
    std::fflush(stdout);
    return play();
  };
}

}  // namespace diffray::cli
