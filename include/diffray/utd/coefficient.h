#pragma once
// The Kouyoumjian–Pathak UTD wedge diffraction coefficient and its transition function (R. G. Kouyoumjian and P. H.
// Pathak, Proc. IEEE 62(11), 1974, eq. 25–29, with Luebbers' face reflection coefficients on the φ + φ′ terms, IEEE
// Trans. AP-32(1), 1984). Time factor e^{iωt}: an outgoing wave is e^{−ikr}. Angles in radians, k in rad/m, distances
// in metres.
//
// Wedge frame: the air (exterior) sector spans φ ∈ [0, nπ], face 0 at φ = 0, face n at φ = nπ; n = 2 is a
// half-plane, n = 1.5 a right-angled (90°) wedge. φ′ is the direction the incident ray comes from, φ the
// one it leaves towards, both measured from face 0 about the edge tangent; β0 is the angle between the
// incident ray and the edge (Keller's cone). Pure functions; thread-safe.
#include <complex>

namespace diffray::utd {

/// The UTD transition function F(X) = 2i√X e^{iX} ∫_{√X}^∞ e^{−iτ²} dτ for X ≥ 0, exact (via Faddeeva's
/// w(z) = e^{−z²} erfc(−iz) from libcerf: F(X) = √(πX) e^{iπ/4} w(e^{3iπ/4}√X), no overflow for any X).
/// F(0) = 0; F → 1 for X → ∞. Throws core::InputError for negative or non-finite X.
std::complex<double> transitionF(double x);

/// One of the four cot·F terms of D, written in terms of ε, the angular distance from its shadow or
/// reflection boundary (ε = π ± β − 2πnN^±): cot(ε/(2n))·F(2kL·sin²(ε/2)). Finite through ε = 0, where
/// the product is evaluated as it is for |ε| > kBoundaryTolRad; within it (the boundary itself, within the
/// rounding of the angles) the mean of the one-sided limits n[±√(2πkL) − 2kLε e^{iπ/4}]e^{iπ/4}, which
/// pairs with a geometric-optics field weighted ½ on the boundary (UtdModel::paths, the same tolerance).
/// kl = k·L.
std::complex<double> cotTransition(double n, double kl, double eps);

/// How close (rad) to a shadow or reflection boundary counts as on it: the diffracted terms take their mean
/// there and the geometric field is halved (paths.cpp). One tolerance for both, or the total field jumps by
/// half the geometric one between them.
inline constexpr double kBoundaryTolRad = 1e-9;

/// Face reflection coefficients of the wedge: +1 rigid (acoustically hard, Neumann), −1 soft (Dirichlet).
struct FaceReflection {
  double face0 = 1.0;  ///< R0: multiplies the term with the reflection boundary of face 0
  double facen = 1.0;  ///< Rn: multiplies the term with the reflection boundary of face n
};

/// Kouyoumjian–Pathak D(n, k, L, φ, φ′, β0) with face reflection coefficients (Luebbers 1984):
///   D = −e^{−iπ/4}/(2n√(2πk) sin β0) · [cot((π + β⁻)/2n) F(kL a⁺(β⁻)) + cot((π − β⁻)/2n) F(kL a⁻(β⁻))
///        + R0 cot((π − β⁺)/2n) F(kL a⁻(β⁺)) + Rn cot((π + β⁺)/2n) F(kL a⁺(β⁺))],  β^∓ = φ ∓ φ′,
/// a^±(β) = 2cos²((2nπN^± − β)/2), N^± the integer nearest to solving 2πnN^± − β = ±π. Units: D in √m.
/// Requires n ≥ 1, k > 0, L > 0, 0 < β0 < π (throws core::InputError otherwise).
/// `truncation` T: a finite edge's factor (paths.h); `apex_on_edge`: whether the apex lies on the edge (else
/// on its line beyond an end, for the wave of the edge's corner). Each term is weighted (on ? 1 − |F(X)| : 0)
/// + |F(X)|·T with its own X: near its boundary (X → 0) the term's integrand along the edge is concentrated
/// at the apex, so it counts in full where the apex is on the edge (it makes up the geometric field's jump
/// there) and not at all beyond an end; far from it (|F| → 1) its amplitude is smooth along the edge and it
/// takes T. T = 1 on the edge is the plain coefficient.
std::complex<double> wedgeCoefficient(double n, double k, double l_m, double phi, double phi_inc, double beta0,
                                      FaceReflection r = {}, std::complex<double> truncation = 1.0,
                                      bool apex_on_edge = true);

}  // namespace diffray::utd
