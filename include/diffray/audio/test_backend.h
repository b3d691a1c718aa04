#pragma once
// The test backend: drives audio::playbackCallback (the very function PortAudio calls) from an ordinary
// thread, without hardware, with a fixed buffer size, until the renderer finishes. It stands in for a
// sound card's clock in two ways a test needs: it may wait between callbacks until the ring holds a
// callback's worth of dry frames (wait_for_input; the callback itself never waits, so the output is
// deterministic), and it calls optional hooks right before and after each callback on the callback thread
// (the allocation test sets a thread-local flag there; the bench times the callback).
// Thread-safety: runTestBackend() blocks the calling thread until its callback thread has finished.
#include <vector>

#include "diffray/audio/playback.h"

namespace diffray::audio {

struct TestBackendOptions {
  long frames_per_callback = 256;
  bool wait_for_input = true;  ///< between callbacks, wait for a full callback's worth of input (or its end)
  long max_callbacks = -1;     ///< stop after this many callbacks (−1: when the renderer finishes)
  bool keep_output = true;     ///< collect the output (interleaved)
  bool time_callbacks = false; ///< record each callback's wall time in seconds
  void (*before_callback)(void* data) = nullptr;  ///< called on the callback thread before each callback
  void (*after_callback)(void* data) = nullptr;   ///< … and after it
  void* hook_data = nullptr;
};

struct TestBackendRun {
  std::vector<float> output;             ///< every frame written, interleaved (keep_output)
  long callbacks = 0;
  std::vector<double> callback_seconds;  ///< one per callback (time_callbacks)
};

/// Runs `renderer` through playbackCallback on a new thread with fixed-size buffers; returns when the
/// callback has returned paComplete (or after max_callbacks).
TestBackendRun runTestBackend(PlaybackRenderer& renderer, const TestBackendOptions& options);

}  // namespace diffray::audio
