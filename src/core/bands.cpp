#include "diffray/core/bands.h"

#include <cmath>

#include "diffray/core/error.h"

namespace diffray::core {
namespace {

// IEC 61260-1 nominal third-octave centres from 10 Hz to 20 kHz (index k = −20 … 13 around 1 kHz).
constexpr double kNominal[] = {10,   12.5, 16,   20,   25,   31.5, 40,    50,    63,    80,    100,  125,
                               160,  200,  250,  315,  400,  500,  630,   800,   1000,  1250,  1600, 2000,
                               2500, 3150, 4000, 5000, 6300, 8000, 10000, 12500, 16000, 20000};
constexpr int kOneKilohertz = 20;  // index of 1000 in kNominal

Bands make(double lo_hz, double hi_hz, bool third) {
  requirePositive("bands: lowest centre", lo_hz);
  requirePositive("bands: highest centre", hi_hz);
  if (hi_hz < lo_hz) throw InputError("bands", "the highest centre is below the lowest");
  std::vector<double> centre, nominal, lower, upper;
  const double half = third ? 0.05 : 0.15;
  for (int i = 0; i < static_cast<int>(sizeof(kNominal) / sizeof(kNominal[0])); ++i) {
    const int k = i - kOneKilohertz;
    if (!third && k % 3 != 0) continue;
    if (kNominal[i] < lo_hz * 0.99 || kNominal[i] > hi_hz * 1.01) continue;
    const double c = 1000.0 * std::pow(10.0, 0.1 * k);
    centre.push_back(c);
    nominal.push_back(kNominal[i]);
    lower.push_back(c * std::pow(10.0, -half));
    upper.push_back(c * std::pow(10.0, half));
  }
  if (centre.empty()) throw InputError("bands", "no band centre lies in the range given");
  if (static_cast<int>(centre.size()) > kMaxBands)
    throw InputError("bands", "more than " + std::to_string(kMaxBands) + " bands");
  return Bands::fromTables(third, centre, nominal, lower, upper);
}

}  // namespace

Bands Bands::fromTables(bool third, std::vector<double> centre, std::vector<double> nominal,
                        std::vector<double> lower, std::vector<double> upper) {
  Bands b;
  b.third_ = third;
  b.centre_hz_ = std::move(centre);
  b.nominal_hz_ = std::move(nominal);
  b.lower_hz_ = std::move(lower);
  b.upper_hz_ = std::move(upper);
  return b;
}

Bands Bands::octave(double lo_hz, double hi_hz) { return make(lo_hz, hi_hz, false); }
Bands Bands::thirdOctave(double lo_hz, double hi_hz) { return make(lo_hz, hi_hz, true); }

std::string Bands::label(int b) const {
  const double n = nominal_hz_[b];
  if (n == std::floor(n)) return std::to_string(static_cast<long>(n));
  std::string s = std::to_string(n);
  while (!s.empty() && s.back() == '0') s.pop_back();
  return s;
}

int Bands::find(double nominal_hz) const {
  for (int b = 0; b < size(); ++b)
    if (std::abs(nominal_hz_[b] - nominal_hz) <= 0.01 * nominal_hz) return b;
  return -1;
}

}  // namespace diffray::core
