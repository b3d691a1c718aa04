#pragma once
// Analytic importance sampling of the Wigner distribution of an opening near its edges, for any
// wavelength, without a table.
//
// A slit of width a has W(x,u) = 2(a − 2|x|)·sinc(2u(a − 2|x|)) (Cuypers et al. 2012, eq. 2, for a rect), i.e. W =
// 4d·sinc(4du) with d = a/2 − |x| the distance to the nearer edge; the step (half-plane edge) has W = sin(4πux)/(πu),
// the same 4d·sinc(4du) with d = x. In the variable w = 4d·u the measure W(x,u) du = sinc(w) dw no longer depends on
// d: one kernel serves every hit position, every edge distance and every wavelength. sinc(z) = sin(πz)/(πz).
// ∫|sinc| diverges (logarithmically), so the kernel is cut at |w| ≤ w_max; diffray takes w_max = 4d·u_max with
// u_max = 2/λ, past which every shift is evanescent for any incidence (|λu_o| ≤ 1 for a propagating wave): nothing that
// propagates is cut.
//
// The tracer narrows the range further to [w_lo, w_hi], the shifts that leave a propagating ray for the
// ray's own incidence (|α + λu'| < √(1 − β²)), so that few samples end as evanescent waves.
//
// Proposal on [w_lo, w_hi] (w_lo < 0 < w_hi): a mixture of the main segment (|w| < 1, uniform) and, on each
// side, the period n = ⌊r⌋ with r log-uniform on [1, M) (M = ⌈|w_lo|⌉ or ⌈w_hi⌉) and the offset t in the
// period from (π/2)·sin(πt), the shape of |sinc| there; the parts weighted by their approximate masses.
// The weight eval/pdf = sinc(w)/pdf(w) is bounded and nearly constant in magnitude, and carries the sign
// (paper section 4, importance sampling of |W|). E[weight] = ∫ sinc over the proposal's support, which
// holds [w_lo, w_hi] (→ 1 = |t(x)|², the first marginal of W, as the range grows). Pure functions;
// thread-safe.
namespace diffray::wbsdf {

struct EdgeKernelSample {
  double w = 0.0;       ///< sampled w (the shift is u' = w/(4d) cycles per metre)
  double weight = 0.0;  ///< sinc(w)/pdf(w), signed
};

/// sinc(w) = sin(πw)/(πw): the kernel's density in w (W(x,u) du = sinc(w) dw).
double edgeKernelEval(double w);
/// The proposal's density at w for the range [w_lo, w_hi] (w_lo ≤ 0 ≤ w_hi); its support is the main
/// segment and the side lobes up to ⌈|w_lo|⌉ and ⌈w_hi⌉ (whole periods).
double edgeKernelPdf(double w, double w_lo, double w_hi);
/// Samples w in the range from two uniforms in [0, 1).
EdgeKernelSample edgeKernelSample(double w_lo, double w_hi, double xi1, double xi2);

}  // namespace diffray::wbsdf
