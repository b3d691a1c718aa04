#pragma once
// The propagating part of the field behind openings in an opaque screen (2D), by direct quadrature of the
// angular-spectrum integral over propagating directions only:
//     U_p(X, z) = ∫_{−π/2}^{π/2} T(sinθ/λ)·e^{i(2π/λ)(X sinθ + z cosθ)}·(cosθ/λ) dθ,
//     T(u) = ∫_openings e^{−i2πux} dx   (unit plane wave at normal incidence, Kirchhoff boundary values).
// U_p + (the evanescent part) = the Rayleigh–Sommerfeld field of rayleigh_sommerfeld.h. Ray methods carry
// propagating energy only, so |U_p|² is what an exact straight-ray transport must reproduce; the gap to
// |U_RS|² is the evanescent near field (noticeable within about a wavelength of the screen).
// An ORACLE: it shares no code with the tracer (own spectrum, own quadrature). Pure; thread-safe.
#include <utility>
#include <vector>

namespace diffray::reference {

/// |U_p(X, z)|², relative to the incident plane wave. Throws core::InputError for z <= 0 or λ <= 0.
double propagatingIntensity2D(const std::vector<std::pair<double, double>>& openings_m, double X_m, double z_m,
                              double wavelength_m);

}  // namespace diffray::reference
