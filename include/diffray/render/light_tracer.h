#pragma once
// The spectral light tracer (paper section "Implementation": photon mapping with signed photons —
// here light tracing, every photon splatted to the camera where it lands on a diffuse surface).
//
// Paths. A photon picks a light with probability ∝ power, a wavelength (laser: its line; white: λ from
// color::sampleWavelength, weight S(λ)/p(λ) with S = 1/400 nm⁻¹), and a start: a point light emits
// isotropically (or toward its `aim` rectangle, sampled by area: weight A·cosθ_y/(4π r²)); a laser from a
// uniform point of its beam's cross-section; an area light (Lambertian, radiance L = P/(πA) on its emitting
// face) from a uniform point x of its rectangle (pdf 1/A) in a cosine-distributed direction about that face
// (pdf cosθ_x/π): L·cosθ_x·dA·dω/(pdf_A·pdf_ω) = P, so the photon's energy is unchanged. With `aim`, the
// direction goes to a point y drawn uniformly on the target rectangle (area A_t): the solid-angle pdf is
// r²/(A_t|cosθ_y|), so the weight is L·cosθ_x·A·A_t|cosθ_y|/r² = P·max(cosθ_x, 0)·A_t|cosθ_y|/(π r²); two-sided
// (P/2 from each face, L = P/(2πA)): (P/2)·|cosθ_x|·A_t|cosθ_y|/(π r²), and without `aim` a face drawn with
// probability 1/2. At an occluder it scatters with the importance-sampled WBSDF
// (transport::scatterAtOccluder, paper eq. 8–10): the signed weight sign(W)·Σ|W| multiplies its energy.
// At a diffuse rectangle it is scored (below), then continues (up to diffuse_bounces times) with
// probability ρ(λ) in a cosine-distributed direction, or ends.
//
// Measurement (next-event estimation to the pinhole). A pixel's value is the mean radiance over its solid
// angle Ω_pix: P = (1/Ω_pix) ∫_pix L dω. A Lambertian surface of albedo ρ under irradiance E has radiance
// L = ρE/π, and the surface element dA at distance r whose normal makes angle θ_s with the direction to the
// pinhole subtends dω = cosθ_s dA / r². So P = (1/Ω_pix) ∫_footprint (ρ/π) E cosθ_s / r² dA, and since the
// photons' energies Φ_k estimate ∫E dA, each photon landing at x_k (visible from the pinhole, on the face
// the camera sees, projecting into the pixel) adds
//      ΔP = Φ_k · ρ(λ_k)/π · cosθ_s / r² / Ω_pix          [W m⁻² sr⁻¹ when power is in W]
// to it — the G-term cosθ_s/r² of the connection, the pinhole side's cosine folded into the exact Ω_pix
// (render/camera.h). A pixel is a finite aperture (its footprint on the wall), so the photons' positive and
// negative energies integrate out within it (paper section 2.4). XYZ adds ΔP·(x̄, ȳ, z̄)(λ_k) (CIE 1931,
// color::cie1931); the spectrally integrated radiance ΔP alone is kept too (the "radiance" channel: for a
// laser it is Y/ȳ(λ)). Occluders block the connection to the camera (the camera is meant to look at the
// diffuse surfaces directly).
//
// Determinism: photons are cut into chunks with their own random streams (core/parallel.h), so a seed gives
// identical images for any thread count. Thread-safe (a PreparedScene is read-only).
#include <cstdint>
#include <functional>
#include <vector>

#include "diffray/receiver/screen.h"
#include "diffray/render/light_setup.h"

namespace diffray::render {

struct RenderOptions {
  std::uint64_t photons = 1'000'000;
  std::uint64_t seed = 1;
  std::uint64_t chunk_photons = 65536;
  /// Draw WBSDF shifts uniformly over each table's range (weight W/p_uniform) instead of importance-sampled
  /// by |W| (the default, paper "Implementation"): unbiased, for the render-is bench. A photon drawing a
  /// zero-mass cell ends with weight 0 and is booked as absorbed on the occluder.
  bool uniform_shifts = false;
  std::function<void(std::uint64_t)> on_progress;  ///< photons done per chunk (thread-safe)
};

/// Pixel sums and the energy balance. Pixels are row-major, top row first.
struct RenderResult {
  int width = 0, height = 0;
  std::vector<double> xyz;          ///< 3 per pixel: CIE XYZ of the mean radiance
  receiver::ScreenTally radiance;   ///< spectrally integrated mean radiance per pixel, with chunk scatter
  double emitted = 0;               ///< total power of the lights (W), Σ of photon energies at emission
  double on_diffuse = 0;            ///< signed energy arriving at diffuse rectangles (all bounces)
  double absorbed_occluders = 0;   ///< stopped on the opaque parts of occluders (t = 0 there), and what a grating does not reflect
  double absorbed_diffuse = 0;     ///< ended at diffuse rectangles (not reflected on)
  double evanescent = 0, escaped = 0, bounce_limit = 0;
  double scored_positive = 0, scored_negative = 0;  ///< Σ ΔP > 0 and Σ |ΔP| < 0 over every camera score
  std::uint64_t photons = 0, camera_scores = 0;
  void merge(const RenderResult& o);
  /// Spectrally integrated radiance of pixel (ix, iy) and its standard error.
  double pixelRadiance(int ix, int iy) const { return radiance.sum[static_cast<std::size_t>(iy) * width + ix]; }
  double pixelStdError(int ix, int iy) const { return radiance.standardError(iy * width + ix); }
  /// Σ|negative pixel radiance| / Σ|pixel radiance|: what stays negative after the pixels' integration.
  double negativePixelFraction() const { return radiance.negativeFraction(); }
  /// Σ|ΔP < 0| / Σ|ΔP|: how signed the photons reaching the camera were.
  double negativeScoreFraction() const;
};

/// Traces options.photons photons; first refuses (checkRenderMemory, with core::ThreadLimit::current() threads
/// and core::physicalMemoryBytes()) a camera whose accumulators would not fit in memory.
RenderResult renderLight(const PreparedScene& scene, const RenderOptions& options);

/// `spp` photons per pixel on a width × height camera: spp × width × height, computed in double and refused
/// (core::InputError naming --spp) above 1e13 photons, the cap on --photons (cli::kMaxCount).
std::uint64_t sppPhotons(std::uint64_t spp, int width, int height);

/// Bytes per pixel of one chunk accumulator while it is merged: xyz (3 doubles), the radiance tally's sum
/// and sum_sq (the open chunk's scratch, 1 double, exists only while a chunk is traced).
inline constexpr double kAccumulatorBytesPerPixel = 5 * sizeof(double);
/// Estimated peak bytes of renderLight's accumulators for a width × height camera on `threads` threads:
/// pixels × (kAccumulatorBytesPerPixel × (threads + 1) + 8 × threads) — the total, one accumulator per
/// thread and each tracing thread's chunk scratch (core::orderedReduce).
double renderPeakBytes(int width, int height, int threads);
/// Throws core::InputError("camera.pixels", …) naming the size, the estimate and the remedy (fewer pixels or
/// --threads) when renderPeakBytes exceeds half of `physical_bytes` (0: unknown, never refused).
void checkRenderMemory(int width, int height, int threads, double physical_bytes);

}  // namespace diffray::render
