#pragma once
// The FDTD update of the wave reference (fdtd.h): the standard rectilinear (SRL) 7-point leapfrog for the
// pressure on an FdtdGrid, locally reacting frequency-independent walls, and the formulas that go with it.
//
// Scheme (Kowalczyk & van Walstijn 2011, IEEE TASLP 19(1), the SRL member of their compact schemes; Bilbao
// 2013, IEEE TASLP 21(7), eq. for the finite-volume boundary node). Courant number λ = c·dt/h ≤ 1/√3.
//   air node with its 6 links open:  p⁺ = 2p − p⁻ + λ²·Σ₆(p_nbr − p)
//   node with K < 6 open links:      p⁺ = [2p + λ²·Σ_K(p_nbr − p) − (1 − g)p⁻] / (1 + g),  g = (λ/2)·Σ_blocked β_j
// The second is the finite-volume balance of a full cubic cell h³: (h³/c²)·δtt p = h·Σ_K (p_nbr − p) −
// h²·Σ_blocked (β_j/c)·δt· p, with the locally reacting wall ∂p/∂n = −(β/c)·∂p/∂t on each blocked face and
// β_j = ρc/Z_j the normalised admittance of the material that blocks link j (centred differences). β = 0
// gives the rigid K-neighbour update; a node whose blocked links average β̄ has g = λβ̄(6 − K)/2, the form
// of Kowalczyk & van Walstijn. The links that leave the domain have β = 1: the first-order absorbing
// boundary ∂p/∂n = −(1/c)∂p/∂t, exact for plane waves at normal incidence; at incidence θ it reflects
// (cosθ − 1)/(cosθ + 1) of the pressure (−15 dB at 45°, total at grazing), so a scene open to free field
// gets weak late returns from the domain's faces.
// Conserved energy (Bilbao, Numerical Sound Synthesis 2009, §10; summation by parts of the scheme times
// p⁺ − p⁻), up to the constant factor h³/(2ρc²dt²):
//   H^{n+½} = Σ_air (p_i^{n+1} − p_i^n)² + λ²·Σ_open links (Δp^{n+1})(Δp^n),   Δp = p_a − p_b over a link,
//   H^{n+½} − H^{n−½} = −Σ_i g_i·(p_i^{n+1} − p_i^{n−1})² ≤ 0,
// non-negative for λ² ≤ 1/3 (stability): constant with rigid walls, non-increasing with absorbing ones.
// Numerical dispersion (plane wave e^{i(ωt − kx)} along an axis, the worst direction):
// sin(ω·dt/2) = λ·sin(k·h/2).
// Precision: the fields are float (4 bytes; half the memory traffic of double), energies summed in double.
// Both updates are evaluated in the difference form above, so that a uniform field is an exact solution
// with rigid walls (the uniform mode's double root z = 1 stays on the unit circle: with separately rounded
// coefficients it grows exponentially over a long run), and λ² is rounded down to float, so that the
// highest grid mode stays inside the stability limit at λ = 1/√3.
// Denormals are flushed to zero inside the update (the stencil's precursor ahead of a wavefront would
// otherwise slow the float arithmetic a hundredfold).
// Thread-safety: step() runs on all TBB threads (core/parallel.h's ThreadLimit applies); one scheme
// object is not to be used from two threads at once.
#include <cstdint>
#include <vector>

#include "diffray/reference/fdtd_grid.h"

namespace diffray::reference {

/// The largest stable Courant number of the SRL scheme, 1/√3.
inline constexpr double kSrlCourantLimit = 0.57735026918962576;

/// Random-incidence (Paris) absorption of a locally reacting wall with real normalised impedance ξ = Z/ρc
/// (Kuttruff, Room Acoustics, eq. 2.53 for real wall impedance):
/// α_st(ξ) = (8/ξ)·[1 + 1/(1 + ξ) − (2/ξ)·ln(1 + ξ)]; its maximum is 0.9512 at ξ = 1.567.
double parisAbsorption(double xi);
/// The largest α_st of a real impedance (0.9512…).
double maxParisAbsorption();
/// The normalised admittance β = 1/ξ whose α_st(ξ) equals α, on the branch ξ ≥ 1.567 (stiff walls: β ≈ α/8
/// for small α); α ≤ 0 gives 0, α above maxParisAbsorption() is clamped to it (`*clamped` set).
double admittanceForAbsorption(double alpha, bool* clamped = nullptr);

/// Axial phase velocity over c of the SRL scheme at frequency f: ω/(c·k) with sin(ω·dt/2) = λ·sin(k·h/2),
/// λ = c·dt/h. Below 1 (waves lag); NaN above the axial cutoff f = asin(λ)/(π·dt).
double srlAxialPhaseVelocityRatio(double f_hz, double h_m, double dt_s, double c_m_s);

/// The band-limited source: a Ricker wavelet (second derivative of a Gaussian) peaking in spectrum at
/// peak_hz, s(t) = (1 − 2π²f²τ²)·e^{−π²f²τ²}, τ = t − delay, delay = 1.6/peak_hz (|s(0)| < 1e-9). Its
/// amplitude spectrum ∝ (f/f_p)²·e^{−(f/f_p)²} is within 2.7 dB of its peak over the octave around f_p,
/// has a double zero at 0 Hz (no net injected mass: no static pressure builds up in a closed room) and is
/// below −160 dB at 4.8·f_p, the SRL's axial cutoff at 10 points per wavelength at the octave's top.
struct RickerPulse {
  double peak_hz = 500.0;
  double delay() const { return 1.6 / peak_hz; }
  double duration() const { return 3.2 / peak_hz; }  ///< |s| < 1e-9 outside [0, duration]
  double operator()(double t_s) const;
};

/// Free-field response of the injection p^{n+1} += s^n at one node: the scheme approximates
/// p_tt = c²∇²p + (s/dt²)·h³·δ(x − x0), whose solution is p(r, t) = h³·s(t − r/c)/(4π·c²·dt²·r). This is
/// the factor h³/(4π·c²·dt²) (m) that multiplies s(t − r/c)/r.
double freeFieldFactor(double h_m, double dt_s, double c_m_s);

/// One node of the boundary list: its open links, and its update coefficients in the current band.
struct FdtdBoundaryNode {
  std::uint32_t node = 0;
  std::uint8_t open = 0;  ///< bit d: link d open (its neighbour is air)
  float a = 0, b = 0, c = 0;  ///< p⁺ = a·p + b·Σ_open (p_nbr − p) − c·p⁻
};

class FdtdScheme {
 public:
  /// A scheme on `grid` (flood-filled) with Courant number `courant` (≤ kSrlCourantLimit) and the admittance
  /// β of each material (index: room material; the domain's edge gets 1). Fields start at zero.
  FdtdScheme(const FdtdGrid& grid, double courant, const std::vector<double>& beta_of_material);
  /// Advances one step: p^{n−1}, p^n → p^n, p^{n+1}.
  void step();
  /// Adds s to the newest field at `node` (call after step(): p^{n+1} += s^n).
  void inject(std::size_t node, float s) { cur_[node] += s; }
  const float* current() const { return cur_; }    ///< p^{n+1} after step()
  const float* previous() const { return prev_; }  ///< p^n after step()
  double courant() const { return lambda_; }
  /// λ² as the update uses it: float, rounded down.
  float coupling() const { return coupling_; }
  const std::vector<FdtdBoundaryNode>& boundary() const { return boundary_; }
  /// Bytes per node the scheme allocates (two float fields), for memory estimates.
  static constexpr double kBytesPerNode = 8.0;

 private:
  const FdtdGrid& grid_;
  double lambda_;
  float coupling_ = 0.0f;
  std::vector<float> field_a_, field_b_;
  float* prev_;
  float* cur_;
  std::vector<FdtdBoundaryNode> boundary_;
};

}  // namespace diffray::reference
