#pragma once
// Temporary files that an interrupted run must not leave behind. Outputs are written to temporaries and
// renamed into place (core/atomic_file.h, audio::WavWriter); if SIGINT, SIGTERM or SIGHUP ends the program
// first (Ctrl-C during a long auralize), the handler installed here deletes every registered temporary and
// then lets the signal take its default course. A TempRegistration registers a path for its lifetime;
// deleting a path that was already renamed or removed is harmless. Thread-safe; the handler only calls
// async-signal-safe functions (unlink, signal, raise) on a fixed table of lock-free slots.
#include <string>

namespace diffray::core {

class TempRegistration {
 public:
  /// Registers `path` (kept on an interrupt if the table of 256 slots is full, or the path too long).
  explicit TempRegistration(const std::string& path);
  ~TempRegistration();
  TempRegistration(const TempRegistration&) = delete;
  TempRegistration& operator=(const TempRegistration&) = delete;
  TempRegistration(TempRegistration&& other) noexcept : slot_(other.slot_) { other.slot_ = -1; }

 private:
  int slot_ = -1;
};

}  // namespace diffray::core
