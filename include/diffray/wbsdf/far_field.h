#pragma once
// The far-field (Fraunhofer) pattern of a rectangular opening along one axis, as a sampler triad.
//
// An opening of width A (t = 1 on it, 0 elsewhere) has T(u) = A·sinc(Au), so its Wigner distribution
// integrated over the opening is ∫W(x,u) dx = |T(u)|² = A²·sinc²(Au) (the Wigner distribution's second marginal).
// Divided by the opening's width (∫|t|² = A) it is a probability density of the shift u: in w = A·u it is
// sinc²(w) dw, one kernel for every width and wavelength, with ∫sinc² = 1 over the whole line.
//
// diffray uses it as the direction law of a ray that leaves an opening after its first flight (the portal
// continuation of transport/room_occluders.h): the product of W's two marginals, |t(x)|²·|T(u)|²/∫|t|²,
// has W's marginals exactly but is positive everywhere, so the rays it draws carry no sign.
//
// Proposal on [w_lo, w_hi] (w_lo < w_hi): the envelope g(w) = min(1, 1/(πw)²) ≥ sinc²(w), uniform for
// |w| ≤ 1/π and 1/(πw)² beyond, with its inverse CDF in closed form. The weight sinc²(w)/pdf(w) lies in
// [0, ∫g] and its mean is ∫_{w_lo}^{w_hi} sinc² (the part of the pattern inside the range). Pure functions;
// thread-safe.
namespace diffray::wbsdf {

struct FarFieldSample {
  double w = 0.0;       ///< sampled w (the shift is u' = w/A cycles per metre)
  double weight = 0.0;  ///< sinc²(w)/pdf(w) ≥ 0; 0 when the range is empty
};

/// sinc²(w): the pattern's density in w (∫ over the line = 1).
double farFieldEval(double w);
/// The proposal's density at w for the range [w_lo, w_hi]; 0 outside it.
double farFieldPdf(double w, double w_lo, double w_hi);
/// Samples w in [w_lo, w_hi] from one uniform in [0, 1).
FarFieldSample farFieldSample(double w_lo, double w_hi, double xi);
/// ∫ sinc² over [w_lo, w_hi] (either end may be infinite): the part of the pattern inside the range, from the
/// antiderivative Si(2πw)/π − sin²(πw)/(π²w) (Si the sine integral; absolute error below 1e-8).
double farFieldMass(double w_lo, double w_hi);

}  // namespace diffray::wbsdf
