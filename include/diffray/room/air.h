#pragma once
// Sound in air: the speed of sound and the pure-tone atmospheric absorption of
// ISO 9613-1:1993, eq. (3)–(5), with the molar concentration of water vapour from the relative humidity by
// the saturation-pressure formula of its Annex B (eq. B.1–B.3). Units: Hz, °C, %, kPa in (room::Air);
// dB/m for the standard's attenuation coefficient α; 1/m for the ENERGY attenuation coefficient m that the
// tracer applies (energy ∝ e^{−m·d}, m = α·ln10/10). Every function checks the Air it is given (ranges
// below) and throws core::InputError naming the field. Pure functions; thread-safe.
#include "diffray/core/bands.h"
#include "diffray/room/room.h"

namespace diffray::room {

/// Throws core::InputError naming the field unless temperature is in [−20, 50] °C (the range of
/// ISO 9613-1's tables and of its fit), relative humidity in [0, 100] % and pressure in [50, 200] kPa (the
/// range the scene file accepts, rooms/README.md).
void checkAir(const Air& air);

/// Molar concentration of water vapour h in % (ISO 9613-1 Annex B, eq. B.1 with B.2–B.3).
double waterVapourPercent(const Air& air);

/// Pure-tone attenuation coefficient α in dB/m at `freq_hz` (> 0), ISO 9613-1 eq. (5). The standard
/// states ±10 % accuracy for 50 Hz–10 kHz, −20…50 °C, 10…100 % RH (and h 0.05…5 %); outside it the same
/// formula is used.
double airAbsorptionDbPerM(double freq_hz, const Air& air);

/// The energy attenuation coefficient m = α·ln10/10 in 1/m of each band, α taken at the band's exact
/// centre frequency (ISO 9613-1 §6.4: the pure-tone value at the exact midband frequency stands for the
/// band). Entries past bands.size() are 0.
core::BandArray airAttenuationPerM(const Air& air, const core::Bands& bands);

/// Speed of sound in m/s: core::speedOfSound(air.temperature_c), after checkAir.
double speedOfSound(const Air& air);

}  // namespace diffray::room
