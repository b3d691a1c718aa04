// `diffray spectrogram IN.wav -o OUT.png [--window N] [--hop N] [--channel C] [--mark T:LABEL]…`: the spectrogram of any audio
// file libsndfile reads (dsp/spectrogram.h: Hann window, dB re a full-scale sine) drawn as a PNG with a log
// frequency axis from 50 Hz to fs/2 (cli/spectrogram_plot.h). One channel (--channel, from 1) or, by
// default, the mean of all channels. The file is read block by block; only the analysed channel is kept.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include "diffray/audio/wav.h"
#include "diffray/cli/commands.h"
#include "diffray/cli/spectrogram_plot.h"
#include "diffray/core/error.h"
#include "diffray/dsp/spectrogram.h"

namespace diffray::cli {

namespace {

struct SpectrogramOptions {
  std::string in;
  std::string out;
  int window = 2048;
  int hop = 0;  ///< 0: window/4
  int channel = 0;  ///< 0: the mean of all channels
  double range_db = 90.0;
  std::string title;
  std::vector<std::string> marks;  ///< TIME[:LABEL]
};

// Frames kept for the plot (ten times its columns): longer inputs keep, per bin, the loudest of each run
// of frames (dsp::spectrogramPeaks), so memory stays at kMaxFrames × bins whatever the file's length while
// the hop stays window/4 (a hop of more than the window would step over clicks at the Hann window's zeros).
constexpr long kMaxFrames = 8000;

void checkOutputPath(const SpectrogramOptions& o) {
  namespace fs = std::filesystem;
  checkOutputFile(o.out, ".png");
  std::error_code ec;
  if (fs::equivalent(o.out, o.in, ec)) throw core::InputError(o.out, "would overwrite the input");
}

/// "1.5:START" → {1.5, "START"}; "2" → {2, "2 s"}. Throws core::InputError naming --mark.
TimeMarker parseMark(const std::string& text) {
  const size_t colon = text.find(':');
  const std::string time = text.substr(0, colon);
  TimeMarker m;
  if (!core::parseDecimal(time, m.time_s) || !std::isfinite(m.time_s))
    throw core::InputError("--mark", "expected TIME[:LABEL] with TIME in seconds, got \"" + text + "\"");
  m.label = colon == std::string::npos ? time + " s" : text.substr(colon + 1);
  return m;
}

}  // namespace

Runner addSpectrogramCommand(CLI::App& app, CommonOptions& /*common*/) {
  auto o = std::make_shared<SpectrogramOptions>();
  CLI::App* sub = app.add_subcommand(
      "spectrogram", "Draw the spectrogram of an audio file (Hann-windowed FFT, dB, log frequency axis) as a PNG "
                     "(needs gnuplot).");
  sub->add_option("file", o->in, "audio file (WAV, FLAC, AIFF, ...)")->check(inputPathValidator())->required();
  sub->add_option("-o,--output", o->out, "output .png")->check(outputPathValidator())->required();
  sub->add_option("--window", o->window, "FFT frame length in samples (even, 8 - 1048576)")
      ->transform(wholeNumberValidator())
      ->capture_default_str();
  sub->add_option("--hop", o->hop, "frame step in samples (default: window/4; long files keep the loudest of "
                                   "each run of frames, at most 8000 runs)")
      ->transform(wholeNumberValidator());
  sub->add_option("--channel", o->channel, "channel to analyse, from 1 (default: the mean of all channels)")
      ->transform(wholeNumberValidator());
  sub->add_option("--range", o->range_db, "dB shown below the loudest pixel")->capture_default_str();
  sub->add_option("--title", o->title, "plot title (default: the file name)");
  sub->add_option("--mark", o->marks, "TIME[:LABEL]: a dashed vertical line at TIME seconds (repeatable), "
                                      "e.g. --mark 1.5:START --mark 3:END");
  return [o]() {
    checkOutputPath(*o);
    std::vector<TimeMarker> marks;
    for (const std::string& text : o->marks) marks.push_back(parseMark(text));
    if (o->hop < 0) throw core::InputError("--hop", "must be at least 1, got " + std::to_string(o->hop));
    core::requirePositive("--range", o->range_db);
    audio::AudioReader reader(o->in);
    warnOf(reader.warning());
    SpectrogramPlotOptions plot;
    // The frequency axis runs from min_freq_hz up to fs/2: a file sampled at 2 × min_freq_hz or less has
    // nothing to draw. Its sample rate is the cause, not -o (where writeSpectrogramPlot would put it).
    if (!(reader.sampleRateHz() > 2.0 * plot.min_freq_hz))
      throw core::InputError(o->in, "sample rate " + std::to_string(static_cast<long>(reader.sampleRateHz())) +
                                        " Hz: the spectrogram's frequency axis starts at " +
                                        std::to_string(static_cast<int>(plot.min_freq_hz)) +
                                        " Hz, which needs a sample rate above " +
                                        std::to_string(static_cast<int>(2.0 * plot.min_freq_hz)) + " Hz");
    if (o->channel < 0 || o->channel > reader.channels())
      throw core::InputError("--channel", "must lie between 1 and " + std::to_string(reader.channels()) + " (" +
                                              o->in + " has " + std::to_string(reader.channels()) + "), got " +
                                              std::to_string(o->channel));
    const std::vector<float> x = audio::readChannel(reader, o->channel - 1);
    const auto n = static_cast<long>(x.size());
    const int hop = o->hop > 0 ? o->hop : std::max(1, o->window / 4);
    const dsp::Spectrogram s = dsp::spectrogramPeaks(x.data(), n, reader.sampleRateHz(), o->window, hop, kMaxFrames);
    plot.title = o->title.empty() ? std::filesystem::path(o->in).filename().string() +
                                        (o->channel > 0 ? ", channel " + std::to_string(o->channel) : std::string())
                                  : o->title;
    plot.range_db = o->range_db;
    plot.markers = marks;
    plot.option = "-o";
    writeSpectrogramPlot(o->out, s, plot);
    const long frames = dsp::frameCount(n, o->window, hop);
    std::cout << "wrote " << o->out << ": " << frames << " frames of " << o->window << " samples every " << hop;
    if (s.frames() < frames) std::cout << ", the loudest of each " << s.hop / hop << " kept";
    std::cout << " (" << n << " samples at " << reader.sampleRateHz() << " Hz)\n";
    return 0;
  };
}

}  // namespace diffray::cli
