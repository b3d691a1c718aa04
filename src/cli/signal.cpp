// `diffray signal sweep|clicks|speech -o DRY.wav [--rate HZ] [--duration S] [--level DBFS] …`: dry test signals
// made locally, mono 32-bit float WAV written atomically (audio::WavWriter).
//  * sweep: exponential sine sweep --from … --to Hz (default 20 Hz … 20 kHz) over --duration (default 10 s)
//    with raised-cosine fades of --fade seconds (dsp/dry_signals.h);
//  * clicks: a click every --interval seconds from t = 0 (default 0.5 s, 5 s long), each --click-width
//    samples (1: a single sample; more: a Hann window);
//  * speech: --text spoken by Debian's espeak-ng (--voice, --speed in words per minute), resampled to --rate;
//    its natural length unless --duration pads it with silence or cuts it.
// --level is the peak in dBFS (default −6), for any click width. Options of another kind are refused rather
// than ignored; a signal longer than one WAV file holds (4 GiB of float32, audio::requireWavFits) is refused
// before it is made.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "diffray/audio/speech.h"
#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/core/error.h"
#include "diffray/dsp/dry_signals.h"

namespace diffray::cli {

namespace {

struct SignalOptions {
  std::string kind;
  std::string out;
  int rate_hz = 48000;
  double duration_s = 0.0;  ///< 0: the kind's default
  double level_dbfs = -6.0;
  dsp::SweepSpec sweep;
  dsp::ClickSpec clicks;
  audio::SpeechSpec speech;
};

constexpr int kMinRateHz = 8000, kMaxRateHz = 384000;

/// Options that belong to one kind only: refused with another.
struct KindOption {
  CLI::Option* option;
  const char* kind;
};

void checkOptions(const SignalOptions& o, const std::vector<KindOption>& specific, const CLI::Option* duration) {
  for (const KindOption& k : specific)
    if (k.option->count() > 0 && o.kind != k.kind)
      throw core::InputError(k.option->get_name(), std::string("applies to ") + k.kind + " only, not " + o.kind);
  if (o.rate_hz < kMinRateHz || o.rate_hz > kMaxRateHz)
    throw core::InputError("--rate", "must lie between " + std::to_string(kMinRateHz) + " and " +
                                         std::to_string(kMaxRateHz) + " Hz, got " + std::to_string(o.rate_hz));
  if (duration->count() > 0) {
    core::requirePositive("--duration", o.duration_s);
    if (o.duration_s > 3600.0) throw core::InputError("--duration", "at most 3600 s");
  }
  core::requireFinite("--level", o.level_dbfs);
  if (o.level_dbfs > 0.0) throw core::InputError("--level", "the peak cannot exceed 0 dBFS");
  checkOutputFile(o.out, ".wav");
  // The length is known before anything is made (speech: only when --duration is given): refuse a signal
  // one WAV cannot hold before it takes gigabytes of memory.
  const double duration_s = duration->count() > 0 ? o.duration_s
                            : o.kind == "sweep"    ? o.sweep.duration_s
                            : o.kind == "clicks"   ? o.clicks.duration_s
                                                   : 0.0;
  if (duration_s > 0.0)
    audio::requireWavFits(duration->count() > 0 ? "--duration" : "--rate", std::round(duration_s * o.rate_hz), 1,
                          o.rate_hz);
}

std::vector<float> generate(SignalOptions& o, bool duration_given) {
  const double amplitude = std::pow(10.0, o.level_dbfs / 20.0);
  const double rate = o.rate_hz;
  if (o.kind == "sweep") {
    o.sweep.rate_hz = rate;
    o.sweep.amplitude = amplitude;
    if (duration_given) o.sweep.duration_s = o.duration_s;
    return dsp::exponentialSweep(o.sweep);
  }
  if (o.kind == "clicks") {
    o.clicks.rate_hz = rate;
    o.clicks.amplitude = amplitude;
    if (duration_given) o.clicks.duration_s = o.duration_s;
    return dsp::clickTrain(o.clicks);
  }
  o.speech.rate_hz = rate;
  o.speech.amplitude = amplitude;
  std::vector<float> x = audio::synthesizeSpeech(o.speech);
  if (duration_given) x.resize(static_cast<size_t>(std::lround(o.duration_s * rate)), 0.0f);
  return x;
}

}  // namespace

Runner addSignalCommand(CLI::App& app, CommonOptions& /*common*/) {
  auto o = std::make_shared<SignalOptions>();
  CLI::App* sub = app.add_subcommand(
      "signal", "Make a dry test signal locally (mono 32-bit float WAV): an exponential sine sweep, a click "
                "train, or speech from espeak-ng.");
  sub->add_option("kind", o->kind, "sweep, clicks or speech")->required()->check(CLI::IsMember({"sweep", "clicks", "speech"}));
  sub->add_option("-o,--output", o->out, "output .wav (32-bit float, mono)")->check(outputPathValidator())->required();
  sub->add_option("--rate", o->rate_hz, "sample rate in Hz (8000 - 384000)")
      ->transform(wholeNumberValidator())
      ->capture_default_str();
  CLI::Option* duration = sub->add_option(
      "--duration", o->duration_s, "length in s (sweep 10, clicks 5; speech: its own length unless given)");
  sub->add_option("--level", o->level_dbfs, "peak level in dBFS")->capture_default_str();
  const std::vector<KindOption> specific = {
      {sub->add_option("--from", o->sweep.from_hz, "sweep: start frequency in Hz")->capture_default_str(), "sweep"},
      {sub->add_option("--to", o->sweep.to_hz, "sweep: end frequency in Hz (at most rate / 2)")->capture_default_str(),
       "sweep"},
      {sub->add_option("--fade", o->sweep.fade_s, "sweep: raised-cosine fade in and out, s")->capture_default_str(),
       "sweep"},
      {sub->add_option("--interval", o->clicks.interval_s, "clicks: time between clicks in s")->capture_default_str(),
       "clicks"},
      {sub->add_option("--click-width", o->clicks.width_samples, "clicks: samples per click (1, or a Hann window)")
           ->transform(wholeNumberValidator())
           ->capture_default_str(),
       "clicks"},
      {sub->add_option("--text", o->speech.text, "speech: what to say"), "speech"},
      {sub->add_option("--voice", o->speech.voice, "speech: espeak-ng voice (espeak-ng --voices)")->capture_default_str(),
       "speech"},
      {sub->add_option("--speed", o->speech.words_per_minute, "speech: words per minute (80 - 450)")
           ->transform(wholeNumberValidator())
           ->capture_default_str(),
       "speech"},
  };
  return [o, specific, duration]() {
    checkOptions(*o, specific, duration);
    const std::vector<float> x = generate(*o, duration->count() > 0);
    audio::requireWavFits("--text", static_cast<double>(x.size()), 1, o->rate_hz);  // speech of its own length
    audio::WavWriter writer(o->out, o->rate_hz, 1);
    writer.write(x.data(), static_cast<long>(x.size()));
    writer.commit();
    std::cout << "wrote " << o->out << ": " << o->kind << ", " << x.size() << " samples (" << static_cast<double>(x.size()) / o->rate_hz
              << " s) at " << o->rate_hz << " Hz, peak " << o->level_dbfs << " dBFS\n";
    return 0;
  };
}

}  // namespace diffray::cli
