// `diffray auralize --ir IR.wav --in DRY.wav -o WET.wav [--gain DB] [--normalize]`: convolves a dry signal
// with an impulse response (dsp::MultichannelConvolver: uniformly partitioned FFT convolution) into a
// 32-bit float WAV of input + IR − 1 frames (the whole tail). Streaming: the dry signal is read and the
// result written in blocks, so memory grows with the IR, not with the input. Channel pairing as in
// dsp/multichannel_convolver.h. The sample rates must agree (no resampling): a mismatch is one error line.
// --gain scales by 10^(DB/20). --normalize takes two passes through a temporary file: the unscaled result
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
#include <iostream>
#include <memory>
#include <vector>

#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/cli/play.h"
#include "diffray/core/error.h"
#include "diffray/dsp/multichannel_convolver.h"

namespace diffray::cli {

namespace {

struct AuralizeOptions {
  std::string ir;
  std::string in;
  std::string out;
  double gain_db = 0.0;
  bool normalize = false;
  bool play = false;
  bool list_devices = false;
  PlayOptions playback;
};

constexpr double kNormalizedPeakDbfs = -1.0;

/// FFT block: the IR's length rounded up to a power of two, within [256, 8192] frames (longer IRs use
/// several partitions; the block bounds the FFT size and so the cache footprint).
int blockFor(long ir_frames) {
  int block = 256;
  while (block < ir_frames && block < 8192) block *= 2;
  return block;
}

/// Removes a file when it goes out of scope (the temporary of the two-pass --normalize).
struct RemoveOnExit {
  std::string path;
  ~RemoveOnExit() { std::remove(path.c_str()); }
};

void checkOutputPath(const AuralizeOptions& o) {
  namespace fs = std::filesystem;
  if (fs::path(o.out).extension() != ".wav") throw core::InputError(o.out, "the output must be a .wav file");
  if (!fs::is_directory(fs::absolute(o.out).parent_path())) throw core::InputError(o.out, "its folder does not exist");
  std::error_code ec;
  for (const std::string& input : {o.ir, o.in})
    if (fs::equivalent(o.out, input, ec)) throw core::InputError(o.out, "would overwrite the input " + input);
}

double dbfs(double peak) { return peak > 0.0 ? 20.0 * std::log10(peak) : -INFINITY; }

/// Convolves the dry file through `conv` into `writer` scaled by `gain`, the tail included; returns the
/// peak |sample| written.
double convolveInto(audio::AudioReader& dry, dsp::MultichannelConvolver& conv, int block, float gain,
                    audio::WavWriter& writer) {
  const int cin = conv.inputChannels(), cout = conv.outputChannels();
  std::vector<float> in(static_cast<size_t>(block) * static_cast<size_t>(cin), 0.0f);
  std::vector<float> out(static_cast<size_t>(block) * static_cast<size_t>(cout), 0.0f);
  double peak = 0.0;
  long tail = conv.irLength() - 1;
  for (;;) {
    long frames = dry.read(in.data(), block);
    if (frames == 0) {  // the input is over: zeros until the IR's tail has rung out
      if (tail == 0) break;
      frames = std::min<long>(tail, block);
      tail -= frames;
      std::fill(in.begin(), in.end(), 0.0f);
    }
    conv.process(in.data(), out.data(), frames);
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

Runner addAuralizeCommand(CLI::App& app, CommonOptions& /*common*/) {
  auto o = std::make_shared<AuralizeOptions>();
  CLI::App* sub = app.add_subcommand(
      "auralize", "Convolve a dry recording with an impulse response (partitioned FFT convolution, streaming) "
                  "into a 32-bit float WAV that keeps the whole reverberant tail.");
  sub->add_option("--ir", o->ir, "impulse response (WAV, FLAC, …): mono, or one channel per output");
  sub->add_option("--in", o->in, "dry signal (same sample rate as the IR)");
  sub->add_option("-o,--out", o->out, "output .wav (32-bit float), input + IR - 1 frames long (or --play)");
  sub->add_option("--gain", o->gain_db, "gain in dB applied to the output")->capture_default_str();
  sub->add_flag("--normalize", o->normalize,
                "scale the output's peak to -1 dBFS (two passes through a temporary file; --gain applies on top)");
  sub->add_flag("--play", o->play, "play the result in real time on an audio device (PortAudio)");
  sub->add_option("--device", o->playback.device, "with --play: output device, by index or name substring "
                                                   "(default: the system's default output)");
  sub->add_option("--block", o->playback.block_frames,
                  "with --play: audio block in frames (the latency: block / sample rate)")->capture_default_str();
  sub->add_flag("--list-devices", o->list_devices, "list the audio output devices and exit");
  return [o]() {
    if (o->list_devices) return listAudioDevices();
    if (o->ir.empty()) throw core::InputError("auralize", "--ir IR.wav is required");
    if (o->in.empty()) throw core::InputError("auralize", "--in DRY.wav is required");
    if (o->out.empty() && !o->play) throw core::InputError("auralize", "give -o WET.wav, --play, or both");
    if (!o->play && !o->playback.device.empty()) throw core::InputError("--device", "only applies with --play");
    o->playback.ir = o->ir;
    o->playback.in = o->in;
    o->playback.gain_db = o->gain_db;
    if (o->out.empty()) return playAuralization(o->playback);
    if (o->play) requireOutputDevice(o->playback.device);  // before writing: no file and then an error
    core::requireFinite("--gain", o->gain_db);
    checkOutputPath(*o);
    audio::AudioReader dry(o->in);
    const audio::AudioBuffer ir = audio::readAudio(o->ir);
    if (ir.sample_rate_hz != dry.sampleRateHz())
      throw core::InputError(o->in, "sample rate " + std::to_string(static_cast<long>(dry.sampleRateHz())) +
                                        " Hz differs from the impulse response's " +
                                        std::to_string(static_cast<long>(ir.sample_rate_hz)) + " Hz (" + o->ir +
                                        "); resample one of them first");
    std::vector<std::vector<float>> ir_channels;
    for (int c = 0; c < ir.channels; ++c) {
      const std::vector<double> h = ir.channel(c);
      ir_channels.emplace_back(h.begin(), h.end());
    }
    const int block = blockFor(ir.frames());
    dsp::MultichannelConvolver conv;
    conv.init(block, ir_channels, dry.channels());
    const int rate = static_cast<int>(dry.sampleRateHz());
    const double gain = std::pow(10.0, o->gain_db / 20.0);
    double peak = 0.0;
    double applied_db = o->gain_db;
    long frames = 0;
    if (!o->normalize) {
      audio::WavWriter writer(o->out, rate, conv.outputChannels());
      peak = convolveInto(dry, conv, block, static_cast<float>(gain), writer);
      frames = writer.framesWritten();
      writer.commit();
    } else {
      RemoveOnExit unscaled{o->out + ".unscaled.tmp." + std::to_string(::getpid())};
      double raw_peak = 0.0;
      {
        audio::WavWriter pass1(unscaled.path, rate, conv.outputChannels());
        raw_peak = convolveInto(dry, conv, block, 1.0f, pass1);
        pass1.commit();
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
    std::cout << "wrote " << o->out << ": " << frames << " frames x " << conv.outputChannels() << " channel"
              << (conv.outputChannels() > 1 ? "s" : "") << " at " << rate << " Hz (input " << dry.frames()
              << " + IR " << ir.frames() << " - 1), gain " << applied_db << " dB, peak " << dbfs(peak) << " dBFS\n";
    return o->play ? playAuralization(o->playback) : 0;
  };
}

}  // namespace diffray::cli
