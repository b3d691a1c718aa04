// The SOFA reader (spatial/hrtf.h) on HRTF sets written in the test: CDL text made into SOFA (netCDF-4)
// files by ncgen (Debian's netcdf-bin), six measurements (±x, ±y, ±z) whose HRIRs are known pulses at known
// taps. Oracle: the stored HRIRs written out by hand. A 48 kHz set read at 48 kHz gives every HRIR back
// shifted by its Data.Delay (M × R and 1 × R, whole samples at the file's rate), less the common lead the
// reader drops, to one float rounding; read at 44.1 kHz, each pulse keeps its time in seconds within one
// sample and every HRIR the same energy. SOFA files that are valid netCDF but no two-ear HRTF set (another
// convention, three receivers, no Data.IR, no sampling rate, a negative or NaN delay) are refused in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/spatial/hrtf.h"
#include "temp_dir.h"

namespace diffray::spatial {
namespace {

constexpr int kM = 6;  // measurements: +x, −x, +y, −y, +z, −z
constexpr const char* kNoNcgen = "ncgen is not installed (Debian's netcdf-bin, tools/deps.sh): no SOFA fixtures";

bool haveNcgen() { return std::system("command -v ncgen >/dev/null 2>&1") == 0; }

// Where measurement m's HRIR at ear r (0 left, 1 right) starts in the file, before its delay: all distinct.
int onset(int m, int r) { return 40 + 2 * m + r; }

// Tap i of a pulse (zero outside it).
double tapOf(const std::vector<double>& pulse, int i) {
  return i >= 0 && i < static_cast<int>(pulse.size()) ? pulse[static_cast<std::size_t>(i)] : 0.0;
}

// A SimpleFreeFieldHRIR set with everything mysofa_check asks for (SOFA conventions and data type, room
// type, E = I = 1, C = 3, an emitter at the origin, receivers on the y axis, sources M × C), and the global
// attributes SOFA requires: libmysofa 1.3.1 cannot read a file with fewer than nine of them (it reports an
// unsupported format).
struct SofaText {
  std::string conventions = "SimpleFreeFieldHRIR";
  double rate_hz = 48000.0;
  int receivers = 2;
  int taps = 128;
  std::vector<double> pulse = {1.0, -0.5};  // each HRIR: this, from onset(m, r)
  std::string delay_dims;                  // "": no Data.Delay; "I, R" or "M, R"
  std::string delays;                      // Data.Delay's values as CDL text
  bool with_ir = true, with_rate = true;
};

std::string cdl(const SofaText& s) {
  std::ostringstream o;
  o << "netcdf fixture {\ndimensions:\n  M = " << kM << " ; R = " << s.receivers << " ; N = " << s.taps
    << " ; E = 1 ; C = 3 ; I = 1 ;\nvariables:\n";
  const auto cartesian = [&](const std::string& name, const std::string& dims) {
    o << "  double " << name << "(" << dims << ") ; " << name << ":Type = \"cartesian\" ; " << name
      << ":Units = \"metre\" ;\n";
  };
  cartesian("ListenerPosition", "I, C");
  cartesian("ListenerUp", "I, C");
  cartesian("ListenerView", "I, C");
  cartesian("ReceiverPosition", "R, C, I");
  cartesian("EmitterPosition", "E, C, I");
  o << "  double SourcePosition(M, C) ; SourcePosition:Type = \"spherical\" ;\n"
    << "    SourcePosition:Units = \"degree, degree, metre\" ;\n";
  if (s.with_ir) o << "  double Data.IR(M, R, N) ;\n";
  if (s.with_rate) o << "  double Data.SamplingRate(I) ; Data.SamplingRate:Units = \"hertz\" ;\n";
  if (!s.delay_dims.empty()) o << "  double Data.Delay(" << s.delay_dims << ") ;\n";
  o << "  :Conventions = \"SOFA\" ; :Version = \"1.0\" ; :SOFAConventions = \"" << s.conventions << "\" ;\n"
    << "  :SOFAConventionsVersion = \"1.0\" ; :APIName = \"diffray tests\" ; :APIVersion = \"1.0\" ;\n"
    << "  :DataType = \"FIR\" ; :RoomType = \"free field\" ; :Title = \"fixture\" ; :License = \"none\" ;\n"
    << "  :Organization = \"diffray\" ; :AuthorContact = \"none\" ;\n"
    << "  :DateCreated = \"-\" ; :DateModified = \"-\" ;\n"
    << "  :ListenerShortName = \"none\" ; :DatabaseName = \"none\" ;\n"
    << "data:\n  ListenerPosition = 0, 0, 0 ;\n  ListenerUp = 0, 0, 1 ;\n  ListenerView = 1, 0, 0 ;\n"
    << "  ReceiverPosition = 0, 0.09, 0, 0, -0.09, 0";
  for (int r = 2; r < s.receivers; ++r) o << ", 0, 0, 0.09";
  // azimuth (anticlockwise from +x), elevation, distance
  o << " ;\n  SourcePosition = 0, 0, 1.2, 180, 0, 1.2, 90, 0, 1.2, 270, 0, 1.2, 0, 90, 1.2, 0, -90, 1.2 ;\n"
    << "  EmitterPosition = 0, 0, 0 ;\n";
  if (s.with_ir) {
    o << "  Data.IR =";
    for (int m = 0; m < kM; ++m)
      for (int r = 0; r < s.receivers; ++r)
        for (int k = 0; k < s.taps; ++k) o << ((m + r + k) ? ", " : " ") << tapOf(s.pulse, k - onset(m, r % 2));
    o << " ;\n";
  }
  if (s.with_rate) o << "  Data.SamplingRate = " << s.rate_hz << " ;\n";
  if (!s.delay_dims.empty()) o << "  Data.Delay = " << s.delays << " ;\n";
  o << "}\n";
  return o.str();
}

// dir/NAME.sofa made from `s` by ncgen; empty when ncgen fails (its message goes to the test's output).
std::string writeSofa(const test::TempDir& dir, const std::string& name, const SofaText& s) {
  const std::string in = dir.file(name + ".cdl"), out = dir.file(name + ".sofa");
  std::ofstream(in) << cdl(s);
  const std::string command = "ncgen -k nc4 '" + in + "' -o '" + out + "'";
  return std::system(command.c_str()) == 0 ? out : std::string();
}

// Data.Delay of the M × R sets, in samples at 48 kHz; the longest is 7, the earliest delayed start
// onset(0, 0) + 0 = 40.
constexpr int kDelay[kM][2] = {{0, 3}, {1, 0}, {2, 5}, {7, 1}, {0, 0}, {4, 2}};

SofaText perMeasurementDelays(const std::vector<double>& pulse) {
  SofaText s;
  s.pulse = pulse;
  s.delay_dims = "M, R";
  for (int m = 0; m < kM; ++m)
    for (int r = 0; r < 2; ++r) s.delays += (m + r ? ", " : "") + std::to_string(kDelay[m][r]);
  return s;
}

// Measurement m, ear r of `h` against the stored pulse starting at `at` times `gain`, every other tap zero.
void expectPulseAt(const Hrtf& h, int m, int r, int at, const std::vector<double>& pulse, double gain, double tol,
                   double& worst) {
  for (int k = 0; k < h.taps(); ++k) {
    const double want = gain * tapOf(pulse, k - at);
    const double got = h.ear(m, r)[k];
    if (want == 0.0) {
      ASSERT_EQ(got, 0.0) << "measurement " << m << " ear " << r << " tap " << k;
    } else {
      ASSERT_NEAR(got, want, tol) << "measurement " << m << " ear " << r << " tap " << k;
      worst = std::max(worst, std::abs(got - want));
    }
  }
}

TEST(HrtfSofa, At48kHzPerMeasurementDelaysShiftEachHrir) {
  if (!haveNcgen()) GTEST_SKIP() << kNoNcgen;
  const test::TempDir dir("sofa_mr");
  const SofaText s = perMeasurementDelays({1.0, -0.5});
  const std::string path = writeSofa(dir, "mr", s);
  ASSERT_FALSE(path.empty());
  const Hrtf h = Hrtf::load(path, 48000.0);
  EXPECT_EQ(h.fileRateHz(), 48000.0);
  EXPECT_EQ(h.sampleRateHz(), 48000.0);
  ASSERT_EQ(h.directions(), kM);
  // The head frame: x forward, y left, z up; azimuth 90° is the left.
  const core::Vec3 axis[kM] = {core::Vec3(1, 0, 0), core::Vec3(-1, 0, 0), core::Vec3(0, 1, 0),
                               core::Vec3(0, -1, 0), core::Vec3(0, 0, 1),  core::Vec3(0, 0, -1)};
  for (int m = 0; m < kM; ++m) {
    EXPECT_NEAR((h.direction(m) - axis[m]).norm(), 0.0, 1e-6) << m;  // float degrees to radians
    EXPECT_EQ(h.nearest(axis[m] + core::Vec3(0.1, 0.1, 0.1)), m);
  }
  // Earliest start: measurement 0, left, tap 40 + delay 0: the reader keeps 8 samples before it, dropping 32.
  // The longest delay (7) lengthens every HRIR: 128 + 7 − 32 taps.
  const int dropped = 32;
  EXPECT_EQ(h.taps(), 128 + 7 - dropped);
  // Every HRIR holds the pulse (1, −0.5), energy 1.25: the diffuse-field gain is 1/√1.25. The taps are exact
  // in float and scaled by one float, so each differs from the ideal by that float's rounding, below
  // 2^−24 × 0.9 ≈ 5.4e-8 (half an ulp at 0.89).
  const double gain = 1.0 / std::sqrt(1.25);
  double worst = 0.0;
  for (int m = 0; m < kM; ++m)
    for (int r = 0; r < 2; ++r)
      expectPulseAt(h, m, r, onset(m, r) + kDelay[m][r] - dropped, s.pulse, gain, 5.4e-8, worst);
  std::cout << "[ measured ] M x R delays: largest tap error " << worst << "\n";
}

TEST(HrtfSofa, At48kHzPerEarDelaysShiftEveryHrirOfThatEar) {
  if (!haveNcgen()) GTEST_SKIP() << kNoNcgen;
  const test::TempDir dir("sofa_ir");
  SofaText s;
  s.delay_dims = "I, R";
  s.delays = "20, 23";
  const std::string path = writeSofa(dir, "ir", s);
  ASSERT_FALSE(path.empty());
  const Hrtf h = Hrtf::load(path, 48000.0);
  ASSERT_EQ(h.directions(), kM);
  // Earliest start: measurement 0, left, tap 40 + 20: 52 dropped, 8 kept; 128 + 23 − 52 taps.
  const int dropped = 52;
  EXPECT_EQ(h.taps(), 128 + 23 - dropped);
  const double gain = 1.0 / std::sqrt(1.25);  // as above
  double worst = 0.0;
  for (int m = 0; m < kM; ++m) {
    expectPulseAt(h, m, 0, onset(m, 0) + 20 - dropped, s.pulse, gain, 5.4e-8, worst);
    expectPulseAt(h, m, 1, onset(m, 1) + 23 - dropped, s.pulse, gain, 5.4e-8, worst);
  }
  std::cout << "[ measured ] 1 x R delays: largest tap error " << worst << "\n";
}

TEST(HrtfSofa, A48kHzSetReadAt44100HzKeepsEachPulsesTimeAndEnergy) {
  // The delays are samples at the file's rate (48 kHz): a pulse at tap t + d there lies at
  // (t + d) × 44100 / 48000 samples at 44.1 kHz. Each HRIR is a single unit pulse, band-limited by the
  // resampler: its largest sample is the one nearest the pulse's time (half a sample off at most), so the
  // peaks' offsets from measurement 0's left peak (the common lead the reader drops cancels) match within
  // one sample. Each HRIR is the same pulse moved, so each has the same energy, 1 after the diffuse-field
  // normalisation, but for the tails a buffer cuts: a band-limited pulse's samples fall off as 1/(π n), and
  // the reader keeps at least 8 samples before the first above 1 % of the peak (n ≈ 32) and 60 after the
  // last pulse, so each side loses at most Σ_{n>30} 1/(π n)² < 1/(30 π²) ≈ 0.34 %: within 1 % in all.
  if (!haveNcgen()) GTEST_SKIP() << kNoNcgen;
  const test::TempDir dir("sofa_rate");
  const std::string path = writeSofa(dir, "rate", perMeasurementDelays({1.0}));
  ASSERT_FALSE(path.empty());
  const Hrtf h = Hrtf::load(path, 44100.0);
  EXPECT_EQ(h.fileRateHz(), 48000.0);
  EXPECT_EQ(h.sampleRateHz(), 44100.0);
  ASSERT_EQ(h.directions(), kM);
  const auto peak = [&](int m, int r) {
    int best = 0;
    for (int k = 1; k < h.taps(); ++k)
      if (std::abs(h.ear(m, r)[k]) > std::abs(h.ear(m, r)[best])) best = k;
    return best;
  };
  const double ratio = 44100.0 / 48000.0;
  const int p0 = peak(0, 0);
  double worst_time = 0.0, worst_energy = 0.0;
  for (int m = 0; m < kM; ++m)
    for (int r = 0; r < 2; ++r) {
      const double want = (onset(m, r) + kDelay[m][r] - onset(0, 0) - kDelay[0][0]) * ratio;
      EXPECT_NEAR(peak(m, r) - p0, want, 1.0) << "measurement " << m << " ear " << r;
      worst_time = std::max(worst_time, std::abs(peak(m, r) - p0 - want));
      double energy = 0.0;
      for (int k = 0; k < h.taps(); ++k) energy += static_cast<double>(h.ear(m, r)[k]) * h.ear(m, r)[k];
      EXPECT_NEAR(energy, 1.0, 0.01) << "measurement " << m << " ear " << r;
      worst_energy = std::max(worst_energy, std::abs(energy - 1.0));
    }
  std::cout << "[ measured ] 48 -> 44.1 kHz: largest peak offset error " << worst_time
            << " samples, energy error " << worst_energy << "\n";
}

TEST(HrtfSofa, SofaFilesThatAreNoTwoEarHrtfSetRefusedInOneLine) {
  if (!haveNcgen()) GTEST_SKIP() << kNoNcgen;
  const test::TempDir dir("sofa_bad");
  const auto refuses = [&](const std::string& name, const SofaText& s, const std::string& words) {
    const std::string path = writeSofa(dir, name, s);
    ASSERT_FALSE(path.empty()) << name;
    try {
      Hrtf::load(path, 48000.0);
      ADD_FAILURE() << name << " was accepted";
    } catch (const core::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(words), std::string::npos) << what;
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  SofaText good;
  good.delay_dims = "I, R";
  good.delays = "0, 1";
  ASSERT_FALSE(writeSofa(dir, "good", good).empty());
  EXPECT_NO_THROW(Hrtf::load(dir.file("good.sofa"), 48000.0));  // the fixture itself is a valid set
  SofaText other = good;
  other.conventions = "GeneralFIR";
  refuses("other", other, "not an HRTF set");
  SofaText three = good;
  three.receivers = 3;
  three.delays = "0, 1, 2";
  refuses("three", three, "not an HRTF set");
  SofaText no_ir = good;
  no_ir.with_ir = false;
  refuses("no_ir", no_ir, "not a two-ear HRTF set");
  SofaText no_rate = good;
  no_rate.with_rate = false;
  refuses("no_rate", no_rate, "not an HRTF set");
  // Delays libmysofa's check lets through: a negative one would move taps before the HRIR's buffer.
  SofaText negative = good;
  negative.delays = "0, -3";
  refuses("negative", negative, "delays are out of range");
  SofaText nan = good;
  nan.delay_dims = "M, R";
  nan.delays = "0, 0, 0, 0, 0, NaN, 0, 0, 0, 0, 0, 0";
  refuses("nan", nan, "delays are out of range");
}

TEST(HrtfSofa, AFileLibmysofaReadsWithoutEndRefusedInOneLine) {
  // tests/data/sofa_endless_read.sofa: tests/fuzz/sofa_seed.cdl's set with bytes shuffled by fuzz_sofa, on
  // which libmysofa 1.3.1's reader does not return (in this process it ran past 60 s). The reader's child
  // process is given 2 s plus 1 s per MB: refused in one line, naming the file.
  const std::string path = std::string(DIFFRAY_SOURCE_DIR) + "/tests/data/sofa_endless_read.sofa";
  try {
    Hrtf::load(path, 48000.0);
    ADD_FAILURE() << "accepted";
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("libmysofa did not finish reading it in 2 s"), std::string::npos) << what;
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace diffray::spatial
