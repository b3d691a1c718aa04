#pragma once
// Closed-form room-acoustics references (Kuttruff, "Room Acoustics"; ISO 3382-1) for the tests and the `diffray
// validate` cases free-field, diffuse-eyring and decay-metrics: Sabine and Eyring reverberation times, the receiver
// sphere's hit fraction and expected readings, free-field energy, the metrics of a pure exponential decay.
// The shoebox image-source sum is in reference/image_lattice.h.
//
// An ORACLE: it shares no code with the tracer, the room loader or the receivers; it takes plain numbers.
// Units: metres, m², m³, seconds, m/s; `air_m_per_m` is the ENERGY attenuation coefficient m in 1/m
// (energy ∝ e^{−m·d}; room::airAttenuationPerM gives it per band). Energies follow the receivers'
// convention: a 1 W omnidirectional source gives 1/r² at distance r (4π times the intensity in W/m²).
// Invalid arguments throw core::InputError. Pure functions; thread-safe.
#include <array>

namespace diffray::reference {

/// 24·ln10 = 55.262…: the 60 dB decay of a diffuse field whose energy density falls as e^{−c·(A/4V + m)·t}
/// takes T = (24 ln10 / c)·V/(A + 4mV). The textbook 0.161 is this constant at c ≈ 343 m/s.
inline constexpr double kSixtyDbConstant = 55.262042231857097;

/// Sabine, the textbook form: T = 0.161·V/(A + 4mV), A = Σ S_i α_i in m².
double sabineT(double volume_m3, double absorption_area_m2, double air_m_per_m);
/// Sabine with the exact constant: T = (24 ln10 / c)·V/(A + 4mV). The validation cases use this one, with
/// the c the tracer uses, so that the comparison does not carry 0.161's rounding (0.1 % at 20 °C).
double sabineT(double volume_m3, double absorption_area_m2, double air_m_per_m, double c_m_s);

/// Eyring, the textbook form: T = 0.161·V/(−S ln(1 − ᾱ) + 4mV), ᾱ = Σ S_i α_i / S in [0, 1].
double eyringT(double volume_m3, double surface_m2, double mean_alpha, double air_m_per_m);
/// Eyring with the exact constant (24 ln10 / c) instead of 0.161: the one the validation uses.
double eyringT(double volume_m3, double surface_m2, double mean_alpha, double air_m_per_m, double c_m_s);

/// Fraction of the rays of an omnidirectional point source that hit a sphere of radius R whose centre is
/// at distance r > R: the solid angle of the sphere over 4π, (1 − √(1 − R²/r²))/2.
double sphereHitFraction(double radius_m, double distance_m);
/// Expected reading of a sphere that divides the energy of the rays that hit it by its cross-section πR²,
/// in the 1/r² convention: 4·sphereHitFraction(R, r)/R² = 1/r² + R²/(4r⁴) + O(R⁴/r⁶). No air.
double sphereCrossSectionReading(double radius_m, double distance_m);
/// Mean of 1/d² over the volume of the sphere (d: distance to the source), the expectation of a
/// track-length estimator (energy × chord length / volume): (3/(2R³))·[R − (r² − R²)/(2r)·ln((r+R)/(r−R))]
/// = 1/r² + R²/(5r⁴) + O(R⁴/r⁶). No air.
double sphereMeanInverseSquare(double radius_m, double distance_m);

/// Free-field energy of a 1 W omnidirectional source at distance r: e^{−m r}/r², arriving at r/c.
double freeFieldEnergy(double distance_m, double air_m_per_m);

/// Areas of the walls of a shoebox Lx × Ly × Lz in the order x−, x+, y−, y+, z− (floor), z+ (ceiling),
/// the order of room::Room::addBox and of image_lattice.h.
std::array<double, 6> shoeboxWallAreas(const std::array<double, 3>& dims_m);

/// ISO 3382-1 metrics of a pure exponential decay p² ∝ e^{−k t}, k = 6 ln10 / T, integrated from 0 to ∞
/// (ISO 3382-1 definitions): every decay-time estimate is T; C_te = 10 log10(e^{k te} − 1) dB; D50 = 1 − e^{−0.05 k};
/// Ts = 1/k. T = 1 s gives C80 = 3.0534 dB, C50 = −0.0206 dB, D50 = 0.49881, Ts = 0.07238 s.
struct ExponentialDecayMetrics {
  double t20_s, t30_s, edt_s;
  double c50_db, c80_db, d50, ts_s;
};
ExponentialDecayMetrics exponentialDecayMetrics(double t60_s);

}  // namespace diffray::reference
