// Atmospheric absorption per ISO 9613-1:1993. Symbols as in the standard.
#include "diffray/room/air.h"

#include <cmath>
#include <sstream>
#include <string>

#include "diffray/core/error.h"
#include "diffray/core/math.h"

namespace diffray::room {
namespace {

constexpr double kReferencePressureKpa = 101.325;  // p_r
constexpr double kReferenceTemperatureK = 293.15;  // T_0 (20 °C)
constexpr double kTriplePointK = 273.16;           // T_01, triple-point isotherm of water (Annex B)
constexpr double kCelsiusToKelvin = 273.15;

void requireWithin(const std::string& field, double value, double lo, double hi, const char* unit) {
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    std::ostringstream s;
    s << "must be within " << lo << " … " << hi << " " << unit << ", got " << value;
    throw core::InputError(field, s.str());
  }
}

}  // namespace

void checkAir(const Air& air) {
  requireWithin("air.temperature", air.temperature_c, -20.0, 50.0, "°C");
  requireWithin("air.humidity", air.humidity_percent, 0.0, 100.0, "%");
  // ISO 9613-1 states its accuracy for pressures below 200 kPa; the scene file accepts the same range.
  requireWithin("air.pressure", air.pressure_kpa, 50.0, 200.0, "kPa");
  if (air.speed_of_sound_m_s != 0.0) requireWithin("air.speed_of_sound", air.speed_of_sound_m_s, 250.0, 450.0, "m/s");
}

double waterVapourPercent(const Air& air) {
  checkAir(air);
  const double t_k = air.temperature_c + kCelsiusToKelvin;
  // Eq. (B.3): C = −6.8346 (T01/T)^1.261 + 4.6151; (B.2): p_sat/p_r = 10^C; (B.1): h = h_r (p_sat/p_r)/(p_a/p_r).
  const double c = -6.8346 * std::pow(kTriplePointK / t_k, 1.261) + 4.6151;
  return air.humidity_percent * std::pow(10.0, c) / (air.pressure_kpa / kReferencePressureKpa);
}

double airAbsorptionDbPerM(double freq_hz, const Air& air) {
  core::requirePositive("air absorption: frequency", freq_hz);
  const double h = waterVapourPercent(air);  // checks `air`
  const double t_k = air.temperature_c + kCelsiusToKelvin;
  const double t_rel = t_k / kReferenceTemperatureK;  // T/T0
  const double p_rel = air.pressure_kpa / kReferencePressureKpa;  // p_a/p_r
  // Eq. (3), (4): relaxation frequencies of oxygen and nitrogen, Hz.
  const double fr_o = p_rel * (24.0 + 4.04e4 * h * (0.02 + h) / (0.391 + h));
  const double fr_n = p_rel / std::sqrt(t_rel) * (9.0 + 280.0 * h * std::exp(-4.170 * (std::cbrt(1.0 / t_rel) - 1.0)));
  // Eq. (5): classical + rotational term, then the two vibrational relaxations.
  const double f2 = freq_hz * freq_hz;
  const double classical = 1.84e-11 / p_rel * std::sqrt(t_rel);
  const double relax = std::pow(t_rel, -2.5) * (0.01275 * std::exp(-2239.1 / t_k) / (fr_o + f2 / fr_o) +
                                               0.1068 * std::exp(-3352.0 / t_k) / (fr_n + f2 / fr_n));
  return 8.686 * f2 * (classical + relax);
}

core::BandArray airAttenuationPerM(const Air& air, const core::Bands& bands) {
  core::BandArray m = core::bandFill(0.0);
  const double db_to_neper_energy = std::log(10.0) / 10.0;  // 10^{−αd/10} = e^{−(α ln10/10) d}
  for (int b = 0; b < bands.size(); ++b) m[b] = airAbsorptionDbPerM(bands.centreHz(b), air) * db_to_neper_energy;
  return m;
}

double speedOfSound(const Air& air) {
  checkAir(air);
  return air.speed_of_sound_m_s > 0.0 ? air.speed_of_sound_m_s : core::speedOfSound(air.temperature_c);
}

}  // namespace diffray::room
