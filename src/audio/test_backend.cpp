#include "diffray/audio/test_backend.h"

#include <chrono>
#include <thread>

namespace diffray::audio {

TestBackendRun runTestBackend(PlaybackRenderer& renderer, const TestBackendOptions& options) {
  TestBackendRun run;
  std::thread callback_thread([&] {
    const long frames = options.frames_per_callback;
    std::vector<float> buffer(static_cast<size_t>(frames) * static_cast<size_t>(renderer.outputChannels()));
    for (;;) {
      if (options.max_callbacks >= 0 && run.callbacks >= options.max_callbacks) break;
      if (options.wait_for_input)
        while (!renderer.inputEnded() && renderer.bufferedFrames() < frames) std::this_thread::yield();
      if (options.before_callback) options.before_callback(options.hook_data);
      const auto t0 = std::chrono::steady_clock::now();
      const int status = playbackCallback(nullptr, buffer.data(), static_cast<unsigned long>(frames), nullptr, 0,
                                          &renderer);
      const auto t1 = std::chrono::steady_clock::now();
      if (options.after_callback) options.after_callback(options.hook_data);
      ++run.callbacks;
      if (options.time_callbacks) run.callback_seconds.push_back(std::chrono::duration<double>(t1 - t0).count());
      if (options.keep_output) run.output.insert(run.output.end(), buffer.begin(), buffer.end());
      if (status != 0) break;  // paComplete
    }
  });
  callback_thread.join();
  return run;
}

}  // namespace diffray::audio
