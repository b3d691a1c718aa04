#pragma once
// Frequency bands: octave bands 63 Hz–8 kHz by default, third-octave bands as an option.
// Centres are the exact base-10 ones of IEC 61260-1 (1000·10^(3k/10) for third octaves, every third of
// them for octaves) and band edges are centre·10^(±0.15) (octave) or 10^(±0.05) (third octave); labels and
// JSON keys use the nominal values ("63", "125", …, "8000"). A ray carries one energy per band at once in
// a BandArray, a fixed-capacity array so that it lives on the stack. Plain value types; thread-safe to share.
#include <array>
#include <string>
#include <vector>

namespace diffray::core {

inline constexpr int kMaxBands = 32;

/// One energy (or coefficient) per band; only the first Bands::size() entries are meaningful.
using BandArray = std::array<double, kMaxBands>;

class Bands {
 public:
  /// Octave bands whose nominal centres lie in [lo_hz, hi_hz] (default 63 Hz – 8 kHz: 8 bands).
  static Bands octave(double lo_hz = 63.0, double hi_hz = 8000.0);
  /// Third-octave bands whose nominal centres lie in [lo_hz, hi_hz] (default 50 Hz – 10 kHz: 24 bands).
  static Bands thirdOctave(double lo_hz = 50.0, double hi_hz = 10000.0);

  int size() const { return static_cast<int>(centre_hz_.size()); }
  bool thirdOctaves() const { return third_; }
  double centreHz(int b) const { return centre_hz_[b]; }    ///< exact centre
  double nominalHz(int b) const { return nominal_hz_[b]; }  ///< 63, 125, …
  double lowerHz(int b) const { return lower_hz_[b]; }
  double upperHz(int b) const { return upper_hz_[b]; }
  /// The nominal centre as text, "63", "125", "1000", "8000": the key used in JSON outputs.
  std::string label(int b) const;
  /// Index of the band whose nominal centre is `nominal_hz` (within 1 %), or −1.
  int find(double nominal_hz) const;

  /// Bands from explicit tables (used by the factories above).
  static Bands fromTables(bool third, std::vector<double> centre, std::vector<double> nominal,
                          std::vector<double> lower, std::vector<double> upper);

 private:
  bool third_ = false;
  std::vector<double> centre_hz_, nominal_hz_, lower_hz_, upper_hz_;
};

/// A BandArray with every entry `value`.
inline BandArray bandFill(double value) {
  BandArray a;
  a.fill(value);
  return a;
}

}  // namespace diffray::core
