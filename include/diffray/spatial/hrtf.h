#pragma once
// A head-related impulse response set read from a SOFA file (AES69-2015, convention SimpleFreeFieldHRIR:
// one HRIR pair per measured source direction) with libmysofa, for binaural impulse responses.
//
// Contract. load() reads the file, checks it is an HRTF set (libmysofa's mysofa_check: the SOFA conventions,
// two receivers, a cartesian or spherical source grid), applies its per-measurement delays (Data.Delay, M × R
// or 1 × R: samples at the file's rate, rounded to whole ones), resamples every HRIR to the requested rate as
// a filter (dsp::resampleImpulseResponse, libsamplerate) when the file's rate differs, drops the delay common
// to all HRIRs (up to 8 samples before the earliest onset), and normalises the set to the diffuse field: the
// mean over the measured directions of the two ears' mean energy Σh² is 1, so a diffuse field heard through
// it keeps its energy per ear on average (the grid's directions weighted alike). Directions are unit vectors
// in the head frame SOFA uses, x forward, y left, z up (the frame of diffray's listeners); nearest() picks
// the measured direction of largest cosine (no interpolation: measured sets are a few degrees apart, and
// interpolating HRIRs in time smears their interaural delay), found exactly through a 2° azimuth × elevation
// table holding, per cell, every measurement that can be nearest to a direction in it (those within the angle
// of the one nearest the cell's centre plus twice the cell's angular radius, by the triangle inequality).
// Units: the HRIRs are dimensionless filter taps at sampleRateHz(). Thread-safety: immutable after load();
// share freely. load() resamples the measurements and builds the table on TBB's pool, each measurement and
// each cell alone (the same set for any thread count).
#include <string>
#include <vector>

#include "diffray/core/math.h"

namespace diffray::spatial {

class Hrtf {
 public:
  /// Where Debian's libmysofa1 installs the MIT KEMAR set (normal pinna), the default set.
  static const char* defaultPath() { return "/usr/share/libmysofa/MIT_KEMAR_normal_pinna.sofa"; }

  /// Reads `path` (empty: defaultPath()) for use at `sample_rate_hz`. Throws core::InputError naming the
  /// file, one line, for a missing or unreadable file, a file libmysofa cannot read as SOFA, a SOFA file
  /// that is no two-ear HRTF set, or one with a delay that is negative, above 100000 samples or not a number.
  static Hrtf load(const std::string& path, double sample_rate_hz);

  const std::string& path() const { return path_; }
  double fileRateHz() const { return file_rate_hz_; }
  double sampleRateHz() const { return rate_hz_; }
  int taps() const { return taps_; }
  int directions() const { return static_cast<int>(dirs_.size()); }
  const core::Vec3& direction(int i) const { return dirs_[static_cast<std::size_t>(i)]; }
  /// The measured direction with the largest cosine to `d` (any non-zero vector).
  int nearest(const core::Vec3& d) const;
  /// The HRIR of direction i at ear 0 (left) or 1 (right): taps() values.
  const float* ear(int i, int side) const {
    return &taps_data_[(static_cast<std::size_t>(i) * 2 + static_cast<std::size_t>(side)) * static_cast<std::size_t>(taps_)];
  }

 private:
  std::string path_;
  double file_rate_hz_ = 0.0, rate_hz_ = 0.0;
  int taps_ = 0;
  std::vector<core::Vec3> dirs_;
  std::vector<float> taps_data_;  ///< [direction][ear][tap]
  std::vector<int> cell_start_;   ///< [elevation cell × azimuth cell + 1]: where its candidates start
  std::vector<int> candidates_;   ///< the cells' candidate measurements, one run per cell
  void index();
};

}  // namespace diffray::spatial
