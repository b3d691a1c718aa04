// Closed-form room-acoustics references (Kuttruff, "Room Acoustics"; ISO 3382-1). Self-contained: no code shared with
// the tracer.
#include "diffray/reference/room_acoustics.h"

#include <cmath>
#include <sstream>
#include <string>

#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

constexpr double kClassicConstant = 0.161;  // the textbook Sabine/Eyring constant (24 ln10 / c at c ≈ 343 m/s), s/m
constexpr double kPi = 3.14159265358979323846;

void requireNonNegative(const std::string& where, double value) {
  core::requireFinite(where, value);
  if (value < 0.0) throw core::InputError(where, "must be >= 0, got " + std::to_string(value));
}

// T = constant·V/(absorption + 4mV); infinite (no loss at all) is an input error, not a number to compare.
double reverberationTime(const char* where, double constant, double volume_m3, double absorption_m2,
                         double air_m_per_m) {
  const double loss = absorption_m2 + 4.0 * air_m_per_m * volume_m3;
  if (!(loss > 0.0)) throw core::InputError(where, "no absorption and no air absorption: the decay never ends");
  return constant * volume_m3 / loss;
}

// −S ln(1 − ᾱ): Eyring's equivalent absorption area (infinite at ᾱ = 1, where T = 0).
double eyringArea(double surface_m2, double mean_alpha) {
  core::requirePositive("eyringT: surface_m2", surface_m2);
  core::requireFinite("eyringT: mean_alpha", mean_alpha);
  if (mean_alpha < 0.0 || mean_alpha > 1.0)
    throw core::InputError("eyringT: mean_alpha", "must be within 0 … 1, got " + std::to_string(mean_alpha));
  return -surface_m2 * std::log1p(-mean_alpha);
}

void requireSphere(const char* where, double radius_m, double distance_m) {
  core::requirePositive(std::string(where) + ": radius_m", radius_m);
  core::requirePositive(std::string(where) + ": distance_m", distance_m);
  if (!(distance_m > radius_m)) {
    std::ostringstream s;
    s << "the source must lie outside the sphere: distance " << distance_m << " m <= radius " << radius_m << " m";
    throw core::InputError(where, s.str());
  }
}

}  // namespace

double sabineT(double volume_m3, double absorption_area_m2, double air_m_per_m) {
  core::requirePositive("sabineT: volume_m3", volume_m3);
  requireNonNegative("sabineT: absorption_area_m2", absorption_area_m2);
  requireNonNegative("sabineT: air_m_per_m", air_m_per_m);
  return reverberationTime("sabineT", kClassicConstant, volume_m3, absorption_area_m2, air_m_per_m);
}

double sabineT(double volume_m3, double absorption_area_m2, double air_m_per_m, double c_m_s) {
  core::requirePositive("sabineT: c_m_s", c_m_s);
  return sabineT(volume_m3, absorption_area_m2, air_m_per_m) * (kSixtyDbConstant / c_m_s) / kClassicConstant;
}

double eyringT(double volume_m3, double surface_m2, double mean_alpha, double air_m_per_m) {
  core::requirePositive("eyringT: volume_m3", volume_m3);
  requireNonNegative("eyringT: air_m_per_m", air_m_per_m);
  const double area = eyringArea(surface_m2, mean_alpha);
  if (std::isinf(area)) return 0.0;  // ᾱ = 1: nothing comes back
  return reverberationTime("eyringT", kClassicConstant, volume_m3, area, air_m_per_m);
}

double eyringT(double volume_m3, double surface_m2, double mean_alpha, double air_m_per_m, double c_m_s) {
  core::requirePositive("eyringT: c_m_s", c_m_s);
  return eyringT(volume_m3, surface_m2, mean_alpha, air_m_per_m) * (kSixtyDbConstant / c_m_s) / kClassicConstant;
}

double sphereHitFraction(double radius_m, double distance_m) {
  requireSphere("sphereHitFraction", radius_m, distance_m);
  const double q = radius_m / distance_m;
  // 1 − √(1 − q²) = q²/(1 + √(1 − q²)): no cancellation for small spheres far away.
  return 0.5 * q * q / (1.0 + std::sqrt(1.0 - q * q));
}

double sphereCrossSectionReading(double radius_m, double distance_m) {
  return 4.0 * sphereHitFraction(radius_m, distance_m) / (radius_m * radius_m);
}

double sphereMeanInverseSquare(double radius_m, double distance_m) {
  requireSphere("sphereMeanInverseSquare", radius_m, distance_m);
  const double r = distance_m, R = radius_m, q = R / r;
  if (q < 0.5) {
    // The closed form cancels badly for small q; its expansion is (3/R²)·Σ_{j≥1} q^{2j}/(4j² − 1),
    // and 40 terms of 0.25^j leave nothing beyond double precision.
    double sum = 0.0, q2j = 1.0;
    for (int j = 1; j <= 40; ++j) {
      q2j *= q * q;
      sum += q2j / (4.0 * j * j - 1.0);
    }
    return 3.0 * sum / (R * R);
  }
  // ∫_ball d⁻² dV = 2π[R − (r² − R²)/(2r)·ln((r+R)/(r−R))] (spherical shells about the source).
  const double integral = 2.0 * kPi * (R - (r * r - R * R) / (2.0 * r) * std::log((r + R) / (r - R)));
  return integral / (4.0 / 3.0 * kPi * R * R * R);
}

double freeFieldEnergy(double distance_m, double air_m_per_m) {
  core::requirePositive("freeFieldEnergy: distance_m", distance_m);
  requireNonNegative("freeFieldEnergy: air_m_per_m", air_m_per_m);
  return std::exp(-air_m_per_m * distance_m) / (distance_m * distance_m);
}

std::array<double, 6> shoeboxWallAreas(const std::array<double, 3>& dims_m) {
  for (int a = 0; a < 3; ++a) core::requirePositive("shoeboxWallAreas: dimension " + std::to_string(a), dims_m[a]);
  const double yz = dims_m[1] * dims_m[2], xz = dims_m[0] * dims_m[2], xy = dims_m[0] * dims_m[1];
  return {yz, yz, xz, xz, xy, xy};
}

ExponentialDecayMetrics exponentialDecayMetrics(double t60_s) {
  core::requirePositive("exponentialDecayMetrics: t60_s", t60_s);
  const double k = 6.0 * std::log(10.0) / t60_s;  // p² ∝ e^{−kt} falls 60 dB in T
  // Clarity: E(0)/E(te) − 1 = e^{k te} − 1; expm1 keeps precision for short T·te.
  const auto clarity = [k](double te_s) { return 10.0 * std::log10(std::expm1(k * te_s)); };
  ExponentialDecayMetrics m{};
  m.t20_s = m.t30_s = m.edt_s = t60_s;
  m.c50_db = clarity(0.050);
  m.c80_db = clarity(0.080);
  m.d50 = -std::expm1(-k * 0.050);
  m.ts_s = 1.0 / k;
  return m;
}

}  // namespace diffray::reference
