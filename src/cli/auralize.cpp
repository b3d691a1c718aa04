// `diffray auralize --ir IR.wav --in DRY.wav -o WET.wav [--gain DB] [--normalize] [--no-resample]`: convolves
// a dry signal with an impulse response (dsp::MultichannelConvolver: uniformly partitioned FFT convolution,
// output channels in parallel on all cores) into a 32-bit float WAV of input + IR − 1 frames (the whole tail). Streaming: the dry signal is read and the
// result written in blocks, so memory grows with the IR, not with the input. Channel pairing as in
// dsp/multichannel_convolver.h. An impulse response at another sample rate than the dry signal is resampled
// to the dry signal's rate (dsp::resampleImpulseResponse: libsamplerate's best sinc, scaled so the filter's
// frequency response is kept) with one info line on stdout; the IR is short, so memory stays bounded and the
// input still streams. --no-resample refuses a mismatch with one error line instead.
// --gain scales by 10^(DB/20), |DB| ≤ 120 (checked when parsing, as door's). An output beyond one WAV file's
// 4 GiB (audio::requireWavFits) is refused before the convolution. --normalize takes two passes through a temporary file: the unscaled result
// is written to OUT.wav.unscaled.tmp.PID (float32, so nothing is lost) while its peak is measured, then read
// back, scaled so the peak sits at −1 dBFS (then --gain on top) and written to OUT.wav; the temporary is
// removed whatever happens. Outputs appear whole or not at all (audio::WavWriter).
// --play plays the convolution in real time instead (or, with -o as well, after writing the file);
// --list-devices lists the audio outputs (src/cli/auralize_play.cpp, include/diffray/cli/play.h).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <vector>

#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/cli/play.h"
#include "diffray/core/error.h"
#include "diffray/core/temp_files.h"
#include "diffray/dsp/multichannel_convolver.h"
#include "diffray/dsp/resample.h"
#include "diffray/spatial/ambisonic_decoder.h"
#include "diffray/spatial/hrtf.h"

namespace diffray::cli {

namespace {

struct AuralizeOptions {
  std::string ir;
  std::string in;
  std::string out;
  double gain_db = 0.0;
  bool normalize = false;
  bool no_resample = false;
  bool play = false;
  bool list_devices = false;
  PlayOptions playback;
};

constexpr double kNormalizedPeakDbfs = -1.0;

/// FFT block: a power of two near a quarter of the IR's length, within [1024, 32768] frames. Offline, the
/// cost per sample is two FFTs of 2·block (∝ log block) plus one complex multiply-add per partition over
/// spectra that stream from memory (∝ IR / block); on a 3 s IR at 48 kHz, 32768 (5 partitions) measured
/// 35 % faster than 8192 (18) and than 65536 (3), whose FFTs leave the cache.
int blockFor(long ir_frames) {
  int block = 1024;
  while (block < (ir_frames + 3) / 4 && block < 32768) block *= 2;
  return block;
}

/// Frames read, convolved and written per step: several blocks, so processParallel() starts its threads
/// rarely and the file I/O goes in large pieces.
long chunkFor(int block) { return std::max<long>(block, 65536); }

/// Removes a file when it goes out of scope (the temporary of the two-pass --normalize).
struct RemoveOnExit {
  std::string path;
  core::TempRegistration registered{path};  // and on an interrupt
  ~RemoveOnExit() { std::remove(path.c_str()); }
};

void checkOutputPath(const AuralizeOptions& o) {
  namespace fs = std::filesystem;
  checkOutputFile(o.out, ".wav");
  std::error_code ec;
  for (const std::string& input : {o.ir, o.in})
    if (fs::equivalent(o.out, input, ec)) throw core::InputError(o.out, "would overwrite the input " + input);
}


/// Convolves the dry file through `conv` into `writer` scaled by `gain`, the tail included; returns the
/// peak |sample| written.
double convolveInto(audio::AudioReader& dry, dsp::MultichannelConvolver& conv, int block, float gain,
                    audio::WavWriter& writer) {
  const int cin = conv.inputChannels(), cout = conv.outputChannels();
  const long chunk = chunkFor(block);
  std::vector<float> in(static_cast<size_t>(chunk) * static_cast<size_t>(cin), 0.0f);
  std::vector<float> out(static_cast<size_t>(chunk) * static_cast<size_t>(cout), 0.0f);
  double peak = 0.0;
  long tail = conv.irLength() - 1;
  for (;;) {
    long frames = dry.read(in.data(), chunk);
    if (frames == 0) {  // the input is over: zeros until the IR's tail has rung out
      if (tail == 0) break;
      frames = std::min<long>(tail, chunk);
      tail -= frames;
      std::fill(in.begin(), in.end(), 0.0f);
    }
    conv.processParallel(in.data(), out.data(), frames);
    const long samples = frames * cout;
    for (long i = 0; i < samples; ++i) {
      out[static_cast<size_t>(i)] *= gain;
      peak = std::max(peak, static_cast<double>(std::abs(out[static_cast<size_t>(i)])));
    }
    writer.write(out.data(), frames);
  }
  return peak;
}

/// Copies `from` into `writer` scaled by `gain` (second pass of --normalize).
void scaleInto(audio::AudioReader& from, float gain, audio::WavWriter& writer) {
  constexpr long kBlock = 8192;
  std::vector<float> buffer(static_cast<size_t>(kBlock) * static_cast<size_t>(from.channels()));
  for (long frames; (frames = from.read(buffer.data(), kBlock)) > 0;) {
    for (long i = 0; i < frames * from.channels(); ++i) buffer[static_cast<size_t>(i)] *= gain;
    writer.write(buffer.data(), frames);
  }
}


}  // namespace

std::vector<std::vector<float>> decodedIr(std::vector<std::vector<float>> channels, const PlayOptions& o, double rate_hz) {
  if (!o.hrtf.empty() && o.decode != "binaural") throw core::InputError("--hrtf", "is for --decode binaural");
  if (o.decode.empty()) return channels;
  const std::vector<core::Vec3> layout =
      o.decode == "binaural" ? std::vector<core::Vec3>() : spatial::parseLayout(o.decode, "--decode");
  spatial::ambisonicOrderOf(static_cast<int>(channels.size()), o.ir);
  if (!layout.empty()) return spatial::decodeToLayout(channels, layout);
  const spatial::Hrtf hrtf = spatial::Hrtf::load(o.hrtf, rate_hz);
  std::cout << "decoding the AmbiX IR to binaural through " << describeHrtf(hrtf) << "\n";
  return spatial::decodeToBinaural(channels, hrtf);
}

std::vector<std::vector<float>> irAtRate(const audio::AudioBuffer& ir, double rate_hz, const std::string& ir_path,
                                         bool no_resample) {
  std::vector<float> h(ir.samples.begin(), ir.samples.end());
  if (ir.sample_rate_hz != rate_hz) {
    const std::string ir_hz = std::to_string(static_cast<long>(ir.sample_rate_hz)) + " Hz";
    const std::string in_hz = std::to_string(static_cast<long>(rate_hz)) + " Hz";
    if (no_resample)
      throw core::InputError(ir_path, "sample rate " + ir_hz + " differs from the input's " + in_hz +
                                       " (--no-resample: resample one of them first, or drop the flag)");
    try {
      h = dsp::resampleImpulseResponse(h, ir.channels, ir.sample_rate_hz, rate_hz);
    } catch (const core::InputError& e) {  // "resample: rate ratio … lies outside …": name the file
      throw core::InputError(ir_path, "cannot resample its " + ir_hz + " to the input's " + in_hz + ": " + reasonOf(e));
    }
    std::cout << "resampled the impulse response from " << ir_hz << " to the input's " << in_hz << " (libsamplerate, best sinc; "
              << ir.frames() << " -> " << h.size() / static_cast<size_t>(ir.channels) << " frames)\n";
  }
  std::vector<std::vector<float>> channels(static_cast<size_t>(ir.channels));
  const size_t frames = h.size() / static_cast<size_t>(ir.channels);
  for (size_t c = 0; c < channels.size(); ++c) {
    channels[c].resize(frames);
    for (size_t f = 0; f < frames; ++f) channels[c][f] = h[f * channels.size() + c];
  }
  return channels;
}

Runner addAuralizeCommand(CLI::App& app, CommonOptions& /*common*/) {
  auto o = std::make_shared<AuralizeOptions>();
  CLI::App* sub = app.add_subcommand(
      "auralize", "Convolve a dry recording with an impulse response (partitioned FFT convolution, streaming) "
                  "into a 32-bit float WAV that keeps the whole reverberant tail.");
  sub->add_option("--ir", o->ir, "impulse response (WAV, FLAC, …): mono, or one channel per output")
      ->check(inputPathValidator());
  sub->add_option("--in", o->in, "dry signal (the IR is resampled to its rate if they differ)")
      ->check(inputPathValidator());
  sub->add_option("-o,--output", o->out, "output .wav (32-bit float), input + IR - 1 frames long (or --play)")
      ->check(outputPathValidator());
  sub->add_option("--gain", o->gain_db, "gain in dB applied to the output (-120 - 120)")
      ->check(gainDbValidator())
      ->capture_default_str();
  sub->add_flag("--normalize", o->normalize,
                "scale the output's peak to -1 dBFS (two passes through a temporary file; --gain applies on top)");
  sub->add_flag("--no-resample", o->no_resample,
                "refuse an IR whose sample rate differs from the input's instead of resampling it");
  sub->add_option("--decode", o->playback.decode,
                  "an AmbiX IR (diffray ir --format ambix) decoded to binaural (two ears, through --hrtf) or to "
                  "loudspeakers AZ:EL,AZ:EL,... in degrees (mode matching; one output channel each)");
  addHrtfOption(sub, o->playback.hrtf, "--decode binaural");
  sub->add_flag("--play", o->play, "play the result in real time on an audio device (PortAudio)");
  sub->add_option("--device", o->playback.device, "with --play: output device, by index or name substring "
                                                   "(default: the system's default output)");
  CLI::Option* block = sub->add_option("--block", o->playback.block_frames,
                                       "with --play: audio block in frames, 16 - 16384 (the latency: block / "
                                       "sample rate)")
                           ->transform(wholeNumberValidator())
                           ->capture_default_str();
  sub->add_flag("--list-devices", o->list_devices, "list the audio output devices and exit");
  return [o, block]() {
    if (o->list_devices) return listAudioDevices();
    if (o->ir.empty()) throw core::InputError("auralize", "--ir IR.wav is required");
    if (o->in.empty()) throw core::InputError("auralize", "--in DRY.wav is required");
    if (o->out.empty() && !o->play) throw core::InputError("auralize", "give -o WET.wav, --play, or both");
    if (!o->play && !o->playback.device.empty()) throw core::InputError("--device", "only applies with --play");
    if (!o->play && block->count() > 0) throw core::InputError("--block", "only applies with --play");
    if (o->play) requireBlockFrames(o->playback.block_frames);  // before -o is written, not after
    o->playback.ir = o->ir;
    o->playback.in = o->in;
    o->playback.gain_db = o->gain_db;
    o->playback.no_resample = o->no_resample;
    if (o->out.empty()) return playAuralization(o->playback);
    if (o->play) requireOutputDevice(o->playback.device);  // before writing: no file and then an error
    core::requireFinite("--gain", o->gain_db);
    checkOutputPath(*o);
    audio::AudioReader dry(o->in);
    std::string cut;
    const audio::AudioBuffer ir = audio::readAudio(o->ir, &cut);
    warnOf(dry.warning());
    warnOf(cut);
    const std::vector<std::vector<float>> ir_channels =
        decodedIr(irAtRate(ir, dry.sampleRateHz(), o->ir, o->no_resample), o->playback, dry.sampleRateHz());
    const long ir_frames = static_cast<long>(ir_channels.front().size());
    const int fft_block = blockFor(ir_frames);
    dsp::MultichannelConvolver conv;
    conv.init(fft_block, ir_channels, dry.channels());
    const int rate = static_cast<int>(dry.sampleRateHz());
    try {  // the dry length is the header's claim: the message says so, naming the input
      audio::requireWavFits(o->out, static_cast<double>(dry.frames()) + static_cast<double>(ir_frames) - 1.0,
                            conv.outputChannels(), rate);
    } catch (const core::InputError& e) {
      throw core::InputError(o->in, "its header claims " + std::to_string(dry.frames()) + " frames; " + e.what());
    }
    const double gain = std::pow(10.0, o->gain_db / 20.0);
    double peak = 0.0;
    double applied_db = o->gain_db;
    long frames = 0;
    if (!o->normalize) {
      audio::WavWriter writer(o->out, rate, conv.outputChannels());
      peak = convolveInto(dry, conv, fft_block, static_cast<float>(gain), writer);
      frames = writer.framesWritten();
      writer.commit();
    } else {
      RemoveOnExit unscaled{o->out + ".unscaled.tmp." + std::to_string(::getpid())};
      double raw_peak = 0.0;
      try {
        audio::WavWriter pass1(unscaled.path, rate, conv.outputChannels());
        raw_peak = convolveInto(dry, conv, fft_block, 1.0f, pass1);
        pass1.commit();
      } catch (const core::InputError& e) {  // a sample that overflowed: the user's output, not the temporary
        if (e.where() != unscaled.path) throw;
        throw core::InputError(o->out, reasonOf(e));
      }
      const double scale = raw_peak > 0.0 ? std::pow(10.0, kNormalizedPeakDbfs / 20.0) / raw_peak * gain : gain;
      if (raw_peak == 0.0) std::cerr << "diffray: warning: the output is silent; --normalize leaves it so\n";
      audio::AudioReader back(unscaled.path);
      audio::WavWriter writer(o->out, rate, conv.outputChannels());
      scaleInto(back, static_cast<float>(scale), writer);
      frames = writer.framesWritten();
      writer.commit();
      peak = raw_peak * scale;
      applied_db = 20.0 * std::log10(scale);
    }
    warnIfClips(o->out, peak, "--normalize sets the peak to -1 dBFS, or lower --gain");
    std::cout << "wrote " << o->out << ": " << frames << " frames x " << conv.outputChannels() << " channel"
              << (conv.outputChannels() > 1 ? "s" : "") << " at " << rate << " Hz (input " << dry.frames()
              << " + IR " << ir_frames << " - 1), gain " << applied_db << " dB, peak " << dbfs(peak) << " dBFS\n";
    return o->play ? playAuralization(o->playback) : 0;
  };
}

}  // namespace diffray::cli
