#include "diffray/spatial/hrtf.h"

#include <mysofa.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include <tbb/parallel_for.h>

#include "diffray/core/error.h"
#include "diffray/dsp/resample.h"

namespace diffray::spatial {

namespace {

struct SofaFree {
  void operator()(MYSOFA_HRTF* h) const { mysofa_free(h); }
};

// libmysofa 1.3.1 can loop without end on a malformed file (its HDF5 reader seeking round a cycle), or
// crash on one. So the file is read once in a child process first, given 2 s plus 1 s per MB (the KEMAR
// set, 1.2 MB, takes about 0.1 s): "" when that read finished, otherwise why the file is refused. Where
// no child can be made, the file is read in this process alone.
std::string childRead(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  const double limit_s = 2.0 + (ec ? 0.0 : static_cast<double>(bytes) / 1e6);
  const pid_t pid = ::fork();
  if (pid < 0) return "";
  if (pid == 0) {  // the child: read, then leave without running this process's exit handlers
    int err = 0;
    mysofa_load(path.c_str(), &err);
    ::_exit(0);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) return "";
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      char limit[32];
      std::snprintf(limit, sizeof limit, "%.0f", limit_s);
      return std::string("libmysofa did not finish reading it in ") + limit + " s (a malformed file)";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (WIFSIGNALED(status)) return "libmysofa crashed reading it (signal " + std::to_string(WTERMSIG(status)) + ")";
  return "";
}

}  // namespace

Hrtf Hrtf::load(const std::string& path_in, double sample_rate_hz) {
  core::requirePositive("HRTF: sample rate", sample_rate_hz);
  Hrtf h;
  h.path_ = path_in.empty() ? defaultPath() : path_in;
  h.rate_hz_ = sample_rate_hz;
  {
    std::ifstream probe(h.path_, std::ios::binary);
    if (!probe) {
      if (path_in.empty())
        throw core::InputError("--hrtf", "the default HRTF set " + h.path_ +
                                             " is missing: install Debian's libmysofa1 (tools/deps.sh), or give --hrtf FILE.sofa");
      throw core::InputError(h.path_, "cannot read the HRTF file");
    }
  }
  if (const std::string why = childRead(h.path_); !why.empty()) throw core::InputError(h.path_, "not a SOFA file: " + why);
  int err = 0;
  std::unique_ptr<MYSOFA_HRTF, SofaFree> sofa(mysofa_load(h.path_.c_str(), &err));
  if (!sofa || err != MYSOFA_OK)
    throw core::InputError(h.path_, "not a SOFA file libmysofa can read (libmysofa error " + std::to_string(err) + ")");
  err = mysofa_check(sofa.get());
  if (err != MYSOFA_OK)
    throw core::InputError(h.path_, "not an HRTF set (SOFA SimpleFreeFieldHRIR, two ears): libmysofa's check "
                                    "fails with error " + std::to_string(err));
  const MYSOFA_HRTF& s = *sofa;
  if (s.R != 2 || s.N == 0 || s.M == 0 || s.DataIR.elements != s.M * s.R * s.N || s.DataSamplingRate.elements < 1 ||
      s.SourcePosition.elements != s.M * s.C)
    throw core::InputError(h.path_, "not a two-ear HRTF set: " + std::to_string(s.R) + " receivers, " +
                                        std::to_string(s.M) + " measurements of " + std::to_string(s.N) + " taps");
  h.file_rate_hz_ = s.DataSamplingRate.values[0];
  if (!(h.file_rate_hz_ > 0.0) || !std::isfinite(h.file_rate_hz_))
    throw core::InputError(h.path_, "the HRTF set's sampling rate is not a positive number");
  mysofa_tocartesian(sofa.get());
  // Per-measurement (M × R) or per-receiver (R) delays, in samples at the file's rate: whole samples ahead.
  // Each must be a number in [0, 100000] (a negative one would shift taps before the buffer).
  const auto stored = [&](unsigned m, unsigned r) -> double {
    if (s.DataDelay.elements == s.M * s.R) return s.DataDelay.values[m * s.R + r];
    if (s.DataDelay.elements == s.R) return s.DataDelay.values[r];
    return 0.0;
  };
  const auto delay = [&](unsigned m, unsigned r) { return std::lround(stored(m, r)); };
  long longest = 0;
  for (unsigned m = 0; m < s.M; ++m)
    for (unsigned r = 0; r < 2; ++r) {
      if (!(stored(m, r) >= 0.0 && stored(m, r) <= 100000.0))
        throw core::InputError(h.path_, "the HRTF set's delays are out of range (each a number of samples in [0, 100000])");
      longest = std::max(longest, delay(m, r));
    }
  const std::size_t n_file = s.N + static_cast<std::size_t>(longest);
  std::vector<std::vector<float>> irs;  // per measurement: interleaved left, right at the file's rate
  for (unsigned m = 0; m < s.M; ++m) {
    const float* p = &s.SourcePosition.values[m * s.C];
    const core::Vec3 d(p[0], p[1], p[2]);
    if (!(d.norm() > 0.0) || !std::isfinite(d.norm()))
      throw core::InputError(h.path_, "measurement " + std::to_string(m) + " has no source direction");
    h.dirs_.push_back(d.normalized());
    std::vector<float> ir(2 * n_file, 0.0f);
    for (unsigned r = 0; r < 2; ++r) {
      const long shift = delay(m, r);
      for (unsigned k = 0; k < s.N; ++k) {
        const float v = s.DataIR.values[(m * s.R + r) * s.N + k];
        if (!std::isfinite(v)) throw core::InputError(h.path_, "an HRIR holds a value that is not a number");
        ir[2 * (k + static_cast<std::size_t>(shift)) + r] = v;
      }
    }
    irs.push_back(std::move(ir));
  }
  // Resampled in groups of kResampleGroup measurements, each group one converter of 2·group channels (the
  // groups in parallel): libsamplerate computes the filter's taps once per output sample for all the channels
  // of a converter and then each channel as it would alone, so a group costs about a third less than its
  // measurements one by one and gives the same samples.
  constexpr std::size_t kResampleGroup = 4;
  if (h.file_rate_hz_ != sample_rate_hz)
    tbb::parallel_for(std::size_t{0}, (irs.size() + kResampleGroup - 1) / kResampleGroup, [&](std::size_t group) {
      const std::size_t first = group * kResampleGroup, count = std::min(kResampleGroup, irs.size() - first);
      std::vector<float> joined(2 * count * n_file);  // [frame][measurement][ear]
      for (std::size_t k = 0; k < n_file; ++k)
        for (std::size_t m = 0; m < count; ++m)
          for (std::size_t r = 0; r < 2; ++r) joined[(k * count + m) * 2 + r] = irs[first + m][2 * k + r];
      const std::vector<float> out = dsp::resampleImpulseResponse(joined, static_cast<int>(2 * count), h.file_rate_hz_, sample_rate_hz);
      const std::size_t frames = out.size() / (2 * count);
      for (std::size_t m = 0; m < count; ++m) {
        std::vector<float>& ir = irs[first + m];
        ir.assign(2 * frames, 0.0f);
        for (std::size_t k = 0; k < frames; ++k)
          for (std::size_t r = 0; r < 2; ++r) ir[2 * k + r] = out[(k * count + m) * 2 + r];
      }
    });
  // The delay common to every HRIR (the measurement's distance, the converter's latency) is dropped, up to
  // 8 samples kept ahead of the earliest onset (a tap above 1 % of its HRIR's peak), so that a binaural
  // response starts where W does.
  std::size_t lead = irs.front().size() / 2;
  for (const auto& ir : irs) {
    float peak = 0.0f;
    for (float v : ir) peak = std::max(peak, std::abs(v));
    for (std::size_t k = 0; k < ir.size() / 2; ++k)
      if (std::abs(ir[2 * k]) > 0.01f * peak || std::abs(ir[2 * k + 1]) > 0.01f * peak) {
        lead = std::min(lead, k);
        break;
      }
  }
  const std::size_t trim = lead > 8 ? lead - 8 : 0;
  for (auto& ir : irs) ir.erase(ir.begin(), ir.begin() + static_cast<long>(2 * trim));
  h.taps_ = static_cast<int>(irs.front().size() / 2);
  // Diffuse-field normalisation: the mean over directions of the ears' mean energy is 1.
  double energy = 0.0;
  for (const auto& ir : irs)
    for (float v : ir) energy += static_cast<double>(v) * v;
  energy /= 2.0 * static_cast<double>(irs.size());
  if (!(energy > 0.0)) throw core::InputError(h.path_, "every HRIR of the set is silent");
  const auto scale = static_cast<float>(1.0 / std::sqrt(energy));
  h.taps_data_.reserve(irs.size() * 2 * static_cast<std::size_t>(h.taps_));
  for (const auto& ir : irs)
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < h.taps_; ++k) h.taps_data_.push_back(ir[2 * static_cast<std::size_t>(k) + side] * scale);
  h.index();
  return h;
}

namespace {

constexpr int kAzCells = 180, kElCells = 90;  // 2° cells

int cellOf(const core::Vec3& d) {
  const double az = std::atan2(d.y(), d.x()), el = std::asin(std::max(-1.0, std::min(1.0, d.z() / d.norm())));
  const int a = std::min(kAzCells - 1, std::max(0, static_cast<int>((az + core::kPi) / core::kTwoPi * kAzCells)));
  const int e = std::min(kElCells - 1, std::max(0, static_cast<int>((el + 0.5 * core::kPi) / core::kPi * kElCells)));
  return e * kAzCells + a;
}

}  // namespace

void Hrtf::index() {
  const double radius = 1.5 * core::kPi / 180.0;  // a 2° × 2° cell's angular radius is at most √2°
  // Each elevation row's cells in parallel (their candidates and counts), then joined in cell order.
  std::vector<std::vector<int>> row_candidates(kElCells), row_counts(kElCells);
  // The angles are compared through their cosines (acos is decreasing), acos taken only for the largest
  // cosine and for a cosine within 1e-12 of the threshold's, where rounding could decide: the same
  // candidates as acos of every cosine, at one acos per cell instead of one per measurement.
  tbb::parallel_for(0, kElCells, [&](int e) {
    std::vector<double> cosine(dirs_.size());
    for (int a = 0; a < kAzCells; ++a) {
      const double az = -core::kPi + (a + 0.5) * core::kTwoPi / kAzCells, el = -0.5 * core::kPi + (e + 0.5) * core::kPi / kElCells;
      const core::Vec3 c(std::cos(az) * std::cos(el), std::sin(az) * std::cos(el), std::sin(el));
      double largest = -1.0;
      for (std::size_t i = 0; i < dirs_.size(); ++i) {
        cosine[i] = std::max(-1.0, std::min(1.0, dirs_[i].dot(c)));
        largest = std::max(largest, cosine[i]);
      }
      const double threshold = std::acos(largest) + 2.0 * radius + 1e-9;
      const double threshold_cos = std::cos(threshold);
      const std::size_t before = row_candidates[e].size();
      for (std::size_t i = 0; i < dirs_.size(); ++i) {
        const bool candidate = threshold >= core::kPi ? true
                               : std::abs(cosine[i] - threshold_cos) > 1e-12 ? cosine[i] > threshold_cos
                                                                              : std::acos(cosine[i]) <= threshold;
        if (candidate) row_candidates[e].push_back(static_cast<int>(i));
      }
      row_counts[e].push_back(static_cast<int>(row_candidates[e].size() - before));
    }
  });
  cell_start_.assign(1, 0);
  candidates_.clear();
  for (int e = 0; e < kElCells; ++e) {
    candidates_.insert(candidates_.end(), row_candidates[e].begin(), row_candidates[e].end());
    for (int count : row_counts[e]) cell_start_.push_back(cell_start_.back() + count);
  }
}

int Hrtf::nearest(const core::Vec3& d) const {
  const int cell = cellOf(d);
  int best = candidates_[static_cast<std::size_t>(cell_start_[static_cast<std::size_t>(cell)])];
  double best_cos = -2.0;
  for (int k = cell_start_[static_cast<std::size_t>(cell)]; k < cell_start_[static_cast<std::size_t>(cell) + 1]; ++k) {
    const int i = candidates_[static_cast<std::size_t>(k)];
    const double c = dirs_[static_cast<std::size_t>(i)].dot(d);
    if (c > best_cos) best_cos = c, best = i;
  }
  return best;
}

}  // namespace diffray::spatial
